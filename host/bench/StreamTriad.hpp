// STREAM triad (a = b + s c) on the OpenCL device: the memory-bandwidth roofline that kernel throughput
// is compared with. Bytes counted as STREAM does: 3 arrays * 4 bytes per element (no write-allocate).
//
//   double gb_s = fw::bench::measure_stream_triad(cc, 32 << 20, 10);   // best of 10 runs
#pragma once

#include <cstddef>

#include "host/runtime/ComputeContext.hpp"

namespace fw::bench {

/// The benchmarks' roofline triad: 32 Mi floats an array (384 MiB in all, far past any cache), best of 10.
inline constexpr std::size_t kRooflineElements = std::size_t(32) << 20;
inline constexpr int kRooflineRepetitions = 10;

/// Best bandwidth over `repetitions` triads of `elements` floats, GB/s (1e9 bytes/s).
double measure_stream_triad(host::ComputeContext& cc, std::size_t elements, int repetitions);

}  // namespace fw::bench
