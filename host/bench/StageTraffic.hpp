// What each stage of a wind step moves, per face or cell: the model behind the benchmarks' fractions of the
// limit that binds a stage (the STREAM triad for the stencils, the measured gather rate for advection).
// Every array element a kernel reads or writes counts once (neighbours are taken as cached); masks are 1
// byte, floats 4. The pressure solver counts its own traffic kernel by kernel
// (PressureSolver::traffic_bytes).
#pragma once

namespace fw::bench {

// Advection's traffic is its scheme's: AdvectionMethod::bytes_per_face and gathered_loads_per_face
// (host/stages/wind/Advection.hpp).

/// Divergence: the three faces' velocities per cell (as many faces as cells per component), the mask, b.
constexpr double kDivergenceBytesPerCell = 3 * 4 + 1 + 4;
/// Gradient: per component, the face read and written, phi and the mask.
constexpr double kGradientBytesPerCell = 3 * (4 + 4 + 4 + 1);

}  // namespace fw::bench
