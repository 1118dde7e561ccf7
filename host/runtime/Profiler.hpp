// Time spent per kernel, from OpenCL profiling events (`--profile`).
//
//   Profiler profiler;                       // owned by ComputeContext when profiling is on
//   profiler.record("advect", event);        // after each enqueue
//   profiler.print(std::cout);               // calls, total ms, mean ms per kernel
#pragma once

#include <cstdint>
#include <map>
#include <ostream>
#include <string>
#include <vector>

#include "host/runtime/opencl.hpp"

namespace fw::host {

struct KernelTiming {
  std::string name;
  std::uint64_t calls = 0;
  double total_ms = 0.0;
  double mean_ms() const { return calls ? total_ms / static_cast<double>(calls) : 0.0; }
};

class Profiler {
 public:
  /// Keeps the event; its time is read on the next collect() (reading it now would stall the queue).
  void record(const std::string& kernel_name, const cl::Event& event);
  /// Waits for the recorded events and adds their durations to the totals.
  void collect();
  /// Per-kernel totals, largest total first (collects first).
  std::vector<KernelTiming> timings();
  void print(std::ostream& out);
  void reset();

 private:
  std::vector<std::pair<std::string, cl::Event>> pending_;
  std::map<std::string, KernelTiming> totals_;
};

}  // namespace fw::host
