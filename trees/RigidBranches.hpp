// Oliapuram & Kumar's (2010, section 3.1) articulated tree, the CPU reference of kernels/tree_branches.cl:
// every element (trees/BranchElements) a rigid rod fixed at its parent's end and turning about it, against
// its joint spring K_e and damper C_e = beta K_e, driven by the wind's drag on it.
//
//   fw::trees::RigidBranches tree(elements, 1.2, fw::trees::rigid_damping(0.05, omega_1 / 1.2));
//   fw::trees::RigidBranchState state = tree.equilibrium(loads);   // at rest in the loads (N, per entry)
//   for (int n = 0; n < steps; ++n) tree.step(loads, dt, state);
//   Eigen::MatrixX3d u = fw::trees::branch_displacements(elements, 1.2, state.angle);   // trees/BranchPose
//
// The dynamics. The joint angles theta_e (rotation vectors relative to the parent, skeleton frame) are the
// coordinates; the equations are linearised about the rest pose, as the modal model's are:
//   M theta'' + C theta' + K theta = J^T F,
// M the articulated tree's mass matrix at rest (a joint carries everything beyond it), K and C
// block-diagonal (one 3 x 3 block per joint), F the elements' drag at their centres. The paper lets each
// element feel only its children's spring torques, from the last step; its children then pass back their
// spring torque but not the force behind it, which leaves a trunk without the lever arm of its crown's load,
// and each joint swinging at its own frequency. Here a child passes back everything (the articulated-body
// recursion: Featherstone's ABA, in the coordinates of each joint), so the static bend is the beam's
// (BranchElements' joint stiffness) and the tree sways at its own first frequency.
//
// Integration: the theta-method with weight w = FW_RIGID_IMPLICIT_WEIGHT (0.6) in the springs and dampers,
//   theta'_{n+1} = theta'_n + h theta'',   theta_{n+1} = theta_n + h ((1 - w) theta'_n + w theta'_{n+1}),
// with the joint torque -K theta_w - C theta'_w taken at the weighted state x_w = (1 - w) x_n + w x_{n+1}:
// the terms w h C + w^2 h^2 K join each joint's inertia in the recursion, which then still costs one pass up
// and one pass down the tree. It is stable at any dt (w >= 1/2). A stiff thin twig whose period is far
// shorter than the step (the paper's explicit update would need sub-steps of its period) shrinks by
// (1 - w) / w = 2/3 a step instead of ringing, as it would under the trapezoidal rule (w = 1/2); the tree's
// own sway loses a damping ratio of only about (w - 1/2) omega h (0.007 for a 0.56 Hz tree at h = 0.02 s),
// where backward Euler (w = 1) takes omega h / 2 (0.035: its sway's standard deviation in turbulence falls
// 20% below the modal model's).
//
// Scale: an instance of scale s (trees/Forest.hpp) scales the table as BranchElements says; its loads are
// the instance's, N.
#pragma once

#include <Eigen/Dense>

#include <vector>

#include "trees/BranchElements.hpp"

namespace fw::trees {

/// Every joint's angle (rad, rotation vector) and rate (rad/s), one per table entry (the root's is zero).
struct RigidBranchState {
  std::vector<Eigen::Vector3d> angle, rate;
};

/// beta = 2 zeta / omega_1 (s): the joint damping C = beta K that gives a mode of angular frequency
/// omega_1 (rad/s, > 0) the damping ratio zeta.
double rigid_damping(double zeta, double omega_1);

class RigidBranches {
 public:
  /// The tree of `elements` at scale s (> 0), its joints damped by C = damping K (damping in s, >= 0).
  /// Throws std::invalid_argument("RigidBranches: ...") otherwise. Keeps a reference to `elements`.
  RigidBranches(const BranchElements& elements, double scale, double damping);

  /// The moment of everything beyond each joint about it, N m: sum over the element and its descendants of
  /// (centre - joint) x load, with `loads` one force per entry (N, skeleton frame, at the elements' centres).
  std::vector<Eigen::Vector3d> joint_moments(const std::vector<Eigen::Vector3d>& loads) const;
  /// At rest in the loads: theta_e = K_e^-1 M_e, no rate.
  RigidBranchState equilibrium(const std::vector<Eigen::Vector3d>& loads) const;
  /// Advances `state` by dt (s, >= 0) with the loads held over the step (header comment).
  void step(const std::vector<Eigen::Vector3d>& loads, double dt, RigidBranchState& state) const;

 private:
  const BranchElements& elements_;
  double scale_, damping_;
};

}  // namespace fw::trees
