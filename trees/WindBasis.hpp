// The wind projection basis of one tree (docs/design.md, "Numerics: Trees: Wind basis"; Diener 2008,
// section 4): precomputed vectors p_i^s that turn wind velocities sampled at a few points of the tree into
// modal forces.
//
//   fw::trees::BeamModel model(skeleton, wood);
//   Eigen::MatrixXd shapes = ...;                               // model.dof_count() x m, M-normalised modes
//   fw::trees::WindBasisSettings settings;
//   settings.samples = 3;                                       // three height bands
//   auto basis = fw::trees::WindBasis::compute(skeleton, model, shapes, settings);
//   Eigen::MatrixX3d wind(3, 3);                                // one row per sample point, m/s
//   for (int s = 0; s < 3; ++s) wind.row(s) = sample_wind(basis.sample_points().row(s));
//   Eigen::VectorXd f = basis.modal_forces(wind);               // f_i = sum_s |v_s| v_s . p_i^s
//   Eigen::MatrixXd G = fw::trees::WindBasis::load_operator(skeleton, settings);   // (6 n) x (3 S)
//   Eigen::VectorXd F = G * fw::trees::WindBasis::squared_wind(wind);              // nodal loads, N, N m
//   auto big = basis.scaled(1.3);                               // the same species, 1.3 times as large
//
// The drag convention (docs/design.md, "Coupling"; the same on the air's side, trees/CanopyDrag.hpp): the
// drag on an area A (m^2) in wind v is F = 1/2 rho_air C_D A |v| v, for both parts of a tree:
//   - wood: element e (nodes a, b) has frontal area D_e L_e, with D_e = r_a + r_b (twice the mean node
//     radius, constant along the element as in the stiffness) and C_D = branch_drag_coefficient C_Db;
//   - foliage: one-sided leaf area lambda_e per metre of element (trees/Foliage.hpp: LAI x crown hull, shared
//     along the leaf-bearing elements) with C_D = leaf_drag_coefficient C_Df; it acts on the whole wind
//     vector, never normal-projected.
// Per unit length, element e so carries the force f(s) = A_e |v| v (N/m) with the symmetric 3x3
//   A_e = 1/2 rho_air (C_Db D_e P_e + C_Df lambda_e I),   P_e = I, or I - x_e x_e^T with branch_normal_drag
// (x_e the element axis). With branch_normal_drag on, the air (which the canopy field slows by the whole
// wind, F = 1/2 rho C_D A |u| u) and the trees balance only for the foliage and for wind normal to the
// branches.
//
// The math. Element e (length L_e, local frame R_e = element_frame(a, b)) displaces along its length as
// u(s) = R_e^T N_e(s) T_e u^e, N_e the 3x12 translational rows of the shape functions
// (integrated_shape_functions below), T_e = diag(R_e, R_e, R_e, R_e) and u^e the element's 12 global DOFs.
// The work of a wind uniform over the element, int f . u ds, is u^e . G_e |v| v with the consistent nodal
// load operator
//   G_e = T_e^T (int N_e ds)^T R_e A_e     (12 x 3, m^2 kg/m^3 = kg/m on translations, kg on rotations).
// Assembled over the elements into the tree's load operator G (6n x 3, node-major, the root included), the
// nodal load vector of a uniform wind is F = G |v| v (N on translations, N m on rotations). The translational
// rows of int N_e ds sum to the integrated length (l1 + l2 = h1 + h3 = s1 - s0: the shape functions are a
// partition of unity), so the sum of the translational nodal loads is the total drag force on the tree,
// sum_e A_e L_e |v| v, the root's share included. The modal force of mode i (column phi_i of `shapes`,
// free-DOF numbering of BeamModel, the root clamped to 0) is f_i = phi_i . F = |v| v . p_i with
//   p_i = G_free^T phi_i,   G_free the rows of G of the model's free DOFs,
// computed through the very same G so that the modal forces and the total drag come from the same code.
// Options:
//   - samples = S: the height range [z_root, z_top] (the root's z to the highest node's z) is split into S
//     equal bands. Band s integrates only the parts of the elements whose height lies in it (elements are
//     split where they cross a band border; parts below the root count to band 0): G = [G_0 .. G_{S-1}],
//     F = sum_s G_s |v_s| v_s, f_i = sum_s |v_s| v_s . p_i^s with p_i^s = G_s,free^T phi_i, and the bands'
//     p_i^s add up to the S = 1 basis. The sample point of band s, where the wind is to be sampled, is the
//     drag-weighted centroid int w x ds / int w ds of the branch length in it, with the drag width
//     w_e = C_Db D_e + C_Df lambda_e (m) of the load (the diameter D_e when every drag coefficient is 0). A
//     band with no branch length (only possible when all nodes lie at the root's height) has p = 0 and the
//     whole tree's centroid as its sample point.
//
// Units: wind in m/s; rho_air in kg/m^3; sample points in m, skeleton frame. p has the units of
// kg/m^3 m^2 times those of the shapes' translational entries: for M-normalised modes (kg^-1/2) p is in
// kg^1/2 / m and f_i in N / kg^1/2, the generalised force of a modal coordinate q_i in kg^1/2 m.
//
// Instances: a geometrically similar tree, skeleton.transformed(I, 0, s), of the same material has mode
// shapes s^-5/2 D phi (D = s on translational DOFs, 1 on rotations; strain energy scales as s^3, kinetic as
// s^5), frequencies omega / s, projections s^1/2 p and sample points s x. scaled(s) applies this; it holds
// with foliage too, because lambda_e scales as s like D_e (Foliage.hpp).
#pragma once

#include <Eigen/Dense>

#include <vector>

#include "trees/Foliage.hpp"

namespace fw::trees {

class Skeleton;
class BeamModel;

/// int_{s0}^{s1} N(s) ds in the element's local frame: the 3x12 integral of the translational rows of the
/// shape-function matrix of an element of length L, over the part s0 <= s <= s1 (m from node a). Columns are
/// the local DOFs (BeamElement.hpp order); rows are local ux, uy, uz. With t = s / L:
///   ux = (1 - t) ux_a + t ux_b,
///   uy = h1 uy_a + h2 rz_a + h3 uy_b + h4 rz_b,   uz = h1 uz_a - h2 ry_a + h3 uz_b - h4 ry_b,
///   h1 = 1 - 3t^2 + 2t^3, h2 = L (t - 2t^2 + t^3), h3 = 3t^2 - 2t^3, h4 = L (t^3 - t^2),
/// the signs following rz = +uy', ry = -uz'. Over the whole element the Hermite integrals are L/2, L^2/12,
/// L/2, -L^2/12 (Stam's B matrix, transposed). Units: m for displacement columns, m^2 for rotation columns.
/// Throws std::invalid_argument("WindBasis: ...") unless L is finite and positive and 0 <= s0 <= s1 <= L.
Eigen::Matrix<double, 3, 12> integrated_shape_functions(double length, double s0, double s1);

struct WindBasisSettings {
  /// Named defaults of the drag convention (header comment).
  static constexpr double kAirDensity = 1.225;             ///< kg/m^3, sea level, 15 C
  static constexpr double kCylinderDragCoefficient = 1.2;  ///< a circular cylinder in cross flow
  /// 1/2 C_D = 0.2, the canopy drag coefficient C_d of canopy LES in the form F = C_d a |u| u
  /// (Shaw & Schumann 1992).
  static constexpr double kFoliageDragCoefficient = 0.4;

  double air_density = kAirDensity;                           ///< rho_air, kg/m^3; finite, >= 0
  double branch_drag_coefficient = kCylinderDragCoefficient;  ///< C_Db of the wood, per frontal area D x L
  double leaf_area_index = 0.0;  ///< one-sided leaf area / crown hull area (Foliage.hpp); 0 = no foliage
  double leaf_drag_coefficient = kFoliageDragCoefficient;  ///< C_Df of the foliage, per one-sided leaf area
  /// Drag from the wind component normal to each branch only (P_e v) instead of the whole wind (Diener).
  /// Applies to the wood only; the foliage always drags with the whole wind. With it on, the trees' load
  /// balances the air's loss only for the foliage and for wind normal to the branches.
  bool branch_normal_drag = false;
  /// Number S of height bands, each with its own sample point and projection vectors; >= 1.
  int samples = 1;

  /// Throws std::invalid_argument("WindBasisSettings: ...") naming the first bad value: air_density,
  /// branch_drag_coefficient, leaf_area_index, leaf_drag_coefficient (each must be finite and >= 0; all
  /// zero switches the wind load off) or samples (>= 1).
  void validate() const;
};

/// What drags on each element of a skeleton (skeleton.elements() order), the one definition both sides of
/// the coupling use (WindBasis for the trees, trees/CanopyDrag for the air): the force per metre of element
/// is 1/2 rho_air (C_Db D_e [P_e] + C_Df lambda_e) |v| v.
struct ElementDrag {
  Foliage foliage;               ///< leaf-bearing elements, lambda_e, crown and leaf area
  std::vector<double> diameter;  ///< D_e = r_a + r_b (twice the mean node radius, as in the stiffness), m
  /// w_e = C_Db D_e + C_Df lambda_e, m: the drag area per metre of element (without the normal projection).
  std::vector<double> drag_width;

  /// Throws std::invalid_argument("WindBasisSettings: ...") for invalid settings.
  static ElementDrag of(const Skeleton& skeleton, const WindBasisSettings& settings);
};

class WindBasis {
 public:
  /// The basis of a tree with its modes: p_i^s = G_s,free^T phi_i through load_operator(), foliage from
  /// Foliage::of(skeleton, settings.leaf_area_index). shapes: model.dof_count() x m, columns in the model's
  /// free-DOF numbering. Throws std::invalid_argument("WindBasis: ...") for a size mismatch (shapes' rows,
  /// the model's node count against the skeleton's), non-finite shapes, or invalid settings.
  static WindBasis compute(const Skeleton& skeleton, const BeamModel& model, const Eigen::MatrixXd& shapes,
                           const WindBasisSettings& settings);

  /// Rebuilds a basis from stored values (the disk cache): projection is (3 S) x m, sample_points S x 3,
  /// with S = settings.samples. Throws std::invalid_argument("WindBasis: ...") for other sizes, non-finite
  /// values or invalid settings.
  static WindBasis from_values(Eigen::MatrixXd projection, Eigen::MatrixX3d sample_points,
                               WindBasisSettings settings);

  /// The consistent nodal load operator G = [G_0 .. G_{S-1}] of the tree (header comment): (6 n) x (3 S),
  /// rows 6 k + j for node k's global DOF j (ux, uy, uz, rx, ry, rz; the root's rows hold the load the clamp
  /// takes directly), columns 3 s + c for component c of |v_s| v_s. The nodal loads of the winds v_s are
  /// F = G * squared_wind(v) (N, N m); the sum of the translational rows is the total drag force. Units:
  /// kg/m on translational rows, kg on rotational rows. Throws std::invalid_argument("WindBasis: ...") for
  /// invalid settings or a skeleton without elements.
  static Eigen::MatrixXd load_operator(const Skeleton& skeleton, const WindBasisSettings& settings);

  /// The 3 S vector w with w.segment<3>(3 s) = |v_s| v_s, m^2/s^2, for the winds of the samples (S x 3, m/s).
  static Eigen::VectorXd squared_wind(const Eigen::MatrixX3d& wind);

  WindBasis() = default;  ///< empty (no samples, no modes); only useful as a placeholder to assign to

  /// Number of wind samples S.
  int sample_count() const { return int(sample_points_.rows()); }
  /// Number of modes m.
  int mode_count() const { return int(projection_.cols()); }

  /// p_i^s, the projection vector of mode i for sample s (units above). Throws std::out_of_range.
  Eigen::Vector3d projection(int sample, int mode) const;
  /// (3 S) x m; rows 3s .. 3s+2 are p^s (x, y, z), one column per mode.
  const Eigen::MatrixXd& projection_matrix() const { return projection_; }
  /// S x 3, m, skeleton frame: where to sample the wind for each band.
  const Eigen::MatrixX3d& sample_points() const { return sample_points_; }
  const WindBasisSettings& settings() const { return settings_; }

  /// Modal forces f_i = sum_s |v_s| v_s . p_i^s for the wind velocities at the sample points (S x 3, m/s,
  /// row s for sample s). Returns the m-vector f. Throws std::invalid_argument("WindBasis: ...") unless wind
  /// has S rows.
  Eigen::VectorXd modal_forces(const Eigen::MatrixX3d& wind) const;

  /// The basis of the same tree scaled by s about the skeleton origin (same material and settings):
  /// projections times s^1/2, sample points times s. Throws std::invalid_argument("WindBasis: ...") unless s
  /// is finite and positive.
  WindBasis scaled(double s) const;

 private:
  Eigen::MatrixXd projection_;
  Eigen::MatrixX3d sample_points_;
  WindBasisSettings settings_;
};

}  // namespace fw::trees
