// What each stage of a wind step moves, per face or cell: the model behind the benchmarks' fractions of the
// limit that binds a stage (the STREAM triad for the stencils, the measured gather rate for advection).
// Every array element a kernel reads or writes counts once (neighbours are taken as cached); masks are 1
// byte, floats 4. The pressure solver counts its own traffic kernel by kernel
// (PressureSolver::traffic_bytes).
#pragma once

#include "fluid/WindSettings.hpp"

namespace fw::bench {

/// Scalar gathered loads per face of one advection (kernels/fluid_advect.cl): the velocity at the face (the
/// component itself, and four faces for each of the other two: 9), the velocity at the midpoint (3 x 8
/// corners) and the advected component at the foot (8). Clamped MacCormack does that forward and backward
/// and a correction pass (a back-trace, the 8 corners, the forward and backward values).
constexpr double kSemiLagrangianLoadsPerFace = 9 + 24 + 8;
constexpr double kMacCormackLoadsPerFace = 2 * kSemiLagrangianLoadsPerFace + (9 + 24 + 8 + 2);

inline double advection_loads_per_face(fluid::AdvectionScheme scheme) {
  return scheme == fluid::AdvectionScheme::maccormack ? kMacCormackLoadsPerFace : kSemiLagrangianLoadsPerFace;
}

/// Bytes per face an advection step streams, neighbours taken as cached. upwind5 (kernels/fluid_upwind.cl):
/// three stages, each padding the three components (a read and a write of each face) and then reading a
/// face of each padded component, the base value and the packed orders (2 bytes) and writing the result;
/// its loads are whole rows, not gathers, so the triad binds it. The semi-Lagrangian step: a pad and the
/// result written (its gathers are counted by advection_loads_per_face); MacCormack two of those and the
/// correction's reads of q, the forward and the backward values.
inline double advection_bytes_per_face(fluid::AdvectionScheme scheme) {
  constexpr double kPad = 4 + 4, kStore = 4;
  switch (scheme) {
    case fluid::AdvectionScheme::upwind5:
      return 3 * (3 * kPad + (3 * 4 + 4 + 2 + kStore));
    case fluid::AdvectionScheme::maccormack:
      return 2 * (kPad + kStore) + (3 * 4 + kStore);
    case fluid::AdvectionScheme::semi_lagrangian:
      return kPad + kStore;
  }
  return 0.0;
}

/// Divergence: the three faces' velocities per cell (as many faces as cells per component), the mask, b.
constexpr double kDivergenceBytesPerCell = 3 * 4 + 1 + 4;
/// Gradient: per component, the face read and written, phi and the mask.
constexpr double kGradientBytesPerCell = 3 * (4 + 4 + 4 + 1);

}  // namespace fw::bench
