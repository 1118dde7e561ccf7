// The loads in a tree's stem as linear maps of its modal coordinates (docs/damage.md, "Loads"): the bending
// moment at every stem section from the root to the top of the trunk, and the root's turning moment, so that
// a step costs one small matrix-vector product per tree.
//
//   fw::trees::BeamModel model(skeleton, wood);
//   auto modes = fw::trees::ModalBasis::compute(model, settings);
//   auto stem = fw::trees::StemLoads::compute(skeleton, model, modes);
//   Eigen::VectorXd M = stem.bending_moments(q);      // N m, one per section, root first
//   double M_root = stem.root_moment(q);              // N m, about the horizontal axes through the root
//   stem.sections()[j].height, stem.sections()[j].diameter;   // m: where, and how thick
//   auto big = stem.scaled(1.2);                      // the instance of scale 1.2 (ModalBasis::scaled's q)
//
// The stem: from the root, at every node the child with the largest radius (the thickest continuation;
// a tie goes to the child that turns least), up to a node without children, the top of the trunk. Its
// sections are its nodes but the top, where nothing bends; a stem of more than kMaxStemSections such nodes
// keeps kMaxStemSections of them, evenly along it by arc length from the root (stem_section_indices), so
// that a tree's sections and its root fill one 16-wide block of the device's loads (kernels/tree_loads.cl).
// Under the crown the outer-fibre stress is nearly constant with height (Morgan & Cannell 1994), so the
// weakest section is found to the spacing, a fifteenth of the stem (1.3 m on a 20 m tree); in the crown the
// bending moment falls off faster than d^3 and the stress with it.
//
// The math. The elastic forces of the deformed tree, K u = K Phi q (BeamModel's stiffness, u the free DOFs),
// are the loads that bend it: the wind's minus the inertia's, as the FEM distributes them to the nodes. The
// bending moment at section j is the statics of the part above it: with x_k the rest position of node k and
// F_k the translational rows of K Phi q at k,
//   M_j = sum over the descendants k of j of (x_k - x_j) x F_k,
// and the tree's own weight on its deflection (Hale et al. 2015's "deflection loading", here computed instead
// of ForestGALES's factor of about 1.14), with m_k the node's lumped mass (half of each adjacent element's
// rho A L) and u_k = Phi_k q its translation:
//   M_j += sum over k of (u_k - u_j) x (0, 0, -m_k g).
// Both are linear in q. The stress needs the part that bends the section, normal to the stem's axis t_j
// (the unit vector to the next stem node); its two components on an orthonormal pair (e1, e2) normal to t_j
// are stored, so |M_j| = |[e1 e2]^T (E_j + W_j) q|, E_j and W_j the two 2 x m maps. The root's turning
// moment is the horizontal part (x, y) of the moment about the root node. The nodal moments of K u (the
// rotational rows) are left out: they are the consistent load's O(L_e^2) part of each element's own load,
// which cancels pairwise between neighbours under a uniform load and with it the statics of the nodal forces
// is exact (w (L - x)^2 / 2 on a cantilever); kept, they would add w L_e^2 / 12 at every section.
//
// Scaling (ModalBasis::scaled: K_s Phi_s = s^1/2 D^-1 K Phi, node shapes s^-3/2 Phi, masses s^3, lengths s):
// for the instance of scale s and its own q, E scales as s^1/2 and W as s^3/2; heights and diameters as s,
// the stem's volume as s^3.
#pragma once

#include <Eigen/Core>

#include <span>
#include <vector>

#include "trees/BeamModel.hpp"
#include "trees/Gravity.hpp"
#include "trees/ModalBasis.hpp"
#include "trees/Skeleton.hpp"

namespace fw::trees {

/// A stem section: the node it lies at, how high and how thick.
struct StemSection {
  int node = 0;           ///< skeleton node
  double height = 0.0;    ///< m, above the root (z difference)
  double diameter = 0.0;  ///< m, twice the node's radius
};

class StemLoads {
 public:
  /// The stem of `skeleton` and its maps from `modes` (of `model`, which `skeleton` made). Throws
  /// std::invalid_argument("StemLoads: ...") when the modes do not fit the model or the root has no child.
  static StemLoads compute(const Skeleton& skeleton, const BeamModel& model, const ModalBasis& modes,
                           double gravity = kGravity);
  /// Rebuilds stored maps (the basis cache): profile P >= 2 entries (every stem node, the top included:
  /// heights, diameters, distances along the stem), the J sections' indices into it (increasing, from 0,
  /// below P - 1), maps 2J x m, root maps 2 x m. Throws std::invalid_argument("StemLoads: ...") for sizes
  /// or indices that do not fit or non-finite values.
  static StemLoads from_values(std::vector<StemSection> profile, Eigen::VectorXd arc_length,
                               std::vector<int> section_indices, Eigen::MatrixXd elastic,
                               Eigen::MatrixXd weight, Eigen::MatrixXd root_elastic,
                               Eigen::MatrixXd root_weight);

  StemLoads() = default;

  int section_count() const { return int(elastic_.rows() / 2); }
  int mode_count() const { return int(elastic_.cols()); }
  /// The sections, root first (section_count() entries).
  std::vector<StemSection> sections() const;
  /// Each section's index into profile() (stem_section_indices).
  const std::vector<int>& section_indices() const { return section_indices_; }
  /// Values at the sections (section_count() of them) carried to every stem node (profile()'s order):
  /// linear in the distance along the stem between two sections, the last section's above it. For drawing
  /// a stem whose every node shows a checked section's figure. Throws std::invalid_argument for a count
  /// that is not section_count().
  std::vector<float> along_stem(std::span<const float> at_sections) const;
  /// Every stem node, the top included, root first, and its distance along the stem from the root (m).
  const std::vector<StemSection>& profile() const { return profile_; }
  const Eigen::VectorXd& arc_length() const { return arc_length_; }

  /// E: rows 2j, 2j+1 the elastic bending moment at section j on its (e1, e2), N m per unit q; 2J x m.
  const Eigen::MatrixXd& elastic() const { return elastic_; }
  /// W: the weight's moment on the deflection, the same layout.
  const Eigen::MatrixXd& weight() const { return weight_; }
  /// The root's turning moment about the horizontal axes (x, y), elastic and weight parts, 2 x m each.
  const Eigen::MatrixXd& root_elastic() const { return root_elastic_; }
  const Eigen::MatrixXd& root_weight() const { return root_weight_; }

  /// |M_j| at every section for the modal coordinates q (mode_count() entries), N m.
  Eigen::VectorXd bending_moments(const Eigen::VectorXd& q) const;
  /// |horizontal part of the moment about the root|, N m.
  double root_moment(const Eigen::VectorXd& q) const;

  /// The tree's height (the top of the stem above the root), m.
  double height() const { return profile_.empty() ? 0.0 : profile_.back().height; }
  /// The stem's diameter at `height` above the root (m), interpolated linearly between stem nodes by
  /// height; the root's below the first node above the root, the top's above the top.
  double diameter_at(double height) const;
  /// The diameter at breast height, 1.3 m above the root (kBreastHeight).
  static constexpr double kBreastHeight = 1.3;
  double breast_height_diameter() const { return diameter_at(kBreastHeight); }
  /// The stem's volume, m^3: the frustums between consecutive stem nodes.
  double stem_volume() const;

  /// The stem of the same tree grown by s (finite, > 0), for its own modal coordinates (see the header).
  StemLoads scaled(double s) const;

 private:
  std::vector<StemSection> profile_;
  Eigen::VectorXd arc_length_;
  std::vector<int> section_indices_;
  Eigen::MatrixXd elastic_, weight_, root_elastic_, root_weight_;
};

/// The stem's nodes, root first (see StemLoads). Throws std::invalid_argument("StemLoads: ...") for a
/// skeleton whose root has no child.
std::vector<int> stem_path(const Skeleton& skeleton);

/// The most sections a stem keeps: with the root's lane, one FW_LANES-wide block (kernels/lanes.cl).
inline constexpr int kMaxStemSections = 15;

/// Each node's distance from the root along `path` (stem_path's), m.
Eigen::VectorXd stem_arc_length(const Skeleton& skeleton, const std::vector<int>& path);

/// The sections of a stem whose nodes lie at `arc_length` (root first, the top last; at least 2 nodes), as
/// indices into it: every node but the top when there are at most kMaxStemSections of them, else the node
/// nearest to each of k L / kMaxStemSections, k = 0 .. kMaxStemSections - 1 (L the stem's length), the top
/// left out and repeats taken once. Always the root (index 0), increasing.
std::vector<int> stem_section_indices(const Eigen::VectorXd& arc_length);

/// The statics behind StemLoads' elastic map: the moment about each node of `sections` of the forces on its
/// descendants, sum_k (x_k - x_j) x F_k. forces: (3 n) x c, node-major (rows 3k..3k+2 node k's force, N),
/// c load cases; returns (3 J) x c, rows 3j..3j+2 section j's moment (N m), skeleton frame.
Eigen::MatrixXd section_moments_of_forces(const Skeleton& skeleton, const std::vector<int>& sections,
                                          const Eigen::MatrixXd& forces);

/// The weight's moment behind StemLoads' weight map: sum over the descendants k of section j of
/// (u_k - u_j) x (0, 0, -m_k g). masses: n lumped node masses (kg); displacements: (3 n) x c, node-major
/// (m); returns (3 J) x c (N m).
Eigen::MatrixXd section_moments_of_weight(const Skeleton& skeleton, const std::vector<int>& sections,
                                          const Eigen::VectorXd& masses, const Eigen::MatrixXd& displacements,
                                          double gravity = kGravity);

/// Each node's lumped mass, kg: half of rho pi r_e^2 L_e of every element it ends, r_e the element's radius
/// (the mean of its nodes', as in BeamModel).
Eigen::VectorXd lumped_node_masses(const Skeleton& skeleton, double density);

}  // namespace fw::trees
