#include "trees/ModalBasis.hpp"

#include <Spectra/SymGEigsShiftSolver.h>
#include <fmt/format.h>
#include <Eigen/Eigenvalues>
#include <Eigen/SparseCholesky>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <numbers>
#include <utility>

#include "trees/BeamModel.hpp"

namespace fw::trees {

namespace {

using SparseMatrix = Eigen::SparseMatrix<double>;
using Clock = std::chrono::steady_clock;

double seconds_since(Clock::time_point start) {
  return std::chrono::duration<double>(Clock::now() - start).count();
}

// Spectra's operation y = (K - sigma M)^-1 x, backed by a sparse LDL^T. Spectra's own SymShiftInvert uses a
// sparse LU; LDL^T is the natural choice for a symmetric positive definite K - sigma M (sigma < 0) and needs
// half the memory.
class ShiftInvertLdlt {
 public:
  using Scalar = double;

  ShiftInvertLdlt(const SparseMatrix& stiffness, const SparseMatrix& mass) : k_(stiffness), m_(mass) {}

  Eigen::Index rows() const { return k_.rows(); }
  Eigen::Index cols() const { return k_.cols(); }

  void set_shift(double sigma) {
    const SparseMatrix shifted = k_ - sigma * m_;
    ldlt_.compute(shifted);
    if (ldlt_.info() != Eigen::Success) {
      throw std::runtime_error(
          fmt::format("ModalBasis: the LDL^T factorisation of K - sigma M failed (sigma = {})", sigma));
    }
  }

  void perform_op(const double* x_in, double* y_out) const {
    Eigen::Map<const Eigen::VectorXd> x(x_in, k_.rows());
    Eigen::Map<Eigen::VectorXd> y(y_out, k_.rows());
    y.noalias() = ldlt_.solve(x);
  }

 private:
  const SparseMatrix& k_;
  const SparseMatrix& m_;
  Eigen::SimplicialLDLT<SparseMatrix> ldlt_;
};

// Spectra's operation y = M x. BeamModel stores both triangles of M, so a plain sparse product does;
// Spectra's SparseSymMatProd reads one triangle through a self-adjoint view, which is several times slower,
// and the B-orthogonalisation of the Lanczos vectors calls this a dozen times per step.
class MassProduct {
 public:
  using Scalar = double;

  explicit MassProduct(const SparseMatrix& mass) : m_(mass) {}

  Eigen::Index rows() const { return m_.rows(); }
  Eigen::Index cols() const { return m_.cols(); }

  void perform_op(const double* x_in, double* y_out) const {
    Eigen::Map<const Eigen::VectorXd> x(x_in, m_.cols());
    Eigen::Map<Eigen::VectorXd> y(y_out, m_.rows());
    y.noalias() = m_ * x;
  }

 private:
  const SparseMatrix& m_;
};

// The shift sits below the spectrum, so K - sigma M is positive definite and the modes nearest to it are the
// lowest ones. Its size (1 rad^2/s^2, about 0.16 Hz) only has to keep the factorisation well away from
// singular; the convergence rate depends on it weakly.
constexpr double kShift = -1.0;

// Fixes each column's sign so that its largest-magnitude entry is positive (the first one on a tie).
void fix_signs(Eigen::MatrixXd& shapes) {
  for (Eigen::Index j = 0; j < shapes.cols(); ++j) {
    Eigen::Index largest = 0;
    shapes.col(j).cwiseAbs().maxCoeff(&largest);
    if (shapes(largest, j) < 0.0) shapes.col(j) *= -1.0;
  }
}

void normalise_to_mass(const SparseMatrix& mass, Eigen::MatrixXd& shapes) {
  for (Eigen::Index j = 0; j < shapes.cols(); ++j) {
    const double modal_mass = shapes.col(j).dot(mass * shapes.col(j));
    shapes.col(j) /= std::sqrt(modal_mass);
  }
}

// Largest absolute row sum, the matrix infinity-norm (= 1-norm for a symmetric matrix).
double max_row_sum(const SparseMatrix& matrix) {
  Eigen::VectorXd sums = Eigen::VectorXd::Zero(matrix.rows());
  for (Eigen::Index col = 0; col < matrix.outerSize(); ++col) {
    for (SparseMatrix::InnerIterator it(matrix, col); it; ++it) sums(it.row()) += std::abs(it.value());
  }
  return sums.maxCoeff();
}

// The normwise backward error of each eigenpair, |K phi - omega^2 M phi| / ((|K| + omega^2 |M|) |phi|)
// (infinity norms): the relative perturbation of K and M that makes the pair exact. Unlike |r| / |K phi| it
// does not grow with the stiffness of the shortest, stiffest elements, whose axial terms cancel in K phi.
double max_backward_error(const SparseMatrix& stiffness, const SparseMatrix& mass,
                          const Eigen::VectorXd& omega, const Eigen::MatrixXd& shapes) {
  const double k_norm = max_row_sum(stiffness);
  const double m_norm = max_row_sum(mass);
  double worst = 0.0;
  for (Eigen::Index j = 0; j < shapes.cols(); ++j) {
    const double lambda = omega(j) * omega(j);
    const Eigen::VectorXd residual = stiffness * shapes.col(j) - lambda * (mass * shapes.col(j));
    const double scale = (k_norm + lambda * m_norm) * shapes.col(j).lpNorm<Eigen::Infinity>();
    worst = std::max(worst, residual.lpNorm<Eigen::Infinity>() / scale);
  }
  return worst;
}

void check_finite_positive(const char* what, double value) {
  if (!std::isfinite(value) || !(value > 0.0)) {
    throw std::invalid_argument(
        fmt::format("ModalSettings: {} must be finite and positive, got {}", what, value));
  }
}

}  // namespace

// --- Damping -----------------------------------------------------------------------------------------------

void Damping::validate() const {
  auto check = [](const char* what, double value) {
    if (!std::isfinite(value) || value < 0.0) {
      throw std::invalid_argument(fmt::format("Damping: {} must be finite and >= 0, got {}", what, value));
    }
  };
  if (model == Model::modal_ratio) {
    if (ratios.empty()) throw std::invalid_argument("Damping: modal_ratio needs at least one damping ratio");
    for (double zeta : ratios) check("damping ratio", zeta);
  } else {
    check("Rayleigh alpha (1/s)", alpha);
    check("Rayleigh beta (s)", beta);
  }
}

Eigen::VectorXd Damping::coefficients(const Eigen::VectorXd& omega) const {
  validate();
  Eigen::VectorXd gamma(omega.size());
  for (Eigen::Index i = 0; i < omega.size(); ++i) {
    if (model == Model::modal_ratio) {
      const double zeta = ratios[std::min<std::size_t>(std::size_t(i), ratios.size() - 1)];
      gamma(i) = 2.0 * zeta * omega(i);
    } else {
      gamma(i) = alpha + beta * omega(i) * omega(i);
    }
  }
  return gamma;
}

void ModalSettings::validate() const {
  if (mode_count < 1) {
    throw std::invalid_argument(fmt::format("ModalSettings: mode_count must be >= 1, got {}", mode_count));
  }
  check_finite_positive("tolerance", tolerance);
  if (max_iterations < 1) {
    throw std::invalid_argument(
        fmt::format("ModalSettings: max_iterations must be >= 1, got {}", max_iterations));
  }
  if (lanczos_vectors != 0 && lanczos_vectors <= mode_count) {
    throw std::invalid_argument(
        fmt::format("ModalSettings: lanczos_vectors must be 0 (automatic) or > mode_count ({}), got {}",
                    mode_count, lanczos_vectors));
  }
  damping.validate();
}

// --- ModalBasis
// ---------------------------------------------------------------------------------------------

ModalBasis ModalBasis::compute(const BeamModel& model, const ModalSettings& settings) {
  settings.validate();
  const SparseMatrix& stiffness = model.stiffness();
  const SparseMatrix& mass = model.mass();
  const int dofs = model.dof_count();
  const int m = settings.mode_count;
  if (m >= dofs) {
    throw std::invalid_argument(
        fmt::format("ModalBasis: {} modes requested but the model has only {} DOFs; ask for at most {}", m,
                    dofs, dofs - 1));
  }

  ModalStatus status;
  status.requested = m;
  status.shift = kShift;
  Eigen::VectorXd eigenvalues;  // omega^2, ascending
  Eigen::MatrixXd shapes;

  const int wanted_ncv =
      settings.lanczos_vectors > 0 ? settings.lanczos_vectors : std::max(2 * m + 1, m + 20);
  const int ncv = std::min(dofs, wanted_ncv);
  if (wanted_ncv >= dofs) {
    // The Lanczos basis would span the whole space: the problem is tiny, solve it densely.
    status.method = "dense (Eigen)";
    const auto start = Clock::now();
    Eigen::GeneralizedSelfAdjointEigenSolver<Eigen::MatrixXd> dense{Eigen::MatrixXd(stiffness),
                                                                    Eigen::MatrixXd(mass)};
    if (dense.info() != Eigen::Success) {
      throw ModalError("ModalBasis: the dense generalized eigensolver failed", status);
    }
    eigenvalues = dense.eigenvalues().head(m);
    shapes = dense.eigenvectors().leftCols(m);
    status.converged = m;
    status.seconds_solve = seconds_since(start);
  } else {
    status.method = "shift-invert Lanczos (Spectra)";
    auto start = Clock::now();
    ShiftInvertLdlt op(stiffness, mass);
    MassProduct mass_op(mass);
    // The constructor factorises K - sigma M (through set_shift).
    Spectra::SymGEigsShiftSolver<ShiftInvertLdlt, MassProduct, Spectra::GEigsMode::ShiftInvert> solver(
        op, mass_op, m, ncv, kShift);
    status.seconds_factorise = seconds_since(start);

    start = Clock::now();
    solver.init();
    status.converged = int(solver.compute(Spectra::SortRule::LargestMagn, settings.max_iterations,
                                          settings.tolerance, Spectra::SortRule::SmallestAlge));
    status.iterations = int(solver.num_iterations());
    status.operations = int(solver.num_operations());
    status.seconds_solve = seconds_since(start);
    if (solver.info() != Spectra::CompInfo::Successful || status.converged < m) {
      throw ModalError(
          fmt::format("ModalBasis: only {} of {} modes converged after {} Lanczos iterations (tolerance {}, "
                      "{} Lanczos vectors); ask for fewer modes, more iterations (max_iterations) or a "
                      "looser tolerance",
                      status.converged, m, status.iterations, settings.tolerance, ncv),
          status);
    }
    eigenvalues = solver.eigenvalues();
    shapes = solver.eigenvectors();
  }

  if ((eigenvalues.array() <= 0.0).any() || !eigenvalues.allFinite()) {
    throw ModalError(fmt::format("ModalBasis: a non-positive eigenvalue omega^2 = {}; the model is not "
                                 "positive definite (is the root clamped?)",
                                 eigenvalues.minCoeff()),
                     status);
  }
  normalise_to_mass(mass, shapes);
  fix_signs(shapes);
  Eigen::VectorXd omega = eigenvalues.cwiseSqrt();
  status.max_residual = max_backward_error(stiffness, mass, omega, shapes);
  return from_values(std::move(omega), std::move(shapes), settings.damping, std::move(status));
}

ModalBasis ModalBasis::from_values(Eigen::VectorXd omega, Eigen::MatrixXd shapes, Damping damping,
                                   ModalStatus status) {
  if (omega.size() < 1 || shapes.cols() != omega.size() || shapes.rows() < omega.size()) {
    throw std::invalid_argument(
        fmt::format("ModalBasis: expected m >= 1 frequencies and a dofs x m shape matrix with dofs > m, got "
                    "{} frequencies "
                    "and {} x {} shapes",
                    omega.size(), shapes.rows(), shapes.cols()));
  }
  if (!omega.allFinite() || (omega.array() <= 0.0).any() || !shapes.allFinite()) {
    throw std::invalid_argument("ModalBasis: frequencies must be finite and positive and shapes finite");
  }
  for (Eigen::Index i = 1; i < omega.size(); ++i) {
    if (omega(i) < omega(i - 1)) {
      throw std::invalid_argument(fmt::format("ModalBasis: frequencies must ascend, got omega[{}] = {} < {}",
                                              i, omega(i), omega(i - 1)));
    }
  }
  ModalBasis basis;
  basis.gamma_ = damping.coefficients(omega);
  basis.omega_ = std::move(omega);
  basis.shapes_ = std::move(shapes);
  basis.damping_ = std::move(damping);
  basis.status_ = std::move(status);
  return basis;
}

Eigen::VectorXd ModalBasis::frequencies_hz() const {
  return omega_ / (2.0 * std::numbers::pi);
}

Eigen::VectorXd ModalBasis::damping_ratios() const {
  return gamma_.cwiseQuotient(2.0 * omega_);
}

Eigen::MatrixX3d ModalBasis::node_displacements(const BeamModel& model, int mode) const {
  if (model.dof_count() != dof_count()) {
    throw std::invalid_argument(fmt::format(
        "ModalBasis: the model has {} DOFs but the basis was built for {}", model.dof_count(), dof_count()));
  }
  if (mode < 0 || mode >= mode_count()) {
    throw std::invalid_argument(fmt::format("ModalBasis: mode {} outside 0..{}", mode, mode_count() - 1));
  }
  Eigen::MatrixX3d displacement = Eigen::MatrixX3d::Zero(model.node_count(), 3);
  for (int node = 0; node < model.node_count(); ++node) {
    for (int axis = 0; axis < 3; ++axis) {
      const int dof = model.free_dof_of(node, axis);
      if (dof >= 0) displacement(node, axis) = shapes_(dof, mode);
    }
  }
  return displacement;
}

ModalBasis ModalBasis::scaled(double s) const {
  if (!std::isfinite(s) || !(s > 0.0)) {
    throw std::invalid_argument(fmt::format("ModalBasis: scale must be finite and positive, got {}", s));
  }
  Eigen::MatrixXd shapes = shapes_ * std::pow(s, -2.5);
  for (Eigen::Index dof = 0; dof < shapes.rows(); ++dof) {
    if (dof % 6 < 3) shapes.row(dof) *= s;  // translations carry one more power of s than rotations
  }
  // No new sign rule here: each scaled shape keeps the sign of its source, so that a wind basis scaled
  // alongside (WindBasis::scaled) still belongs to it.
  return from_values(omega_ / s, std::move(shapes), damping_, status_);
}

}  // namespace fw::trees
