#include "host/runtime/Device.hpp"

#include <catch2/catch.hpp>

#include "tests/support/ScopedEnv.hpp"

#include <algorithm>
#include <cctype>
#include <cstdlib>
#include <optional>
#include <string>
#include <vector>

#include "host/runtime/ClError.hpp"

using fw::host::DeviceInfo;

namespace {

using fw::test::ScopedEnv;

// Every device, or an empty list when there is none and the test runs outside CI (it then warns).
// Under CI (the environment variable CI is set) a missing device fails the test.
std::vector<DeviceInfo> devices_or_skip() {
  try {
    return fw::host::list_devices();
  } catch (const fw::host::NoDeviceError& e) {
    if (std::getenv("CI") != nullptr) FAIL("no OpenCL device under CI: " << e.what());
    WARN("no OpenCL device, device test not run: " << e.what());
  }
  return {};
}

std::string upper(std::string s) {
  std::transform(s.begin(), s.end(), s.begin(), [](unsigned char c) { return char(std::toupper(c)); });
  return s;
}

std::string lower(std::string s) {
  std::transform(s.begin(), s.end(), s.begin(), [](unsigned char c) { return char(std::tolower(c)); });
  return s;
}

bool same_device(const DeviceInfo& a, const DeviceInfo& b) {
  return a.platform_index == b.platform_index && a.device_index == b.device_index;
}

// The first device whose platform or device name contains `needle`, compared case-insensitively.
const DeviceInfo* first_match(const std::vector<DeviceInfo>& devices, const std::string& needle) {
  for (const auto& d : devices)
    if (lower(d.platform_name).find(lower(needle)) != std::string::npos ||
        lower(d.device_name).find(lower(needle)) != std::string::npos)
      return &d;
  return nullptr;
}

}  // namespace

TEST_CASE("Device: list_devices finds at least one device with its properties filled in") {
  const auto devices = devices_or_skip();
  if (devices.empty()) return;
  for (std::size_t n = 0; n < devices.size(); ++n) {
    const DeviceInfo& d = devices[n];
    INFO("device " << n << ": " << d.platform_name << " / " << d.device_name);
    CHECK_FALSE(d.platform_name.empty());
    CHECK_FALSE(d.device_name.empty());
    CHECK_THAT(d.platform_version, Catch::StartsWith("OpenCL "));
    CHECK_THAT(d.device_version, Catch::StartsWith("OpenCL "));
    CHECK((d.type == "GPU" || d.type == "CPU" || d.type == "accelerator" || d.type == "other"));
    CHECK(d.compute_units > 0);
    CHECK(d.global_memory_bytes > 0);
    CHECK(d.max_allocation_bytes > 0);
    CHECK(d.max_allocation_bytes <= d.global_memory_bytes);
    CHECK(d.device() != nullptr);
    // Indices count devices within each platform, in order.
    if (n > 0) {
      const DeviceInfo& prev = devices[n - 1];
      if (d.platform_index == prev.platform_index)
        CHECK(d.device_index == prev.device_index + 1);
      else
        CHECK((d.platform_index > prev.platform_index && d.device_index == 0));
    }
  }
  CHECK(devices.front().device_index == 0);
}

TEST_CASE("Device: an empty filter prefers the first GPU, else the first CPU, else the first device") {
  const auto devices = devices_or_skip();
  if (devices.empty()) return;
  const DeviceInfo* expected = nullptr;
  for (const char* type : {"GPU", "CPU"}) {
    for (const auto& d : devices)
      if (!expected && d.type == type) expected = &d;
  }
  if (!expected) expected = &devices.front();
  const DeviceInfo chosen = fw::host::select_device("");
  INFO("chosen " << chosen.platform_name << " / " << chosen.device_name << " [" << chosen.type << "]");
  CHECK(same_device(chosen, *expected));
  const bool any_gpu = std::any_of(devices.begin(), devices.end(), [](auto& d) { return d.type == "GPU"; });
  if (any_gpu) CHECK(chosen.type == "GPU");
}

TEST_CASE("Device: a filter is a case-insensitive substring of the platform or device name") {
  const auto devices = devices_or_skip();
  if (devices.empty()) return;
  const DeviceInfo& first = devices.front();
  REQUIRE(first.device_name.size() >= 1);
  // A piece from the middle of the first device's name, in upper and in lower case.
  const std::size_t start = first.device_name.size() / 3;
  const std::string piece =
      first.device_name.substr(start, std::min<std::size_t>(8, first.device_name.size()));
  for (const std::string& filter : {upper(piece), lower(piece), first.device_name}) {
    INFO("filter '" << filter << "'");
    const DeviceInfo* expected = first_match(devices, filter);
    REQUIRE(expected != nullptr);
    CHECK(same_device(*expected, first));  // the first device matches, so nothing earlier can
    CHECK(same_device(fw::host::select_device(filter), *expected));
  }
  // The platform name of the last device matches too.
  const std::string platform = upper(devices.back().platform_name);
  const DeviceInfo* expected = first_match(devices, platform);
  REQUIRE(expected != nullptr);
  const DeviceInfo chosen = fw::host::select_device(platform);
  CHECK(same_device(chosen, *expected));
  CHECK(lower(chosen.platform_name).find(lower(platform)) != std::string::npos);
}

TEST_CASE("Device: a filter that matches nothing throws NoDeviceError listing the devices") {
  const auto devices = devices_or_skip();
  if (devices.empty()) return;
  const std::string filter = "no-such-device-7f3a";
  try {
    fw::host::select_device(filter);
    FAIL("select_device('" << filter << "') returned a device");
  } catch (const fw::host::NoDeviceError& e) {
    const std::string what = e.what();
    INFO(what);
    CHECK_THAT(what, Catch::Contains(filter));
    for (const auto& d : devices) {
      CHECK_THAT(what, Catch::Contains(d.device_name));
      CHECK_THAT(what, Catch::Contains(d.platform_name));
    }
  }
}

TEST_CASE("Device: device_filter_from_env prefers the command line, then FORESTWIND_DEVICE") {
  SECTION("variable set") {
    const ScopedEnv env("FORESTWIND_DEVICE", std::string("from-env"));
    CHECK(fw::host::device_filter_from_env("from-cli") == "from-cli");
    CHECK(fw::host::device_filter_from_env("") == "from-env");
  }
  SECTION("variable unset") {
    const ScopedEnv env("FORESTWIND_DEVICE", std::nullopt);
    CHECK(fw::host::device_filter_from_env("from-cli") == "from-cli");
    CHECK(fw::host::device_filter_from_env("") == "");
  }
}

TEST_CASE("Device: the no-platform message names the Debian package that provides one") {
  CHECK_THAT(fw::host::no_platform_message(), Catch::Contains("pocl-opencl-icd"));
}
