// The device memory a run will allocate, part by part. Each stage owns the estimate of what it allocates
// (WindGrid, ForestStages, LeafStages, ...); the planner's builders add one part each, so that `check`
// shows where the memory goes before any device is touched.
//
//   fw::host::DeviceMemory memory;
//   memory.add("wind grid", fw::host::WindGrid::estimate_device_bytes(spec, settings, 1));
//   memory.total();      // bytes
#pragma once

#include <cstddef>
#include <string>
#include <utility>
#include <vector>

namespace fw::host {

struct DeviceMemoryPart {
  std::string name;  ///< what allocates it, for people: "wind grid", "trees", "leaves", ...
  std::size_t bytes = 0;
};

class DeviceMemory {
 public:
  void add(std::string name, std::size_t bytes) { parts_.push_back({std::move(name), bytes}); }
  const std::vector<DeviceMemoryPart>& parts() const { return parts_; }
  std::size_t total() const {
    std::size_t sum = 0;
    for (const auto& part : parts_) sum += part.bytes;
    return sum;
  }

 private:
  std::vector<DeviceMemoryPart> parts_;
};

}  // namespace fw::host
