#include <fmt/format.h>

#include <iostream>

#include "host/cli/Commands.hpp"
#include "host/runtime/Device.hpp"
#include "io/JsonWriter.hpp"

namespace fw::cli {

int run_devices(bool json) {
  const auto devices = host::list_devices();  // NoDeviceError -> exit 3 in main
  if (json) {
    io::JsonWriter out;
    out.begin_object().key("devices").begin_array();
    for (const auto& d : devices) {
      out.begin_object();
      out.key("platform_index").value(d.platform_index);
      out.key("device_index").value(d.device_index);
      out.key("platform").value(d.platform_name);
      out.key("platform_version").value(d.platform_version);
      out.key("device").value(d.device_name);
      out.key("device_version").value(d.device_version);
      out.key("type").value(d.type);
      out.key("compute_units").value(d.compute_units);
      out.key("global_memory_bytes").value(static_cast<std::uint64_t>(d.global_memory_bytes));
      out.key("max_allocation_bytes").value(static_cast<std::uint64_t>(d.max_allocation_bytes));
      out.key("max_clock_mhz").value(d.max_clock_mhz);
      out.end_object();
    }
    out.end_array().end_object();
    std::cout << out.str() << "\n";
    return 0;
  }
  int last_platform = -1;
  for (const auto& d : devices) {
    if (d.platform_index != last_platform) {
      std::cout << fmt::format("platform {}: {} ({})\n", d.platform_index, d.platform_name,
                               d.platform_version);
      last_platform = d.platform_index;
    }
    std::cout << fmt::format(
        "  device {}: {} [{}], {} compute units, {:.1f} GiB global memory, {:.1f} GiB max "
        "allocation, {} MHz\n",
        d.device_index, d.device_name, d.type, d.compute_units, d.global_memory_bytes / 1073741824.0,
        d.max_allocation_bytes / 1073741824.0, d.max_clock_mhz);
  }
  const auto chosen = host::select_device(host::device_filter_from_env(""));
  std::cout << fmt::format("default: {} / {} (choose with --device or FORESTWIND_DEVICE)\n",
                           chosen.platform_name, chosen.device_name);
  return 0;
}

}  // namespace fw::cli
