#include "trees/StrongWindCorrection.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <cmath>
#include <stdexcept>
#include <string>
#include <utility>

namespace fw::trees {
namespace {

[[noreturn]] void fail(const std::string& what) {
  throw std::invalid_argument("StrongWindCorrection: " + what);
}

// Golden-section steps after the grid search: each shrinks the bracket by 0.618, so 60 take one grid cell
// (beta_max / (search_points - 1)) below 1e-12 of itself, past where the residual changes in double.
constexpr int kGoldenSteps = 60;
const double kInverseGolden = (std::sqrt(5.0) - 1.0) / 2.0;

// The corrected trajectories of one mode, split by the symmetry of the samples: column k - 1 (k = 1..K) of
// odd is (d(q_k) - d(-q_k)) / 2, of even (d(q_k) + d(-q_k)) / 2, with the Gram matrices of both.
struct Trajectories {
  Eigen::MatrixXd odd, even;
  Eigen::MatrixXd odd_gram, even_gram;
};

Trajectories sample_trajectories(const Skeleton& skeleton, const Eigen::VectorXd& phi, double q_max, int K) {
  Trajectories t;
  t.odd.resize(phi.size(), K);
  t.even.resize(phi.size(), K);
  for (int k = 1; k <= K; ++k) {
    const double q = q_max * k / K;
    const Eigen::VectorXd plus = StrongWindCorrection::corrected_deformation(skeleton, q * phi);
    const Eigen::VectorXd minus = StrongWindCorrection::corrected_deformation(skeleton, -q * phi);
    t.odd.col(k - 1) = 0.5 * (plus - minus);
    t.even.col(k - 1) = 0.5 * (plus + minus);
  }
  t.odd_gram = t.odd.transpose() * t.odd;
  t.even_gram = t.even.transpose() * t.even;
  return t;
}

// q~_k for k = 1..K at beta = b q_max, in units of q_max (a common factor the residual does not see).
Eigen::VectorXd reparametrised_samples(double beta, int K) {
  Eigen::VectorXd t(K);
  for (int k = 1; k <= K; ++k) t(k - 1) = StrongWindCorrection::reparametrised(double(k) / K, beta);
  return t;
}

// Sum over the 2 K + 1 samples and all nodes of |d_k - q~_k v - q~_k^2 w|^2 with the best v, w for this beta:
// the part of the trajectories outside the span of q~ (odd) and of q~^2 (even). The samples -k and k give
// the same odd and even residuals, hence the factor 2; k = 0 has d = 0 and q~ = 0.
double residual(const Trajectories& t, double beta, int K) {
  const Eigen::VectorXd odd = reparametrised_samples(beta, K);
  const Eigen::VectorXd even = odd.cwiseAbs2();
  const double odd_part = t.odd_gram.trace() - odd.dot(t.odd_gram * odd) / odd.squaredNorm();
  const double even_part = t.even_gram.trace() - even.dot(t.even_gram * even) / even.squaredNorm();
  return 2.0 * (odd_part + even_part);
}

// The beta in [0, beta_max] with the smallest residual: grid, then golden section in the best cell.
double search_beta(const Trajectories& t, const StrongWindSettings& settings) {
  const int K = settings.samples_per_side;
  const double step = settings.beta_max / (settings.search_points - 1);
  int best = 0;
  double best_residual = residual(t, 0.0, K);
  for (int j = 1; j < settings.search_points; ++j) {
    const double r = residual(t, j * step, K);
    if (r < best_residual) best = j, best_residual = r;
  }
  double lo = std::max(0.0, (best - 1) * step), hi = std::min(settings.beta_max, (best + 1) * step);
  double x1 = hi - kInverseGolden * (hi - lo), x2 = lo + kInverseGolden * (hi - lo);
  double r1 = residual(t, x1, K), r2 = residual(t, x2, K);
  for (int n = 0; n < kGoldenSteps; ++n) {
    if (r1 < r2) {
      hi = x2, x2 = x1, r2 = r1;
      x1 = hi - kInverseGolden * (hi - lo);
      r1 = residual(t, x1, K);
    } else {
      lo = x1, x1 = x2, r1 = r2;
      x2 = lo + kInverseGolden * (hi - lo);
      r2 = residual(t, x2, K);
    }
  }
  // The grid point stays the answer when refinement found nothing better (a minimum at an end of the range).
  const double refined = r1 < r2 ? x1 : x2;
  return std::min(r1, r2) < best_residual ? refined : best * step;
}

// max over elements of |(phi_c - phi_p) normal to the element| / L: the slope per unit q by which the mode
// turns its steepest element.
double largest_slope(const Skeleton& skeleton, const Eigen::VectorXd& phi) {
  double slope = 0.0;
  for (const auto& [parent, child] : skeleton.elements()) {
    const Eigen::Vector3d rest = skeleton.node(child).position - skeleton.node(parent).position;
    const Eigen::Vector3d parent_phi =
        parent == skeleton.root() ? Eigen::Vector3d::Zero() : Eigen::Vector3d(phi.segment<3>(3 * parent));
    const Eigen::Vector3d relative = phi.segment<3>(3 * child) - parent_phi;
    const Eigen::Vector3d axis = rest.normalized();
    slope = std::max(slope, (relative - axis.dot(relative) * axis).norm() / rest.norm());
  }
  return slope;
}

void check_shapes(const Eigen::MatrixXd& m, const char* name, Eigen::Index rows, Eigen::Index cols) {
  if (m.rows() != rows || m.cols() != cols)
    fail(fmt::format("{} is {} x {}, expected {} x {}", name, m.rows(), m.cols(), rows, cols));
  if (!m.allFinite()) fail(fmt::format("{} has non-finite values", name));
}

}  // namespace

void StrongWindSettings::validate() const {
  auto bad = [](const std::string& what) { throw std::invalid_argument("StrongWindSettings: " + what); };
  if (samples_per_side < 2) bad(fmt::format("samples_per_side must be >= 2, got {}", samples_per_side));
  if (!std::isfinite(reach) || reach <= 0.0) bad(fmt::format("reach must be finite and > 0, got {}", reach));
  if (!std::isfinite(max_slope) || max_slope <= 0.0)
    bad(fmt::format("max_slope must be finite and > 0, got {}", max_slope));
  if (search_points < 3) bad(fmt::format("search_points must be >= 3, got {}", search_points));
  if (!std::isfinite(beta_max) || beta_max <= 0.0)
    bad(fmt::format("beta_max must be finite and > 0, got {}", beta_max));
}

double StrongWindCorrection::reparametrised(double q, double b) {
  return b == 0.0 ? q : std::atan(b * q) / b;
}

Eigen::VectorXd StrongWindCorrection::corrected_deformation(const Skeleton& skeleton,
                                                            const Eigen::VectorXd& linear) {
  const int n = skeleton.size();
  if (linear.size() != 3 * n)
    fail(fmt::format("the linear displacement has {} values, expected {}", linear.size(), 3 * n));
  Eigen::VectorXd corrected = Eigen::VectorXd::Zero(3 * n);  // the root stays where it is (clamped)
  for (const auto& [parent, child] : skeleton.elements()) {
    const Eigen::Vector3d rest = skeleton.node(child).position - skeleton.node(parent).position;
    const Eigen::Vector3d child_u = linear.segment<3>(3 * child);
    const Eigen::Vector3d parent_u =
        parent == skeleton.root() ? Eigen::Vector3d::Zero() : Eigen::Vector3d(linear.segment<3>(3 * parent));
    const Eigen::Vector3d delta = child_u - parent_u;
    const double length = rest.norm(), deformed_length = (rest + delta).norm();
    // x'_c - x_c = (x'_p - x_p) + L unit(r + delta) - r, r = x_c - x_p: displacements, not positions, so that
    // far from the origin no digits are lost. L unit(r + delta) - r itself, a difference of two nearly equal
    // vectors at small delta, is written without that cancellation (with L = |r|, L / |d| - 1 =
    // (L^2 - |d|^2) / (|d| (L + |d|)) = -(2 r.delta + delta.delta) / (|d| (L + |d|)), d = r + delta), so
    // that small motion keeps its relative accuracy. A collapsed element keeps its rest direction: no change.
    Eigen::Vector3d change = Eigen::Vector3d::Zero();
    if (deformed_length >= Skeleton::kMinElementLength)
      change = (length / deformed_length) * delta - ((2.0 * rest.dot(delta) + delta.squaredNorm()) /
                                                     (deformed_length * (length + deformed_length))) *
                                                        rest;
    corrected.segment<3>(3 * child) = corrected.segment<3>(3 * parent) + change;
  }
  return corrected;
}

StrongWindCorrection StrongWindCorrection::fit(const Skeleton& skeleton, const Eigen::MatrixXd& node_shapes,
                                               const StrongWindSettings& settings) {
  settings.validate();
  const int n = skeleton.size();
  if (node_shapes.rows() != 3 * n)
    fail(fmt::format("node shapes have {} rows, expected 3 x {} nodes", node_shapes.rows(), n));
  if (!node_shapes.allFinite()) fail("node shapes have non-finite values");
  const int m = int(node_shapes.cols()), K = settings.samples_per_side;

  double size = 0.0;
  const Eigen::Vector3d root = skeleton.node(skeleton.root()).position;
  for (const SkeletonNode& node : skeleton.nodes()) size = std::max(size, (node.position - root).norm());

  StrongWindCorrection c;
  c.v_ = Eigen::MatrixXd::Zero(3 * n, m);
  c.w_ = Eigen::MatrixXd::Zero(3 * n, m);
  c.b_ = Eigen::VectorXd::Zero(m);
  c.fits_.assign(std::size_t(m), StrongWindModeFit{});
  for (int i = 0; i < m; ++i) {
    const Eigen::VectorXd phi = node_shapes.col(i);
    double largest = 0.0;
    for (int node = 0; node < n; ++node) largest = std::max(largest, phi.segment<3>(3 * node).norm());
    // A mode without translations (torsion of a straight pole) displaces nothing: v = w = 0 is exact.
    if (largest == 0.0) continue;
    const double slope = largest_slope(skeleton, phi);
    const double q_max =
        std::min(settings.reach * size / largest, slope > 0.0 ? settings.max_slope / slope : HUGE_VAL);
    const Trajectories t = sample_trajectories(skeleton, phi, q_max, K);
    const double beta = search_beta(t, settings);
    const double b = beta / q_max;

    Eigen::VectorXd odd(K), linear(K);
    for (int k = 1; k <= K; ++k) {
      linear(k - 1) = q_max * k / K;
      odd(k - 1) = reparametrised(linear(k - 1), b);
    }
    const Eigen::VectorXd even = odd.cwiseAbs2();
    const Eigen::VectorXd v = t.odd * odd / odd.squaredNorm();
    const Eigen::VectorXd w = t.even * even / even.squaredNorm();

    // Residuals summed directly (not from the Gram identity, which cancels digits on a near-perfect fit).
    const double total = 2.0 * (t.odd.squaredNorm() + t.even.squaredNorm());
    const double missed =
        2.0 * ((t.odd - v * odd.transpose()).squaredNorm() + (t.even - w * even.transpose()).squaredNorm());
    const double missed_linear =
        2.0 * ((t.odd - phi * linear.transpose()).squaredNorm() + t.even.squaredNorm());
    c.v_.col(i) = v;
    c.w_.col(i) = w;
    c.b_(i) = b;
    c.fits_[std::size_t(i)] = {q_max, std::sqrt(missed / total), std::sqrt(missed_linear / total),
                               (v - phi).norm() / phi.norm()};
  }
  return c;
}

StrongWindCorrection StrongWindCorrection::from_values(Eigen::MatrixXd v, Eigen::MatrixXd w,
                                                       Eigen::VectorXd b,
                                                       std::vector<StrongWindModeFit> fits) {
  const Eigen::Index m = b.size();
  if (v.rows() % 3 != 0) fail(fmt::format("v has {} rows, not 3 per node", v.rows()));
  check_shapes(v, "v", v.rows(), m);
  check_shapes(w, "w", v.rows(), m);
  if (!b.allFinite() || (m > 0 && b.minCoeff() < 0.0)) fail("b must be finite and >= 0");
  if (Eigen::Index(fits.size()) != m) fail(fmt::format("{} fits for {} modes", fits.size(), m));
  StrongWindCorrection c;
  c.v_ = std::move(v);
  c.w_ = std::move(w);
  c.b_ = std::move(b);
  c.fits_ = std::move(fits);
  return c;
}

Eigen::VectorXd StrongWindCorrection::displacement(const Eigen::VectorXd& q) const {
  if (q.size() != mode_count()) fail(fmt::format("q has {} entries, expected {}", q.size(), mode_count()));
  Eigen::VectorXd u = Eigen::VectorXd::Zero(v_.rows());
  for (int i = 0; i < mode_count(); ++i) {
    const double t = reparametrised(q(i), b_(i));
    u += t * v_.col(i) + (t * t) * w_.col(i);
  }
  return u;
}

Eigen::VectorXd StrongWindCorrection::corrected_displacement(const Skeleton& skeleton,
                                                             const Eigen::VectorXd& q) const {
  if (skeleton.size() != node_count())
    fail(fmt::format("the skeleton has {} nodes, the correction {}", skeleton.size(), node_count()));
  return corrected_deformation(skeleton, displacement(q));
}

StrongWindCorrection StrongWindCorrection::scaled(double s) const {
  if (!std::isfinite(s) || s <= 0.0) fail(fmt::format("scale must be finite and > 0, got {}", s));
  StrongWindCorrection c = *this;
  c.v_ *= std::pow(s, -1.5);
  c.w_ *= std::pow(s, -4.0);
  c.b_ *= std::pow(s, -2.5);
  for (StrongWindModeFit& f : c.fits_) f.q_max *= std::pow(s, 2.5);
  return c;
}

}  // namespace fw::trees
