// Corner-load throughput on the OpenCL device: the limit that binds advection, whose back-traces load the
// eight corners of cells near each face (kernels/bench_gather.cl does the same loads, through the same
// cell_corners(), and nothing else). Measured in both regimes of cell_corners: scattered (gathers) and
// windowed (the back-traces of a smooth flow).
//
//   auto rates = fw::bench::measure_corner_load_rates(cc, {128, 128, 64}, 10);   // best of 10
//   double gathers_per_s = rates.scattered;
#pragma once

#include <array>

#include "host/runtime/ComputeContext.hpp"

namespace fw::bench {

/// Corner loads per second (eight per position), best of the passes.
struct CornerLoadRates {
  double scattered = 0.0;  ///< every lane's cell displaced on its own: gathers
  double windowed = 0.0;   ///< a work-item's cells along one row, straddling two shifts: windowed loads
};

/// Best rates over `repetitions` passes of eight-corner loads at one displaced position per cell of an
/// nx x ny x nz array, in scalar values loaded per second.
CornerLoadRates measure_corner_load_rates(host::ComputeContext& cc, const std::array<int, 3>& grid,
                                          int repetitions);

}  // namespace fw::bench
