#include "trees/ForestReference.hpp"

#include <fmt/format.h>

#include "trees/UnresolvedTurbulence.hpp"

#include <algorithm>
#include <cmath>
#include <stdexcept>

namespace fw::trees {
namespace {

[[noreturn]] void fail(const std::string& what) {
  throw std::invalid_argument("ForestReference: " + what);
}

// Component c at lattice position (x, y, z) (face units: face (i, j, k) sits at integer coordinates),
// clamped to the component's own lattice.
double sample_component(const fluid::GridSpec& spec, const std::vector<float>& q, int c, const double at[3]) {
  int lo[3], hi[3];
  double t[3];
  for (int a = 0; a < 3; ++a) {
    const int extent = fluid::reference::extent(spec, c, a);
    const double x = std::clamp(at[a], 0.0, double(extent - 1));
    lo[a] = std::min(int(std::floor(x)), extent - 1);
    hi[a] = std::min(lo[a] + 1, extent - 1);
    t[a] = x - lo[a];
  }
  double sum = 0.0;
  for (int corner = 0; corner < 8; ++corner) {
    const int i = corner & 1 ? hi[0] : lo[0];
    const int j = corner & 2 ? hi[1] : lo[1];
    const int k = corner & 4 ? hi[2] : lo[2];
    const double weight = (corner & 1 ? t[0] : 1.0 - t[0]) * (corner & 2 ? t[1] : 1.0 - t[1]) *
                          (corner & 4 ? t[2] : 1.0 - t[2]);
    sum += weight * q[fluid::reference::face_index(spec, c, i, j, k)];
  }
  return sum;
}

}  // namespace

void ForestReference::check_sampled_wind(const Eigen::MatrixX3d& sampled_wind) const {
  if (sampled_wind.rows() != total_samples())
    fail(fmt::format("sampled wind has {} rows, expected {}", sampled_wind.rows(), total_samples()));
}

void ForestReference::check_wind_and_travel(const Eigen::MatrixX3d& sampled_wind,
                                            const TreeTravel& travel) const {
  check_sampled_wind(sampled_wind);
  if (travel.distance.size() != forest_.instance_count() ||
      travel.last_step.size() != forest_.instance_count())
    fail(fmt::format("travel has {} distances and {} last steps, expected {}", travel.distance.size(),
                     travel.last_step.size(), forest_.instance_count()));
}

Eigen::Vector3d sample_mac_velocity(const fluid::GridSpec& spec, const fluid::MacVelocity& velocity,
                                    const Eigen::Vector3d& world) {
  Eigen::Vector3d v;
  for (int c = 0; c < 3; ++c) {
    double at[3];
    for (int a = 0; a < 3; ++a)
      at[a] = (world(a) - spec.origin[std::size_t(a)]) / spec.h - (a == c ? 0.0 : 0.5);
    v(c) = sample_component(spec, velocity.component(c), c, at);
  }
  return v;
}

Eigen::Vector3d cell_centred_velocity(const fluid::GridSpec& spec, const fluid::MacVelocity& velocity,
                                      const Eigen::Vector3d& world) {
  const std::array<int, 3> cell = spec.cell_holding({world.x(), world.y(), world.z()});
  Eigen::Vector3d v;
  for (int c = 0; c < 3; ++c) {
    int next[3] = {cell[0], cell[1], cell[2]};
    ++next[c];
    const auto& q = velocity.component(c);
    v(c) = 0.5 * (double(q[fluid::reference::face_index(spec, c, cell[0], cell[1], cell[2])]) +
                  q[fluid::reference::face_index(spec, c, next[0], next[1], next[2])]);
  }
  return v;
}

void exact_modal_step(double& q, double& qdot, double f, double omega, double gamma, double dt) {
  // x = q - f/omega^2 obeys x'' + 2a x' + omega^2 x = 0, a = gamma/2, d = omega^2 - a^2. With
  // C(t), S(t) = cos(w t), sin(w t)/w (d = w^2 > 0), cosh(k t), sinh(k t)/k (d = -k^2 < 0), or their common
  // Taylor series in d t^2 (near critical damping, where both forms lose accuracy):
  //   x(t) = e^-at [x0 C + (v0 + a x0) S],   x'(t) = e^-at [v0 C - (a v0 + omega^2 x0) S].
  const double a = 0.5 * gamma;
  const double w2 = omega * omega;
  const double x0 = q - f / w2, v0 = qdot;
  const double d = (omega - a) * (omega + a);
  const double z = d * dt * dt;
  double c, s;  // e^-at C and e^-at S
  if (std::abs(z) < 1e-4) {
    const double decay = std::exp(-a * dt);
    c = decay * (1.0 - z / 2.0 + z * z / 24.0);
    s = decay * dt * (1.0 - z / 6.0 + z * z / 120.0);
  } else if (d > 0.0) {
    const double wd = std::sqrt(d);
    const double decay = std::exp(-a * dt);
    c = decay * std::cos(wd * dt);
    s = decay * std::sin(wd * dt) / wd;
  } else {
    // e^-at cosh(kt) and e^-at sinh(kt) from the two decaying exponentials, which cannot overflow;
    // a - k = omega^2 / (a + k) without cancellation.
    const double k = std::sqrt(-d);
    const double slow = std::exp(-w2 / (a + k) * dt), fast = std::exp(-(a + k) * dt);
    c = 0.5 * (slow + fast);
    s = 0.5 * (slow - fast) / k;
  }
  q = f / w2 + x0 * c + (v0 + a * x0) * s;
  qdot = v0 * c - (a * v0 + w2 * x0) * s;
}

void semi_implicit_modal_step(double& q, double& qdot, double f, double omega, double gamma, double dt) {
  qdot += dt * (f - gamma * qdot - omega * omega * q);
  q += dt * qdot;
}

Eigen::MatrixX3d ForestReference::sample_positions() const {
  Eigen::MatrixX3d points(total_samples(), 3);
  for (int k = 0; k < forest_.instance_count(); ++k) {
    const TreeInstance& t = forest_.instances()[std::size_t(k)];
    const Eigen::Matrix3d r = forest_.rotation(k);
    const Eigen::MatrixX3d& local = forest_.species_of(k).wind().sample_points();
    for (int s = 0; s < local.rows(); ++s)
      points.row(forest_.sample_offset(k) + s) =
          (t.position + t.scale * r * local.row(s).transpose()).transpose();
  }
  return points;
}

Eigen::MatrixX3d ForestReference::sample_wind(const fluid::GridSpec& spec,
                                              const fluid::MacVelocity& velocity) const {
  const Eigen::MatrixX3d points = sample_positions();
  Eigen::MatrixX3d wind(points.rows(), 3);
  for (int s = 0; s < points.rows(); ++s)
    wind.row(s) = sample_mac_velocity(spec, velocity, points.row(s).transpose()).transpose();
  return wind;
}

Eigen::VectorXd ForestReference::modal_forces(const Eigen::MatrixX3d& sampled_wind,
                                              const fluid::DragLaw& law) const {
  check_sampled_wind(sampled_wind);
  Eigen::VectorXd f(total_modes());
  for (int k = 0; k < forest_.instance_count(); ++k) {
    const TreeInstance& t = forest_.instances()[std::size_t(k)];
    const Eigen::Matrix3d r = forest_.rotation(k);
    const WindBasis& basis = forest_.species_of(k).wind();
    for (int i = 0; i < basis.mode_count(); ++i) {
      double sum = 0.0;
      for (int s = 0; s < basis.sample_count(); ++s) {
        const Eigen::Vector3d v = sampled_wind.row(forest_.sample_offset(k) + s).transpose();
        sum += law.factor(v.norm()) * v.norm() * v.dot(std::sqrt(t.scale) * r * basis.projection(s, i));
      }
      f(forest_.mode_offset(k) + i) = sum;
    }
  }
  return f;
}

Eigen::VectorXd ForestReference::modal_forces(const fluid::GridSpec& spec, const fluid::MacVelocity& velocity,
                                              const fluid::DragLaw& law) const {
  return modal_forces(sample_wind(spec, velocity), law);
}

Eigen::VectorXd ForestReference::omega() const {
  Eigen::VectorXd w(total_modes());
  for (int k = 0; k < forest_.instance_count(); ++k) {
    const ModalBasis& modes = forest_.species_of(k).modes();
    w.segment(forest_.mode_offset(k), modes.mode_count()) =
        modes.omega() / forest_.instances()[std::size_t(k)].scale;
  }
  return w;
}

Eigen::VectorXd ForestReference::gamma() const {
  Eigen::VectorXd g(total_modes());
  const Eigen::VectorXd w = omega();
  for (int k = 0; k < forest_.instance_count(); ++k) {
    const ModalBasis& modes = forest_.species_of(k).modes();
    const int first = forest_.mode_offset(k);
    g.segment(first, modes.mode_count()) =
        2.0 * modes.damping_ratios().cwiseProduct(w.segment(first, modes.mode_count()));
  }
  return g;
}

void ForestReference::step(Eigen::VectorXd& q, Eigen::VectorXd& qdot, const Eigen::VectorXd& forces,
                           double dt, ModalIntegrator integrator) const {
  const int m = total_modes();
  if (q.size() != m || qdot.size() != m || forces.size() != m)
    fail(fmt::format("q, qdot and forces must have {} entries, got {}, {}, {}", m, q.size(), qdot.size(),
                     forces.size()));
  if (!std::isfinite(dt) || dt < 0.0) fail(fmt::format("dt must be finite and >= 0, got {}", dt));
  const Eigen::VectorXd w = omega(), g = gamma();
  for (int i = 0; i < m; ++i) {
    if (integrator == ModalIntegrator::exact)
      exact_modal_step(q(i), qdot(i), forces(i), w(i), g(i), dt);
    else
      semi_implicit_modal_step(q(i), qdot(i), forces(i), w(i), g(i), dt);
  }
}

Eigen::MatrixX3d ForestReference::displacements(const Eigen::VectorXd& q, bool strong_wind_correction) const {
  if (q.size() != total_modes()) fail(fmt::format("q has {} entries, expected {}", q.size(), total_modes()));
  Eigen::MatrixX3d u(total_nodes(), 3);
  for (int k = 0; k < forest_.instance_count(); ++k) {
    const int m = forest_.species_of(k).modes().mode_count();
    u.middleRows(forest_.node_offset(k), forest_.species_of(k).skeleton().size()) =
        forest_.instance_displacements(k, q.segment(forest_.mode_offset(k), m), strong_wind_correction);
  }
  return u;
}

Eigen::VectorXd ForestReference::static_modal_response(const Eigen::VectorXd& forces) const {
  if (forces.size() != total_modes())
    fail(fmt::format("forces have {} entries, expected {}", forces.size(), total_modes()));
  return forces.cwiseQuotient(omega().cwiseAbs2());
}

Eigen::VectorXd ForestReference::static_modal_response(const fluid::GridSpec& spec,
                                                       const fluid::MacVelocity& velocity) const {
  return static_modal_response(modal_forces(spec, velocity));
}

Eigen::VectorXd ForestReference::unresolved_modal_forces(const Eigen::MatrixX3d& sampled_wind,
                                                         const TreeTravel& travel,
                                                         const UnresolvedTurbulence& series,
                                                         const std::vector<int>& offsets,
                                                         double intensity) const {
  check_wind_and_travel(sampled_wind, travel);
  if (offsets.size() != std::size_t(total_samples()))
    fail(fmt::format("offsets have {} entries, expected {}", offsets.size(), total_samples()));
  if (!std::isfinite(intensity) || intensity < 0.0)
    fail(fmt::format("intensity must be finite and >= 0, got {}", intensity));
  Eigen::VectorXd f = Eigen::VectorXd::Zero(total_modes());
  for (int k = 0; k < forest_.instance_count(); ++k) {
    const TreeInstance& t = forest_.instances()[std::size_t(k)];
    const Eigen::Matrix3d r = forest_.rotation(k);
    const WindBasis& basis = forest_.species_of(k).wind();
    for (int s = 0; s < basis.sample_count(); ++s) {
      const int flat = forest_.sample_offset(k) + s;
      const Eigen::Vector3d v = sampled_wind.row(flat).transpose();
      const Eigen::Vector3d xi = series.average(
          travel.distance(k) + series.spacing() * offsets[std::size_t(flat)], travel.last_step(k));
      const Eigen::Vector3d load = linearised_drag_increment(v, unresolved_fluctuation(v, xi, intensity));
      for (int i = 0; i < basis.mode_count(); ++i)
        f(forest_.mode_offset(k) + i) += load.dot(std::sqrt(t.scale) * r * basis.projection(s, i));
    }
  }
  return f;
}

void ForestReference::advance_travelled(TreeTravel& travel, const Eigen::MatrixX3d& sampled_wind,
                                        double dt) const {
  check_wind_and_travel(sampled_wind, travel);
  if (!std::isfinite(dt) || dt < 0.0) fail(fmt::format("dt must be finite and >= 0, got {}", dt));
  for (int k = 0; k < forest_.instance_count(); ++k) {
    travel.last_step(k) = sampled_wind.row(forest_.sample_offset(k)).norm() * dt;
    travel.distance(k) += travel.last_step(k);
  }
}

}  // namespace fw::trees
