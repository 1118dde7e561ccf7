// The FEM model of one tree: every skeleton element becomes a 3D Euler-Bernoulli frame element
// (trees/BeamElement.hpp), assembled into sparse global stiffness and mass matrices with the root clamped.
//
//   fw::trees::BeamModel model(skeleton, fw::trees::Material{1.0e10, 3.85e9, 900.0});
//   const Eigen::SparseMatrix<double>& K = model.stiffness();   // dof_count() x dof_count()
//   const Eigen::SparseMatrix<double>& M = model.mass();
//   int i = model.free_dof_of(node, 2);                        // uz of that node, -1 for the root
//
// DOF numbering: the unconstrained system has 6 DOF per node, index 6*node + local with local in
// 0..5 = ux uy uz rx ry rz in the GLOBAL frame (m and rad, right-hand rule; see BeamElement.hpp). The root's
// 6 DOF are clamped and removed: the free system numbers the remaining nodes in increasing node order,
// skipping the root, so free DOF = 6*(node < root ? node : node - 1) + local. K and M are
// (6(n-1)) x (6(n-1)), symmetric, and positive definite for a valid skeleton.
//
// Element radius = mean of its two node radii; section = solid circle (BeamSection::circle).
#pragma once

#include <Eigen/Sparse>

#include <cstddef>

#include "trees/Material.hpp"

namespace fw::trees {

class Skeleton;

class BeamModel {
 public:
  /// Assembles K and M. Throws std::invalid_argument("BeamModel: ...") for a skeleton with fewer than 2 nodes
  /// and for an invalid material (Material::validate).
  BeamModel(const Skeleton& skeleton, const Material& material);

  /// Global stiffness of the free DOFs, N/m, N and N m per unit displacement or rotation.
  const Eigen::SparseMatrix<double>& stiffness() const { return stiffness_; }
  /// Global consistent mass of the free DOFs, kg and kg m^2.
  const Eigen::SparseMatrix<double>& mass() const { return mass_; }

  /// The wood the model was assembled with.
  const Material& material() const { return material_; }

  /// Number of free DOFs, 6 (n - 1).
  int dof_count() const { return dof_count_; }
  /// Number of skeleton nodes n, the root included.
  int node_count() const { return node_count_; }
  /// Index of DOF `local` (0..5 = ux uy uz rx ry rz) of `node` in the free system, -1 for the root's DOFs.
  /// Throws std::out_of_range for a node outside 0..n-1 or local outside 0..5.
  int free_dof_of(int node, int local) const;
  /// The same numbering without a model: the free DOF of (node, local) in a skeleton whose root is `root`,
  /// -1 for the root's own DOFs. No range checks.
  static int free_dof_index(int root, int node, int local) {
    if (node == root) return -1;
    return 6 * (node < root ? node : node - 1) + local;
  }

  /// Stored entries of stiffness(); mass() has the same pattern. Every element couples the full 6x6 blocks
  /// of its free nodes, so this is 36 (n - 1) + 72 * (elements between two non-root nodes).
  std::size_t nonzeros() const { return static_cast<std::size_t>(stiffness_.nonZeros()); }

 private:
  Material material_;
  int node_count_ = 0;
  int root_ = -1;
  int dof_count_ = 0;
  Eigen::SparseMatrix<double> stiffness_;
  Eigen::SparseMatrix<double> mass_;
};

}  // namespace fw::trees
