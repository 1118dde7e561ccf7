// Gather throughput on the OpenCL device: the limit that binds advection, whose back-traces load the
// corners of cells at scattered positions (kernels/bench_gather.cl does the same loads, through the same
// gather(), and nothing else).
//
//   double loads_per_s = fw::bench::measure_gather_rate(cc, {128, 128, 64}, 10);   // best of 10
#pragma once

#include <array>

#include "host/runtime/ComputeContext.hpp"

namespace fw::bench {

/// Best rate over `repetitions` passes of eight-corner gathers at one displaced position per cell of an
/// nx x ny x nz array, in scalar loads per second.
double measure_gather_rate(host::ComputeContext& cc, const std::array<int, 3>& grid, int repetitions);

}  // namespace fw::bench
