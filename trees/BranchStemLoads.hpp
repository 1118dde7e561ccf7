// The stem loads of the element trees (trees/TreeDynamics.hpp: rigid_bodies, springs) for storm damage
// (docs/damage-element-trees.md): the bending moment at every stem section and the root's turning moment from
// the joints, the counterpart of trees/StemLoads.hpp's modal maps, and the CPU reference of
// kernels/tree_loads.cl branch_tree_loads. The critical moments, the failure rule and the record are the
// modal trees' (trees/TreeDamage.hpp).
//
//   fw::trees::BranchStem stem = fw::trees::BranchStem::of(skeleton);        // StemLoads' stem and sections
//   fw::trees::BranchStemMoments M = fw::trees::branch_stem_moments(
//       skeleton, elements, stem, fw::trees::TreeDynamics::rigid_bodies, 1.2, state.angle);
//   M.bending(j), M.root;                                                     // N m
//   fw::trees::TreeLoad load = fw::trees::branch_tree_load(M, critical, 1.2);  // as tree_load's
//
// The sections are the modal model's (stem_path, stem_section_indices; StemLoads::sections): at most
// kMaxStemSections stem nodes, the top excluded, and a section's moment is that of everything above its
// node, the cut just below the node (StemLoads: the node's descendants).
//
// The elastic moment. A joint's spring carries what bends the wood at it:
//   - rigid_bodies: the joint moment K_e theta_e (s^3 K_e at scale s). In statics it is the moment about the
//     joint of every element load beyond it (RigidBranches::equilibrium: theta = K^-1 M), and so on a uniform
//     load exactly the beam's w (L - x)^2 / 2 (the loads sit at the element centres, where the midpoint rule
//     integrates the linear lever arm exactly). In motion it is the wind's moment less the inertia's (and
//     less the damper's C theta', as the modal model's K Phi q leaves out the damping forces): a gust's
//     overshoot loads the stem as it does the modal model's. The statics of the element loads alone would
//     miss that, so the joint moment is the more faithful of the two.
//   - springs: Ota's element bends by tan theta = P / (k L), P its own load across it taken as a tip load on
//     a cantilever spring of stiffness k (s k, s L at scale s); the moment at its joint is that load's,
//     P L = k L^2 tan |theta| (s^3 k L^2 tan |theta| at scale s), along theta (about a x P, as the bend
//     turns). It carries the sway's sine and the largest bend's cap with the bend itself. It is the element's
//     own load only: in this model no joint carries the load of the elements beyond it, so the stem's moments
//     are single elements' (w L_e^2 on a uniform pole, where a beam carries w (L - x)^2 / 2), change with the
//     cut (halving the elements quarters them), and a springs tree fails only on a weak stem of its own.
// The cut below a section's node passes every joint at it: the section's elastic moment is the sum of the
// joint moments of every element that starts at its node (the stem's next element and the side branches
// there), each a vector in the skeleton frame (the parent's frame at rest, in which the linearised joints
// turn).
//
// The weight on the deflection, as the modal model's (StemLoads: Hale et al. 2015's deflection loading):
//   W_j = sum over the descendants k of j of (u_k - u_j) x (0, 0, -m_k g),
// u the displacements of the pose (trees/BranchPose: exact rotations, every element keeping its length) and
// m_k the lumped node masses (half of each adjacent element's rho A L). Lumping each element's mass at its
// centre instead gives the same sum: a rigid element's centre moves by the mean of its ends' displacements,
// so m_e (u_c - u_j) = m_e / 2 (u_a - u_j) + m_e / 2 (u_b - u_j), and an element starting at j puts its lower
// half on j's own zero lever arm either way (the device sums the element masses at their centres).
//
// The stress: the part of M_j = E_j + W_j normal to the stem's rest axis t_j (to the next stem node), as the
// modal maps project; the root's turning moment is the horizontal part (x, y) of section 0's. Rest axes and
// the rest frame, as the linearised joints (and the modal maps): under a large bend the section's own axis
// has turned by the stem's angle, and a moment along the rest axis (torsion) would then bend it by the sine
// of that angle; a vertical stem's weight moment is horizontal and all bending either way.
//
// Scale s (trees/BranchElements.hpp): masses s^3, lengths s (the pose's), joint stiffness s^3, spring
// constants and lengths s: the moments scale as s^3 when the angles are the same, as the critical moments
// (diameters^3, volume) do.
#pragma once

#include <Eigen/Dense>

#include <vector>

#include "trees/BranchElements.hpp"
#include "trees/Gravity.hpp"
#include "trees/Skeleton.hpp"
#include "trees/TreeDamage.hpp"
#include "trees/TreeDynamics.hpp"

namespace fw::trees {

/// The stem of an element tree as its joints see it, per entry of its table (BranchElements: the skeleton's
/// topological order).
class BranchStem {
 public:
  /// The stem of `skeleton` (stem_path; std::invalid_argument("StemLoads: ...") when the root has no child).
  static BranchStem of(const Skeleton& skeleton);

  /// J, the sections: StemLoads::section_count()'s.
  int section_count() const { return int(axes_.size()); }
  /// The stem's nodes, root first, the top included (stem_path).
  const std::vector<int>& path() const { return path_; }
  /// Per section: its skeleton node (StemLoads::sections()[j].node).
  const std::vector<int>& section_nodes() const { return section_nodes_; }
  /// Per section: its stem node's table entry.
  const std::vector<int>& section_entries() const { return section_entries_; }
  /// Per section: the stem's unit axis at rest, from its node to the next stem node.
  const std::vector<Eigen::Vector3d>& axes() const { return axes_; }
  /// Per table entry: the section whose node is the entry's joint (its element starts at section j's node),
  /// else -1 (the root's entry: -1).
  const std::vector<int>& joint_sections() const { return joint_sections_; }
  /// Per table entry: the highest section its element lies above (that of the deepest section node among
  /// its base node and the base's ancestors); it is above every section up to that one. Root: -1.
  const std::vector<int>& element_sections() const { return element_sections_; }

 private:
  std::vector<int> path_, section_nodes_, section_entries_, joint_sections_, element_sections_;
  std::vector<Eigen::Vector3d> axes_;
};

/// The moment (N m, skeleton frame) entry e's joint carries at the angle theta (rad, rotation vector) at
/// scale s under `model` (rigid_bodies or springs; the header says which). Throws std::invalid_argument for
/// modal.
Eigen::Vector3d joint_moment(const BranchElement& e, TreeDynamics model, double scale,
                             const Eigen::Vector3d& theta);

/// One pose's stem loads.
struct BranchStemMoments {
  Eigen::Matrix3Xd elastic;  ///< per section (column j), the joint moments at it, N m, skeleton frame
  Eigen::Matrix3Xd weight;   ///< per section, the weight's moment on the deflection
  Eigen::VectorXd bending;   ///< |part of elastic + weight normal to the section's rest axis|, N m
  double root = 0.0;         ///< |horizontal part of section 0's|, N m
};

/// The stem loads of the tree of `elements` (of `skeleton`, whose stem is `stem`) moved by `model` at scale s
/// (> 0) with the joint angles `angles` (one per table entry). Throws std::invalid_argument for counts that
/// do not fit or a modal `model`.
BranchStemMoments branch_stem_moments(const Skeleton& skeleton, const BranchElements& elements,
                                      const BranchStem& stem, TreeDynamics model, double scale,
                                      const std::vector<Eigen::Vector3d>& angles, double gravity = kGravity);

/// The moments against the critical moments of the species' scale-1 stem (critical_moments of its
/// StemLoads, whose sections these are) at scale s: as tree_load for a modal tree.
TreeLoad branch_tree_load(const BranchStemMoments& moments, const CriticalMoments& critical, double scale);

}  // namespace fw::trees
