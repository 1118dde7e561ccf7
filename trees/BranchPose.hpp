// The pose of a tree of element models (trees/RigidBranches, trees/SpringBranches) from its joint angles:
// the cumulative transformation of Oliapuram & Kumar (2010, section 3.2), the CPU reference of
// kernels/tree_branches.cl branch_deform.
//
//   Eigen::MatrixX3d u = fw::trees::branch_displacements(elements, 1.2, angles);   // node_count x 3, m
//
// Each element turns with its parent and then by its own joint angle theta_e (a rotation vector, relative to
// the parent, in the parent's frame, which is the skeleton frame at rest): Q_e = Q_parent Exp(theta_e), the
// root's Q the identity. Its outer node sits at its parent node's new position plus Q_e times the rest
// element, so every element keeps its length however far it turns. Written as displacements,
// u_node = u_parent + (Q_e - I) s rest_e: differences only, so that trees far from the origin lose no digits.
#pragma once

#include <Eigen/Dense>

#include <vector>

#include "trees/BranchElements.hpp"

namespace fw::trees {

/// Exp(theta): the rotation by |theta| (rad) about theta's direction (Rodrigues), the identity at 0.
Eigen::Matrix3d rotation_of(const Eigen::Vector3d& theta);

/// Every node's displacement (skeleton node order, node_count x 3, m, skeleton frame; the root's 0) of the
/// tree of `elements` at scale s with the joint angles `angles` (one per table entry). Throws
/// std::invalid_argument("branch_displacements: ...") for a wrong count.
Eigen::MatrixX3d branch_displacements(const BranchElements& elements, double scale,
                                      const std::vector<Eigen::Vector3d>& angles);

}  // namespace fw::trees
