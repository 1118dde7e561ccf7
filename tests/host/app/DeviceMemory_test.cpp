// host/app/DeviceMemory: a run that does not fit the device is refused with both numbers, for the device's
// whole memory and for its largest allocation (which PoCL makes a quarter of the memory, so that a real grid
// meets the total first: only a device described here reaches the second).
#include "host/app/DeviceMemory.hpp"

#include <catch2/catch.hpp>

#include <stdexcept>

namespace {

constexpr std::size_t kMib = std::size_t(1) << 20;

fw::host::DeviceInfo device(std::size_t global_mib, std::size_t max_allocation_mib) {
  fw::host::DeviceInfo d;
  d.device_name = "small device";
  d.global_memory_bytes = global_mib * kMib;
  d.max_allocation_bytes = max_allocation_mib * kMib;
  return d;
}

fw::host::DeviceMemory grid_and_trees() {
  fw::host::DeviceMemory memory;
  memory.add("wind grid", 600 * kMib, 100 * kMib);
  memory.add("trees", 40 * kMib);
  return memory;
}

}  // namespace

TEST_CASE("DeviceMemory: a run within the device's memory and largest allocation is accepted") {
  CHECK(grid_and_trees().total() == 640 * kMib);
  CHECK(grid_and_trees().largest_buffer() == 100 * kMib);
  CHECK_NOTHROW(fw::host::require_fits(grid_and_trees(), device(640, 100), "run.yaml"));
}

TEST_CASE("DeviceMemory: more than the device's memory is refused with the needed and available bytes") {
  CHECK_THROWS_AS(fw::host::require_fits(grid_and_trees(), device(639, 1000), "run.yaml"),
                  std::invalid_argument);
  CHECK_THROWS_WITH(fw::host::require_fits(grid_and_trees(), device(639, 1000), "run.yaml"),
                    Catch::StartsWith("run.yaml: the run needs about 640 MiB (671088640 bytes)") &&
                        Catch::Contains("wind grid 600 MiB, trees 40 MiB") &&
                        Catch::Contains("'small device' has 639 MiB (670040064 bytes)"));
}

TEST_CASE("DeviceMemory: a buffer above the device's largest allocation is refused with both sizes") {
  CHECK_THROWS_WITH(fw::host::require_fits(grid_and_trees(), device(4096, 99), "run.yaml"),
                    Catch::StartsWith("run.yaml: the run's largest buffer needs 100 MiB (104857600 bytes)") &&
                        Catch::Contains("at most 99 MiB (103809024 bytes) in one buffer") &&
                        Catch::Contains("CL_DEVICE_MAX_MEM_ALLOC_SIZE"));
}
