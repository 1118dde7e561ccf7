// The device memory a run will allocate, part by part. Each stage owns the estimate of what it allocates
// (WindGrid, ForestStages, LeafStages, ...); the planner's builders add one part each, so that `check`
// shows where the memory goes before any device is touched.
//
//   fw::host::DeviceMemory memory;
//   memory.add("wind grid", fw::host::WindGrid::estimate_device_bytes(setup));
//   memory.total();      // bytes
//   fw::host::require_fits(memory, device, "storm.yaml");   // exit 2 when the device is too small
#pragma once

#include <algorithm>
#include <cstddef>
#include <string>
#include <string_view>
#include <utility>
#include <vector>

#include "host/runtime/Device.hpp"

namespace fw::host {

struct DeviceMemoryPart {
  std::string name;  ///< what allocates it, for people: "wind grid", "trees", "leaves", ...
  std::size_t bytes = 0;
  std::size_t largest_buffer = 0;  ///< its largest single allocation, when the part knows it (else 0)
};

class DeviceMemory {
 public:
  void add(std::string name, std::size_t bytes, std::size_t largest_buffer = 0) {
    parts_.push_back({std::move(name), bytes, largest_buffer});
  }
  const std::vector<DeviceMemoryPart>& parts() const { return parts_; }
  std::size_t total() const {
    std::size_t sum = 0;
    for (const auto& part : parts_) sum += part.bytes;
    return sum;
  }
  /// The largest single allocation any part names.
  std::size_t largest_buffer() const {
    std::size_t largest = 0;
    for (const auto& part : parts_) largest = std::max(largest, part.largest_buffer);
    return largest;
  }

 private:
  std::vector<DeviceMemoryPart> parts_;
};

/// Throws std::invalid_argument (exit 2) when `memory` does not fit `device`: its total above the device's
/// global memory, or its largest buffer above the device's largest allocation (CL_DEVICE_MAX_MEM_ALLOC_SIZE).
/// The message starts with `what` (the scenario file) and gives both numbers, needed and available, and the
/// parts. For one process: over ranks each rank's block is checked where it is allocated (WindGrid).
void require_fits(const DeviceMemory& memory, const DeviceInfo& device, std::string_view what);

}  // namespace fw::host
