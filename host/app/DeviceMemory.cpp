#include "host/app/DeviceMemory.hpp"

#include <fmt/format.h>

#include <stdexcept>

namespace fw::host {

namespace {
constexpr double kMib = 1024.0 * 1024.0;

std::string by_part(const DeviceMemory& memory) {
  std::string text;
  for (const DeviceMemoryPart& part : memory.parts())
    text += fmt::format("{}{} {:.0f} MiB", text.empty() ? "" : ", ", part.name, double(part.bytes) / kMib);
  return text;
}
}  // namespace

void require_fits(const DeviceMemory& memory, const DeviceInfo& device, std::string_view what) {
  const std::size_t total = memory.total();
  if (total > device.global_memory_bytes)
    throw std::invalid_argument(fmt::format(
        "{}: the run needs about {:.0f} MiB ({} bytes) of device memory ({}), but '{}' has {:.0f} MiB ({} "
        "bytes); shrink the grid (domain.size, domain.cell_size) or the forest, or choose a larger device "
        "with --device",
        what, double(total) / kMib, total, by_part(memory), device.device_name,
        double(device.global_memory_bytes) / kMib, device.global_memory_bytes));
  const std::size_t largest = memory.largest_buffer();
  if (largest > device.max_allocation_bytes)
    throw std::invalid_argument(fmt::format(
        "{}: the run's largest buffer needs {:.0f} MiB ({} bytes), but '{}' allocates at most {:.0f} MiB ({} "
        "bytes) in one buffer (CL_DEVICE_MAX_MEM_ALLOC_SIZE); shrink the grid (domain.size, "
        "domain.cell_size), "
        "or choose another device with --device",
        what, double(largest) / kMib, largest, device.device_name, double(device.max_allocation_bytes) / kMib,
        device.max_allocation_bytes));
}

}  // namespace fw::host
