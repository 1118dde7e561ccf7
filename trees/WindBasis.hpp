// The wind projection basis of one tree (DESIGN.md, "Numerics: Trees: Wind basis"; Diener 2008, section 4):
// precomputed vectors p_i^s that turn wind velocities sampled at a few points of the tree into modal forces.
//
//   fw::trees::BeamModel model(skeleton, wood);
//   Eigen::MatrixXd shapes = ...;                               // model.dof_count() x m, M-normalised modes
//   fw::trees::WindBasisSettings settings;
//   settings.samples = 3;                                       // three height bands
//   auto basis = fw::trees::WindBasis::compute(skeleton, model, shapes, settings);
//   Eigen::MatrixX3d wind(3, 3);                                // one row per sample point, m/s
//   for (int s = 0; s < 3; ++s) wind.row(s) = sample_wind(basis.sample_points().row(s));
//   Eigen::VectorXd f = basis.modal_forces(wind);               // f_i = sum_s |v_s| v_s . p_i^s
//   auto big = basis.scaled(1.3);                               // the same species, 1.3 times as large
//
// The math. Each element e (nodes a, b, length L_e, local frame R_e = element_frame(a, b), diameter
// D_e = 2 r_e with r_e the mean of its node radii) carries Diener's mean aerodynamic stress per unit length
// f(s) = C D_e |v| v. Its work on mode i (column phi_i of `shapes`, free-DOF numbering of BeamModel, the root
// clamped to 0) is f_i = sum_e int f . phi_i(s) ds, with the global displacement along the element
// phi_i(s) = R_e^T N_e(s) T_e phi_i^e, N_e the 3x12 translational rows of the shape functions
// (integrated_shape_functions below) and T_e = diag(R_e, R_e, R_e, R_e). With v uniform over the element
// p_i = C sum_e D_e R_e^T (int N_e ds) T_e phi_i^e   and   f_i = |v| v . p_i.
// Options:
//   - branch_normal_drag: only the wind component normal to the branch drags, f = C D_e |v| P_e v with
//     P_e = I - x_e x_e^T (x_e the element axis); P_e is symmetric, so it folds into p_i.
//   - samples = S: the height range [z_root, z_top] (the root's z to the highest node's z) is split into S
//     equal bands. Band s integrates only the parts of the elements whose height lies in it (elements are
//     split where they cross a band border; parts below the root count to band 0), so
//     f_i = sum_s |v_s| v_s . p_i^s and the bands' p_i^s add up to the S = 1 basis. The sample point of band
//     s, where the wind is to be sampled, is the diameter-weighted centroid of the branch length in it,
//     int D x ds / int D ds. A band with no branch length (only possible when all nodes lie at the root's
//     height) has p = 0 and the whole tree's centroid as its sample point.
//
// Units: wind in m/s; C (drag_factor) in kg/m^3; sample points in m, skeleton frame. p has the units of
// C m^2 times those of the shapes' translational entries: for M-normalised modes (kg^-1/2) p is in
// kg^1/2 / m and f_i in N / kg^1/2, the generalised force of a modal coordinate q_i in kg^1/2 m.
//
// Instances: a geometrically similar tree, skeleton.transformed(I, 0, s), of the same material has mode
// shapes s^-5/2 D phi (D = s on translational DOFs, 1 on rotations; strain energy scales as s^3, kinetic as
// s^5), frequencies omega / s, projections s^1/2 p and sample points s x. scaled(s) applies this.
#pragma once

#include <Eigen/Dense>

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
  /// C = 1/2 rho_air C_D, kg/m^3: air density 1.225 kg/m^3 and drag coefficient 1.2 of a cylinder in
  /// cross flow. Finite and >= 0 (0 switches the wind load off).
  double drag_factor = 0.5 * 1.225 * 1.2;
  /// Drag from the wind component normal to each branch only (P_e v) instead of the whole wind (Diener).
  bool branch_normal_drag = false;
  /// Number S of height bands, each with its own sample point and projection vectors; >= 1.
  int samples = 1;

  /// Throws std::invalid_argument("WindBasisSettings: ...") naming the first bad value.
  void validate() const;
};

class WindBasis {
 public:
  /// The basis of a tree with its modes. shapes: model.dof_count() x m, columns in the model's free-DOF
  /// numbering. Throws std::invalid_argument("WindBasis: ...") for a size mismatch (shapes' rows, the
  /// model's node count against the skeleton's), non-finite shapes, or invalid settings.
  static WindBasis compute(const Skeleton& skeleton, const BeamModel& model, const Eigen::MatrixXd& shapes,
                           const WindBasisSettings& settings);

  /// Rebuilds a basis from stored values (the disk cache): projection is (3 S) x m, sample_points S x 3,
  /// with S = settings.samples. Throws std::invalid_argument("WindBasis: ...") for other sizes, non-finite
  /// values or invalid settings.
  static WindBasis from_values(Eigen::MatrixXd projection, Eigen::MatrixX3d sample_points,
                               WindBasisSettings settings);

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
