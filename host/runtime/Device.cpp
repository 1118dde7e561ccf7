#include "host/runtime/Device.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <cctype>
#include <cstdlib>
#include <thread>

#include "base/TextNumber.hpp"
#include "host/runtime/ClError.hpp"

namespace fw::host {
namespace {

std::string lower(std::string s) {
  std::transform(s.begin(), s.end(), s.begin(), [](unsigned char c) { return std::tolower(c); });
  return s;
}

std::string type_name(cl_device_type type) {
  if (type & CL_DEVICE_TYPE_GPU) return "GPU";
  if (type & CL_DEVICE_TYPE_CPU) return "CPU";
  if (type & CL_DEVICE_TYPE_ACCELERATOR) return "accelerator";
  return "other";
}

std::vector<cl::Platform> platforms_or_empty() {
  std::vector<cl::Platform> platforms;
  try {
    cl::Platform::get(&platforms);
  } catch (const cl::Error&) {
    // The ICD loader reports CL_PLATFORM_NOT_FOUND_KHR when no driver is installed.
    platforms.clear();
  }
  return platforms;
}

}  // namespace

std::string no_platform_message() {
  return "no OpenCL platform found: install an OpenCL driver, e.g. `apt-get install pocl-opencl-icd` for "
         "the CPU (or run scripts/install-deps.sh as root)";
}

std::vector<DeviceInfo> list_devices() {
  auto platforms = platforms_or_empty();
  if (platforms.empty()) throw NoDeviceError(no_platform_message());
  std::vector<DeviceInfo> result;
  for (std::size_t p = 0; p < platforms.size(); ++p) {
    std::vector<cl::Device> devices;
    try {
      platforms[p].getDevices(CL_DEVICE_TYPE_ALL, &devices);
    } catch (const cl::Error&) {
      continue;  // a platform with no devices
    }
    for (std::size_t d = 0; d < devices.size(); ++d) {
      DeviceInfo info;
      info.platform_index = static_cast<int>(p);
      info.device_index = static_cast<int>(d);
      info.platform_name = platforms[p].getInfo<CL_PLATFORM_NAME>();
      info.platform_version = platforms[p].getInfo<CL_PLATFORM_VERSION>();
      info.device_name = devices[d].getInfo<CL_DEVICE_NAME>();
      info.device_version = devices[d].getInfo<CL_DEVICE_VERSION>();
      info.type = type_name(devices[d].getInfo<CL_DEVICE_TYPE>());
      info.compute_units = devices[d].getInfo<CL_DEVICE_MAX_COMPUTE_UNITS>();
      info.global_memory_bytes = devices[d].getInfo<CL_DEVICE_GLOBAL_MEM_SIZE>();
      info.max_allocation_bytes = devices[d].getInfo<CL_DEVICE_MAX_MEM_ALLOC_SIZE>();
      info.local_memory_bytes = devices[d].getInfo<CL_DEVICE_LOCAL_MEM_SIZE>();
      info.max_clock_mhz = devices[d].getInfo<CL_DEVICE_MAX_CLOCK_FREQUENCY>();
      info.device = devices[d];
      result.push_back(std::move(info));
    }
  }
  if (result.empty()) throw NoDeviceError("OpenCL platforms exist but none has a device");
  return result;
}

DeviceInfo select_device(const std::string& filter) {
  return select_device(filter, 0);
}

DeviceInfo select_device(const std::string& filter, int node_rank) {
  auto devices = list_devices();
  std::vector<DeviceInfo> candidates;
  if (!filter.empty()) {
    const std::string needle = lower(filter);
    for (const auto& d : devices) {
      if (lower(d.platform_name).find(needle) != std::string::npos ||
          lower(d.device_name).find(needle) != std::string::npos)
        candidates.push_back(d);
    }
    if (candidates.empty()) {
      std::string names;
      for (const auto& d : devices) names += fmt::format("\n  {} / {}", d.platform_name, d.device_name);
      throw NoDeviceError(
          fmt::format("no OpenCL device matches the filter '{}'; the devices are:{}", filter, names));
    }
  }
  for (const char* wanted : {"GPU", "CPU"}) {
    if (!candidates.empty()) break;
    for (const auto& d : devices)
      if (d.type == wanted) candidates.push_back(d);
  }
  if (candidates.empty()) candidates = devices;
  return candidates[std::size_t(std::max(node_rank, 0)) % candidates.size()];
}

int share_cpu_cores(int node_ranks) {
  constexpr const char* kVariable = "POCL_MAX_PTHREAD_COUNT";
  if (node_ranks <= 1) return 0;
  // A value that is no whole number gives PoCL's own default, one thread.
  if (const char* set = std::getenv(kVariable)) return std::max(1, base::parse_number<int>(set).value_or(1));
  const int share = std::max(1, int(std::thread::hardware_concurrency()) / node_ranks);
  ::setenv(kVariable, std::to_string(share).c_str(), 0);
  return share;
}

std::string device_filter_from_env(const std::string& command_line_filter) {
  if (!command_line_filter.empty()) return command_line_filter;
  const char* env = std::getenv("FORESTWIND_DEVICE");
  return env ? std::string(env) : std::string();
}

}  // namespace fw::host
