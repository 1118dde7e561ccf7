// Diener 2008, section 5.2 (docs/design.md, "Numerics: Trees", "Strong wind"): the strong-wind correction of
// the linear modal displacement, which keeps branch lengths constant under strong wind. Two parts:
//   1. Diener's fitted quadratic correction (per node, parallel): u = sum_i q~_i v_i + q~_i^2 w_i, close to
//      length-keeping already;
//   2. followed by a projection that restores each element's rest length exactly (sequential along each
//      tree, output frames only): the walk below (corrected_deformation) applied to Diener's pose.
//
//   fw::trees::StrongWindSettings settings;               // 2 K + 1 = 17 amplitudes up to 0.5 of the tree
//   auto correction = fw::trees::StrongWindCorrection::fit(skeleton, species.node_shapes(), settings);
//   Eigen::VectorXd u = correction.corrected_displacement(skeleton, q);  // (3 n): parts 1 and 2, as shown
//   Eigen::VectorXd u_diener = correction.displacement(q);  // (3 n): part 1, sum_i q~_i v_i + q~_i^2 w_i
//   Eigen::VectorXd u_lin = species.node_shapes() * q;      // what it corrects
//   correction.fits()[i].relative_residual;              // how well mode i's trajectories were matched
//   auto big = correction.scaled(1.2);                   // the correction of species.scaled(1.2)
//
// Model (Diener eqs. 16-17): u = sum_i q~_i v_i + q~_i^2 w_i, q~_i = a_i arctan(b_i q_i), with node vectors
// v_i, w_i in the layout of SpeciesBasis::node_shapes() ((3 n) x m: rows 3k..3k+2 are node k's x y z, the
// root's rows zero) and per-mode scalars a_i = 1 / b_i (so q~ = q - b^2 q^3 / 3 + ...: to first order
// u = sum_i q_i v_i) and b_i >= 0 (b_i = 0 stands for q~ = q). Units: q in kg^1/2 m (M-normalised modes),
// b in 1 / (kg^1/2 m), v in m / (kg^1/2 m) like phi, w in m / (kg m^2).
//
// The fit, mode by mode:
//   - the corrected deformation of mode i at amplitude q walks the skeleton from the root (parents before
//     children): node c of element (p, c) sits at x'_c = x'_p + L_e unit((x_c + q phi_c) - (x_p + q phi_p)),
//     x'_root = x_root, L_e the rest length. Every element keeps its rest length exactly and points where the
//     linear pose points, so the pose follows the linear one at small q (up to the modes' own tiny axial
//     strain);
//   - amplitudes q_k = q_max k / K, k = -K..K, q_max the smaller of two bounds: the largest linear node
//     displacement q_max max_node |phi_i| reaches `reach` times the tree's size (the largest distance of a
//     node from the root: the height of an upright tree), or the steepest element of the linear pose turns by
//     `max_slope` (its displacement normal to itself over its length). reach = 0.5: a crown top swept through
//     half the tree's height is past what a tree survives, so a storm's sway stays inside the fitted range.
//     max_slope = 0.6 (31 degrees) sizes the higher, local modes, whose twigs the height bound alone would
//     fold over: fitted over such a range their least-squares v drifts from phi (by up to 60% on the test
//     trees, under 5% with the bound), which would change the everyday small motion. Past q_max the arctan
//     saturates at q~ = pi / (2 b), so extrapolation stays bounded;
//   - v_i, w_i per node by linear least squares over the 2 K + 1 samples of d_k = x'(q_k) - x for a given
//     b: the samples are symmetric in q, q~ is odd and q~^2 even, so the normal equations decouple into
//     v = sum q~_k d_k / sum q~_k^2 and w = sum q~_k^2 d_k / sum q~_k^4;
//   - b_i by a 1D search of beta = b q_max on [0, beta_max] minimising the residual summed over all nodes: a
//     uniform grid of `search_points`, then golden-section refinement in the best grid cell. With the
//     samples' Gram matrices (K x K, odd and even parts) computed once, a trial b costs O(K^2), not O(n K).
//
// v is the least-squares fit, not phi, so small motion is q v: q~ = q to first order, but v differs from phi
// by a few percent (StrongWindModeFit::shape_change). Fixing v = phi instead makes small
// motion exact but, with one b per mode, cannot give each node its own cubic foreshortening: under a load in
// the shape of the first mode that bends the tip by 30% of the tree's height it left 1.8-4% element stretch
// (measured while choosing, with the height bound alone) against 0.1-0.5% with v fitted.
//
// Why the length-restoring pass (part 2): the length-keeping pose of a mix of modes has cross terms q_i q_j
// (an element turned by mode i foreshortens along mode j's turn too) that no sum of per-mode terms holds.
// One mode at a time, Diener's part keeps lengths within 0.5% at a 30% tip deflection (linear: 12-15%);
// under a static uniform wind, whose response mixes the sway modes with some of the higher bending modes, it
// leaves 1-2% stretch on a cantilever and 3-5% on a broadleaf crown (linear: 11-13%). The pass walks the
// skeleton from the root, parents before children, and puts each node at its parent's corrected position
// plus the rest element length times the unit vector of Diener's element (node minus parent, both Diener's):
// lengths are then exact to rounding, and since Diener's pose nearly keeps lengths already, the pass moves
// nodes little and the pose stays Diener's (tests/trees/StrongWindCorrection_test.cpp). It is the same walk
// as the fit's, applied to Diener's pose instead of a linear one: a node depends on all of its ancestors, so
// on the device a tree is never split between work-items (kernels/tree_deform.cl, tree_deform_strong, which
// does both parts in one walk), a cost paid only on output frames. Like part 1 it commutes with the
// instances' scaling and yaw (lengths scale by s, unit vectors turn by R), so an instance's corrected pose is
// s R times the species'.
//
// Instances (trees/Forest.hpp): the tree grown by s (modes s^-5/2 D phi, so translations s^-3/2 phi) at
// modal coordinate q_s has the linear displacement s (s^-5/2 q_s) phi, i.e. s times the species' at
// q = s^-5/2 q_s. The corrected deformation is equivariant under scaling, so the grown tree's corrected
// displacement is s times the species' at that q:
//   u_s(q_s) = s sum_i (q~_i v_i + q~_i^2 w_i),   q~_i = arctan(b_i s^-5/2 q_s,i) / b_i,
// which is the correction with v_s = s^-3/2 v, w_s = s^-4 w, b_s = s^-5/2 b in the grown tree's own q
// (scaled()); a fresh fit on the grown tree gives the same (its samples map one to one). Yaw turns u by R.
#pragma once

#include <Eigen/Core>

#include <vector>

#include "trees/Skeleton.hpp"

namespace fw::trees {

struct StrongWindSettings {
  int samples_per_side = 8;  ///< K: the fit samples q = q_max k / K, k = -K..K (2 K + 1 amplitudes), >= 2
  double reach = 0.5;        ///< largest linear node displacement sampled, times the tree's size, > 0
  double max_slope = 0.6;    ///< largest sampled turn of an element, |normal displacement| / length, > 0
  int search_points = 201;   ///< trial values of beta = b q_max on [0, beta_max] before refinement, >= 3
  double beta_max = 4.0;     ///< the search range of b q_max: arctan(4) / 4 = 0.33, far past any fit, > 0

  /// Throws std::invalid_argument("StrongWindSettings: ...") for values outside the ranges above.
  void validate() const;
};

/// How the fit of one mode went.
struct StrongWindModeFit {
  double q_max = 0.0;  ///< the largest sampled |q|, kg^1/2 m (0 for a mode without translations)
  /// sqrt(sum over samples and nodes |d_k - q~_k v - q~_k^2 w|^2 / sum |d_k|^2): the corrected
  /// trajectories the model misses, relative to their size.
  double relative_residual = 0.0;
  /// The same for the linear model d_k = q_k phi: what the correction improves on.
  double linear_relative_residual = 0.0;
  /// |v - phi| / |phi| over all nodes: how much the fit changes small motion (0 without translations).
  double shape_change = 0.0;
};

class StrongWindCorrection {
 public:
  StrongWindCorrection() = default;  ///< no modes, no nodes

  /// Fits the correction of every column of node_shapes ((3 n) x m, n = skeleton.size(), the layout above).
  /// Throws std::invalid_argument("StrongWindCorrection: ...") for mismatched sizes or non-finite shapes,
  /// and what settings.validate() throws.
  static StrongWindCorrection fit(const Skeleton& skeleton, const Eigen::MatrixXd& node_shapes,
                                  const StrongWindSettings& settings = {});

  /// Rebuilds a correction from stored values (the disk cache): v, w (3 n) x m, b m values >= 0, fits m
  /// entries. Throws std::invalid_argument("StrongWindCorrection: ...") for mismatched sizes, non-finite
  /// values or a negative b.
  static StrongWindCorrection from_values(Eigen::MatrixXd v, Eigen::MatrixXd w, Eigen::VectorXd b,
                                          std::vector<StrongWindModeFit> fits);

  /// The length-keeping pose of the walk above for any displacement (3 n, root rows ignored: a linear one
  /// in the fit, Diener's in the length-restoring pass), as a displacement from the rest positions (3 n). An
  /// element whose image has collapsed to under Skeleton::kMinElementLength keeps its rest direction. Throws
  /// std::invalid_argument for a wrong size.
  static Eigen::VectorXd corrected_deformation(const Skeleton& skeleton, const Eigen::VectorXd& linear);

  /// q~ = arctan(b q) / b, and q itself for b = 0.
  static double reparametrised(double q, double b);

  int mode_count() const { return int(b_.size()); }
  int node_count() const { return int(v_.rows() / 3); }

  const Eigen::MatrixXd& linear_shapes() const { return v_; }     ///< v, (3 n) x m
  const Eigen::MatrixXd& quadratic_shapes() const { return w_; }  ///< w, (3 n) x m
  const Eigen::VectorXd& b() const { return b_; }                 ///< b_i, 1 / (kg^1/2 m)
  const std::vector<StrongWindModeFit>& fits() const { return fits_; }

  /// Diener's part alone, u = sum_i q~_i v_i + q~_i^2 w_i for q (m values): 3 n, m, skeleton frame. Throws
  /// std::invalid_argument for a wrong size.
  Eigen::VectorXd displacement(const Eigen::VectorXd& q) const;

  /// The whole correction: Diener's part followed by the length-restoring pass,
  /// corrected_deformation(skeleton, displacement(q)), 3 n, m, skeleton frame: every element keeps its rest
  /// length. `skeleton` is the one the correction was fitted on (node_count() nodes). Throws
  /// std::invalid_argument for a wrong size.
  Eigen::VectorXd corrected_displacement(const Skeleton& skeleton, const Eigen::VectorXd& q) const;

  /// The correction of the tree grown by s (finite, > 0; see the header comment), in its own modal
  /// coordinates. Throws std::invalid_argument.
  StrongWindCorrection scaled(double s) const;

 private:
  Eigen::MatrixXd v_, w_;
  Eigen::VectorXd b_;
  std::vector<StrongWindModeFit> fits_;
};

}  // namespace fw::trees
