// The FEM's static answer to a steady wind (docs/design.md, "Trees": other tree models): the displacement of
// every node of a clamped tree under a wind uniform over it, from a direct sparse solve of the whole model,
// with no modal truncation. It is the reference that the other tree models (rigid bodies, cantilever
// springs) and the modal model's truncation are measured against.
//
//   fw::trees::BeamModel model(skeleton, wood);
//   fw::trees::WindBasisSettings drag;                         // the species' drag convention
//   Eigen::MatrixX3d u = fw::trees::static_deflection(skeleton, model, drag, {10.0, 0.0, 0.0});
//   double tip_dx = u(top_node, 0);                            // m
//
// The math: K u = F, K the stiffness of the free DOFs (trees/BeamModel.hpp, the root clamped) and F the
// consistent nodal load of the wind v, F = G |v| v (trees/WindBasis.hpp, load_operator: the same drag as the
// modal forces and the air's side), solved by a sparse LDL^T factorisation (K is symmetric positive
// definite once the root is clamped). With every mode kept, the modal static solution sum_i phi_i
// (phi_i . F) / omega_i^2 is this same u.
#pragma once

#include <Eigen/Core>

#include "trees/BeamModel.hpp"
#include "trees/Skeleton.hpp"
#include "trees/WindBasis.hpp"

namespace fw::trees {

/// The static displacement of every node (node_count x 3, m, skeleton frame; the root's row 0) of `skeleton`
/// (whose `model` it is) in the wind `wind` (m/s, skeleton frame) uniform over the tree, with the drag of
/// `drag` (its samples do not matter: the wind is the same in every band). Throws std::runtime_error when the
/// factorisation fails (a stiffness that is not positive definite).
Eigen::MatrixX3d static_deflection(const Skeleton& skeleton, const BeamModel& model,
                                   const WindBasisSettings& drag, const Eigen::Vector3d& wind);

}  // namespace fw::trees
