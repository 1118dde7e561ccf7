// How a tree's modes advance in time: each mode is a damped oscillator q'' + gamma q' + omega^2 q = f
// (docs/design.md, "Numerics: Trees: Integration").
#pragma once

#include <cmath>

namespace fw::trees {

enum class ModalIntegrator {
  exact,          ///< exact solution of the damped oscillator for the force held over the step
  semi_implicit,  ///< Diener's semi-implicit Euler: qdot += dt (f - gamma qdot - omega^2 q); q += dt qdot
};

/// The largest dt (s) at which semi-implicit Euler stays stable for a mode of angular frequency omega
/// (rad/s, > 0) and damping gamma (1/s, >= 0): the root of dt^2 omega^2 + 2 gamma dt = 4 (Jury's test on
/// the amplification matrix, trace 2 - dt^2 omega^2 - gamma dt, determinant 1 - gamma dt).
inline double semi_implicit_dt_limit(double omega, double gamma) {
  return (std::sqrt(gamma * gamma + 4.0 * omega * omega) - gamma) / (omega * omega);
}

}  // namespace fw::trees
