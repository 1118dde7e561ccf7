// What the tests of the element tree models share (tests/trees/RigidBranches_test.cpp,
// tests/trees/SpringBranches_test.cpp, tests/validation/TreeModels_test.cpp, and the kernels' tree_branches
// and tree_loads tests): every element's load in a uniform wind, the highest node, the peak of a series'
// spectrum, and one species of each model.
#pragma once

#include <Eigen/Core>

#include <cmath>
#include <numbers>
#include <vector>

#include "trees/BranchElements.hpp"
#include "trees/Skeleton.hpp"
#include "trees/TreeDynamics.hpp"

namespace fw::test {

/// The drag on every entry's element (N, scale 1) in a wind `wind` (m/s) uniform over the tree.
inline std::vector<Eigen::Vector3d> uniform_loads(const trees::BranchElements& elements,
                                                  const Eigen::Vector3d& wind) {
  std::vector<Eigen::Vector3d> loads(std::size_t(elements.size()), Eigen::Vector3d::Zero());
  for (int j = 1; j < elements.size(); ++j) loads[std::size_t(j)] = elements.load(j, wind);
  return loads;
}

/// Species 0, 1 and 2 of a forest of the three models (docs/tree-models.md), as three_model_dynamics gives
/// them.
inline constexpr int kRigid = 0, kSprings = 1, kModal = 2;

/// Rigid bodies (damping 0.08), springs (capped at 25 degrees, sway 0.5) and modal: the kernel tests' three
/// species, settings away from the defaults so that each enters the result.
inline std::vector<trees::SpeciesDynamics> three_model_dynamics() {
  std::vector<trees::SpeciesDynamics> dynamics(3);
  dynamics[kRigid].model = trees::TreeDynamics::rigid_bodies;
  dynamics[kRigid].rigid_bodies.damping_ratio = 0.08;
  dynamics[kSprings].model = trees::TreeDynamics::springs;
  dynamics[kSprings].springs.max_angle_deg = 25.0;
  dynamics[kSprings].springs.sway_amplitude = 0.5;
  return dynamics;
}

/// The highest node (the first of equal heights): the tip that probes.csv reports.
inline int top_node(const trees::Skeleton& skeleton) {
  int top = 0;
  for (int n = 0; n < skeleton.size(); ++n)
    if (skeleton.node(n).position.z() > skeleton.node(top).position.z()) top = n;
  return top;
}

/// The f in [lo, hi] (Hz, by steps of `step`) where |sum_k x_k e^(-2 pi i f k dt)| peaks: a series' dominant
/// frequency, resolved finer than its FFT's bins.
inline double spectral_peak(const std::vector<double>& x, double dt, double lo, double hi, double step) {
  double best = 0.0, best_f = lo;
  for (double f = lo; f <= hi; f += step) {
    double re = 0.0, im = 0.0;
    for (std::size_t k = 0; k < x.size(); ++k) {
      re += x[k] * std::cos(2.0 * std::numbers::pi * f * double(k) * dt);
      im += x[k] * std::sin(2.0 * std::numbers::pi * f * double(k) * dt);
    }
    if (re * re + im * im > best) best = re * re + im * im, best_f = f;
  }
  return best_f;
}

}  // namespace fw::test
