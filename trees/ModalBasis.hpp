// The lowest vibration modes of a tree's FEM model (docs/design.md, "Numerics: Trees", "Modes").
//
//   fw::trees::BeamModel model(skeleton, wood);
//   fw::trees::ModalSettings settings;
//   settings.mode_count = 25;
//   settings.damping = fw::trees::Damping::modal_ratio(0.05);
//   auto modes = fw::trees::ModalBasis::compute(model, settings);   // throws ModalError if m cannot converge
//   modes.frequencies_hz();          // m values, ascending
//   modes.shapes().col(i);           // phi_i, model.dof_count() entries, M-normalised
//   modes.status().iterations;       // Lanczos restarts used; .converged, .max_residual, ...
//   auto big = modes.scaled(1.2);    // the same species grown 20% larger: omega / 1.2
//
// Math: the generalized symmetric eigenproblem K phi = omega^2 M phi on the free (root-clamped) DOFs of
// BeamModel, K and M sparse symmetric positive definite. The m eigenpairs with the smallest omega^2 come from
// Spectra's shift-invert Lanczos (SymGEigsShiftSolver, GEigsMode::ShiftInvert) about a shift sigma < 0: each
// operation solves (K - sigma M) y = x with a sparse LDL^T factorisation, which for a tree-shaped mesh has
// almost no fill-in, so a 30k-node tree factorises in well under a second. Problems too small for a Lanczos
// basis of 2m+1 vectors are solved densely instead (status().method says which).
//
// Normalisation: phi_i^T M phi_i = 1, so modal mass is 1 (kg m^2 units folded into phi) and modal stiffness
// is omega_i^2. Each mode's sign is fixed so that its largest-magnitude entry is positive, which makes the
// basis deterministic. The modal equation is q_i'' + gamma_i q_i' + omega_i^2 q_i = f_i with f_i = phi_i^T f.
//
// Damping: a damping ratio per mode (gamma_i = 2 zeta_i omega_i) or Rayleigh damping C = alpha M + beta K
// (gamma_i = alpha + beta omega_i^2, Diener eq. 9).
//
// Instance scale (docs/design.md, "Instances"): the tree skeleton.transformed(I, 0, s) of the same material
// has K_s = s^3 D^-1 K D^-1 and M_s = s^5 D^-1 M D^-1, D = diag(s on translations, 1 on rotations), because
// strain energy scales as s^3 and kinetic energy as s^5 for a geometrically similar displacement field. Hence
// omega_s = omega / s and phi_s = s^(-5/2) D phi (M_s-normalised). scaled(s) applies exactly that.
#pragma once

#include <Eigen/Core>

#include <stdexcept>
#include <string>
#include <vector>

namespace fw::trees {

class BeamModel;

/// How each mode dissipates energy.
struct Damping {
  enum class Model { modal_ratio, rayleigh };
  Model model = Model::modal_ratio;
  /// Damping ratios zeta (dimensionless, >= 0), one per mode in ascending frequency; when there are fewer
  /// values than modes the last one applies to the rest. Used by Model::modal_ratio.
  std::vector<double> ratios = {0.05};
  double alpha = 0.0;  ///< Rayleigh mass coefficient, 1/s (Model::rayleigh)
  double beta = 0.0;   ///< Rayleigh stiffness coefficient, s (Model::rayleigh)

  static Damping modal_ratio(double zeta) { return Damping{Model::modal_ratio, {zeta}, 0.0, 0.0}; }
  static Damping rayleigh(double alpha, double beta) { return Damping{Model::rayleigh, {}, alpha, beta}; }

  /// Throws std::invalid_argument("Damping: ...") for a negative or non-finite coefficient or no ratio.
  void validate() const;
  /// gamma_i (1/s) for the given angular frequencies omega_i (rad/s).
  Eigen::VectorXd coefficients(const Eigen::VectorXd& omega) const;
};

struct ModalSettings {
  int mode_count = 20;        ///< m, the number of lowest modes kept, 1 <= m < dof_count
  Damping damping;            ///< per-mode damping
  double tolerance = 1e-10;   ///< Spectra's relative precision on the eigenvalues of the shifted problem
  int max_iterations = 1000;  ///< Lanczos restarts before giving up
  int lanczos_vectors = 0;    ///< ncv, Lanczos basis size; 0 picks max(2m + 1, m + 20), capped at the DOFs
  /// Throws std::invalid_argument("ModalSettings: ...").
  void validate() const;
};

/// What the solve did: enough to tell a slow or marginal solve from a good one.
struct ModalStatus {
  std::string method;  ///< "shift-invert Lanczos (Spectra)" or "dense (Eigen)"
  int requested = 0;   ///< m
  int converged = 0;   ///< eigenpairs that met the tolerance
  int iterations = 0;  ///< Lanczos restarts (0 for dense)
  int operations = 0;  ///< shift-invert solves (0 for dense)
  double shift = 0.0;  ///< sigma, rad^2/s^2
  /// Max over modes of the normwise backward error |K phi - omega^2 M phi| / ((|K| + omega^2 |M|) |phi|),
  /// infinity norms: the relative change of K and M that would make the computed pair exact.
  double max_residual = 0.0;
  double seconds_factorise = 0.0;
  double seconds_solve = 0.0;
};

/// The requested modes did not converge; carries the status for the message and for callers.
class ModalError : public std::runtime_error {
 public:
  ModalError(const std::string& message, ModalStatus status)
      : std::runtime_error(message), status_(std::move(status)) {}
  const ModalStatus& status() const { return status_; }

 private:
  ModalStatus status_;
};

class ModalBasis {
 public:
  /// Solves for the lowest settings.mode_count modes. Throws std::invalid_argument("ModalBasis: ...") for bad
  /// settings or m >= dof_count, and ModalError when fewer than m modes converge within max_iterations.
  static ModalBasis compute(const BeamModel& model, const ModalSettings& settings);

  /// Rebuilds a basis from stored values (the disk cache). omega: m, rad/s ascending; shapes: dofs x m.
  /// Throws std::invalid_argument("ModalBasis: ...") for mismatched sizes or non-finite values.
  static ModalBasis from_values(Eigen::VectorXd omega, Eigen::MatrixXd shapes, Damping damping,
                                ModalStatus status = {});

  int mode_count() const { return int(omega_.size()); }
  int dof_count() const { return int(shapes_.rows()); }

  /// Angular frequencies omega_i, rad/s, ascending (m values).
  const Eigen::VectorXd& omega() const { return omega_; }
  /// Natural frequencies omega_i / 2 pi, Hz.
  Eigen::VectorXd frequencies_hz() const;
  /// gamma_i of q'' + gamma q' + omega^2 q = f, 1/s.
  const Eigen::VectorXd& damping_coefficients() const { return gamma_; }
  /// zeta_i = gamma_i / (2 omega_i), dimensionless.
  Eigen::VectorXd damping_ratios() const;
  const Damping& damping() const { return damping_; }

  /// Mode shapes Phi, dof_count x m, columns M-normalised, in BeamModel's free-DOF numbering.
  const Eigen::MatrixXd& shapes() const { return shapes_; }
  const ModalStatus& status() const { return status_; }

  /// Nodal translations of mode i, #nodes by 3, m per unit modal coordinate; the root's row is zero.
  /// `model` must be the model the basis was computed from (same DOF count, else std::invalid_argument).
  Eigen::MatrixX3d node_displacements(const BeamModel& model, int mode) const;

  /// The basis of the geometrically similar tree scaled by s (finite, > 0) with the same material; see the
  /// header comment. Rayleigh damping is re-evaluated at the new frequencies, damping ratios are kept. Each
  /// mode keeps the sign of its source (so a fresh solve may differ from it by the sign of a whole mode).
  /// Free DOF k is a rotation when k % 6 >= 3 (BeamModel's numbering). Throws std::invalid_argument.
  ModalBasis scaled(double s) const;

 private:
  Eigen::VectorXd omega_;
  Eigen::VectorXd gamma_;
  Eigen::MatrixXd shapes_;
  Damping damping_;
  ModalStatus status_;
};

}  // namespace fw::trees
