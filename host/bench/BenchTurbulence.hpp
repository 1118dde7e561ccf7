// The turbulence that `bench wind` and `bench coupled` add to their laminar cases, so that the cost of
// turbulence is the difference between two runs in the same process.
//
//   host::WindGridSetup setup = ...;                  // a laminar case, ambient 10 m/s
//   add_bench_turbulence(setup, grid);                // the inflow box
//   wind.set_turbulence_sigma(kBenchTurbulenceSigma); // once the grid exists
//
// The case: intensity 15% of the 10 m/s wind (sigma 1.5 m/s), L_u 16 cells, a von Karman box of points every
// h/2 as long as the domain on each axis (as a run's plan builds it), seed 1; with subgrid stress, C_s 0.16
// and a rough ground of z0 0.05 m.
#pragma once

#include <array>

#include "host/stages/WindGrid.hpp"

namespace fw::bench {

inline constexpr double kBenchTurbulenceSigma = 1.5;       // m/s
inline constexpr double kBenchTurbulenceIntensity = 0.15;  // sigma / U at U = 10 m/s
inline constexpr double kBenchTurbulenceLengthCells = 16.0;
inline constexpr double kBenchSmagorinsky = 0.16;
inline constexpr double kBenchRoughnessLength = 0.05;  // m

/// Sets setup.turbulence to the bench's box for a grid of `grid` cells of setup.spec.h.
void add_bench_turbulence(host::WindGridSetup& setup, const std::array<int, 3>& grid);
/// And the Smagorinsky stress and the rough-wall stress.
void add_bench_subgrid_stress(host::WindGridSetup& setup);

}  // namespace fw::bench
