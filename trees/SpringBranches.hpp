// Ota et al.'s (2004) cantilever springs as Yildiz implements them, the CPU reference of
// kernels/tree_branches.cl spring_angles: every element bends quasi-statically under its own wind load.
//
//   fw::trees::SpringSettings settings;                          // trees/TreeDynamics.hpp
//   std::vector<double> phases = fw::trees::spring_phases(tree_id, elements.size());
//   std::vector<Eigen::Vector3d> theta =
//       fw::trees::spring_angles(elements, settings, 1.2, loads, phases, t);
//   Eigen::MatrixX3d u = fw::trees::branch_displacements(elements, 1.2, theta);   // trees/BranchPose
//
// Element e (length s L_e, spring constant s k_e at scale s; trees/BranchElements) carries the part of its
// drag F_e normal to it, P = |F_e - (F_e . a) a| (a its rest axis; the load along it bends nothing), and
// (Yildiz's eqs. 1-7):
//   theta_s = min(atan(P / (s k_e) / (s L_e)), theta_max)                the steady bend,
//   a_e     = sway_amplitude theta_s / theta_max                       a bent element sways more,
//   theta   = min(atan(P (1 + a_e sin(2 pi f t + b_e)) / (s k_e) / (s L_e)), theta_max),
// turning the element about a x P (towards the load) by theta, relative to its parent: angles accumulate
// from parent to child through the pose (trees/BranchPose). b_e is random per element and tree
// (spring_phases). Yildiz turns each segment about the world's horizontal axes, and had to reverse the turn
// of a segment hanging upside down (a weeping tree's), whose tip would otherwise move into the wind; turning
// about a x P, every tip moves downwind whichever way its element points, and a hanging segment's angle
// from the vertical decreases with the wind, which is that fix.
//
// No inertia: the tree follows the wind within the step, with no sway of its own at its natural frequency;
// between gusts it stands still but for the sine, and it never overshoots. Only a single element's own load
// bends it: a trunk does not feel its crown's drag (its spring is the stiffest of all), so the tree bends far
// less than the FEM under the same wind (docs/trees.md gives the figure).
#pragma once

#include <Eigen/Dense>

#include <cstdint>
#include <vector>

#include "trees/BranchElements.hpp"
#include "trees/TreeDynamics.hpp"

namespace fw::trees {

/// b_e in [0, 2 pi) for every entry of tree `tree_id`'s table of `count` entries: a hash of the two, the
/// same on the device (kernels/tree_branches.cl) and in every run.
std::vector<double> spring_phases(int tree_id, int count);

/// The joint angles (rad, rotation vectors in the skeleton frame, one per entry, the root's 0) of the tree
/// of `elements` at scale s under `loads` (N per entry, skeleton frame, at scale s) at time t (s).
/// Throws std::invalid_argument("spring_angles: ...") for wrong counts.
std::vector<Eigen::Vector3d> spring_angles(const BranchElements& elements, const SpringSettings& settings,
                                           double scale, const std::vector<Eigen::Vector3d>& loads,
                                           const std::vector<double>& phases, double time);

}  // namespace fw::trees
