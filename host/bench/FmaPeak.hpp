// The device's measured arithmetic peak: float fused multiply-adds per second, the compute roofline for
// kernels that are FMA-bound (the skeleton deformation u = Phi q).
//
//   double gfma_s = fw::bench::measure_fma_peak(cc, 5);   // best of 5 runs, 1e9 FMA/s
#pragma once

#include "host/runtime/ComputeContext.hpp"

namespace fw::bench {

/// Best rate over `repetitions` runs of kernels/bench_fma.cl, in 1e9 single-precision FMAs per second
/// (one float8 fma counts 8).
double measure_fma_peak(host::ComputeContext& cc, int repetitions);

}  // namespace fw::bench
