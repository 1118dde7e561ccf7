// How a tree's modes advance in time: each mode is a damped oscillator q'' + gamma q' + omega^2 q = f
// (DESIGN.md, "Numerics: Trees: Integration").
#pragma once

namespace fw::trees {

enum class ModalIntegrator {
  exact,          ///< exact solution of the damped oscillator for the force held over the step
  semi_implicit,  ///< Diener's semi-implicit Euler: qdot += dt (f - gamma qdot - omega^2 q); q += dt qdot
};

}  // namespace fw::trees
