// The elements of one tree as the two element models see them (trees/TreeDynamics.hpp: rigid_bodies,
// springs): each element a body of its own, fixed at its parent's end, with its mass, its joint's stiffness,
// its drag and, for the springs, its flat-spring constant. The table is in the skeleton's topological order
// (parents before children), so a walk down the table meets every parent before its children and a walk up
// meets every child before its parent.
//
//   fw::trees::BranchElements elements = fw::trees::BranchElements::of(skeleton, wood, drag);
//   for (int j = 1; j < elements.size(); ++j) {            // entry 0 is the root: no element
//     const fw::trees::BranchElement& e = elements[j];     // from node e.parent_node to node e.node
//     Eigen::Vector3d force = elements.load(j, wind);      // N, the drag of a wind `wind` at its centre
//   }
//
// Units: SI, skeleton frame, scale 1. An instance of scale s (trees/Forest.hpp) has lengths times s, masses
// times s^3, rotational inertias times s^5, joint stiffnesses times s^3, drag per metre times s and spring
// constants times s: a wind then bends every joint by the same angle at every scale.
//
// Joint stiffness (rigid_bodies). Element e turns about its base joint against a spring K_e (3 x 3, N m/rad,
// rotations as vectors in the skeleton frame). A beam's curvature spreads over its length; a chain of rigid
// elements lumps it into the joints. Each joint takes the compliance of half of its own element and, when
// the element continues its parent (the parent's thickest child, the first on a tie), of the parent's outer
// half:
//   K_e^-1 = L_e / 2 C(e) + [e continues p] L_p / 2 C(p),  C(e) = (I - a a^T) / (E I_e) + a a^T / (G J_e),
// a the element's unit axis, I_e = pi r^4 / 4 and J_e = pi r^4 / 2 of its mean radius (as trees/BeamModel).
// On a uniform cantilever of N elements under a tip force this gives the Euler-Bernoulli tip deflection
// times (1 + 1 / (2 N^2)), where the joint at the element's base alone (K = E I / L) gives (1 + 3 / (2 N)):
// lumping at the midpoints is second order, at the ends first order. At a fork, a side branch's joint
// leaves out the parent's outer half, which only bends under the continuing child's load here.
//
// Drag (trees/WindBasis.hpp ElementDrag, the convention both sides of the coupling share): the force on the
// element in a wind v at its centre is L_e (b_e P_e + l_e I) |v| v, b_e = 1/2 rho_air C_Db D_e (P_e the
// normal projection with branch_normal_drag, else I) and l_e = 1/2 rho_air C_Df lambda_e. Its sum over the
// elements in a uniform wind is the FEM's total load, sum_e A_e L_e |v| v.
//
// Spring constant (springs; Ota et al. 2004): a flat cantilever spring of width b, thickness t and length l
// bends by P / k under a tip load P, k = E b t^3 / (4 l^3); with b = t = D_e, the element's diameter.
#pragma once

#include <Eigen/Dense>

#include <vector>

#include "kernels/shared_types.h"
#include "trees/Material.hpp"
#include "trees/WindBasis.hpp"

namespace fw::trees {

class Skeleton;

/// One entry of the table: the element from parent_node to node (the root's entry has none: zeros).
struct BranchElement {
  int node = -1;          ///< the element's outer node (skeleton index)
  int parent_node = -1;   ///< its base node, where its joint is; -1 for the root's entry
  int parent_entry = -1;  ///< the table entry of parent_node (0 when the element starts at the root)
  Eigen::Vector3d rest = Eigen::Vector3d::Zero();    ///< node minus parent node at rest, m
  Eigen::Vector3d centre = Eigen::Vector3d::Zero();  ///< the element's midpoint at rest, m
  double length = 0.0;                               ///< L_e, m
  double mass = 0.0;                                 ///< rho A_e L_e, kg
  double axial_inertia = 0.0;  ///< rho J_e L_e, kg m^2: the rod's inertia about its own axis
  Eigen::Matrix3d joint_stiffness = Eigen::Matrix3d::Zero();  ///< K_e, N m/rad (header comment)
  double branch_drag = 0.0;                                   ///< b_e = 1/2 rho_air C_Db D_e, kg/m^3 x m
  double leaf_drag = 0.0;                                     ///< l_e = 1/2 rho_air C_Df lambda_e, kg/m^3 x m
  double spring_stiffness = 0.0;                              ///< k = E D_e^4 / (4 L_e^3), N/m
};

class BranchElements {
 public:
  /// The table of `skeleton` (at least two nodes) with the wood `material` and the drag of `drag`.
  /// Throws std::invalid_argument("BranchElements: ...") for a skeleton without elements or invalid
  /// settings.
  static BranchElements of(const Skeleton& skeleton, const Material& material, const WindBasisSettings& drag);

  /// n entries, the root's first.
  int size() const { return int(entries_.size()); }
  const BranchElement& operator[](int entry) const { return entries_.at(std::size_t(entry)); }
  const std::vector<BranchElement>& entries() const { return entries_; }
  /// Whether the wood drags only with the wind normal to it (WindBasisSettings::branch_normal_drag).
  bool normal_drag() const { return normal_drag_; }

  /// The drag force on entry's element (N, skeleton frame) in the wind `wind` (m/s) at its centre, scale 1.
  Eigen::Vector3d load(int entry, const Eigen::Vector3d& wind) const;

  /// The table as the device reads it (kernels/shared_types.h FwBranch), in float.
  std::vector<FwBranch> pack() const;

 private:
  std::vector<BranchElement> entries_;
  bool normal_drag_ = false;
};

}  // namespace fw::trees
