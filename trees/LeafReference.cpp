#include "trees/LeafReference.hpp"

#include <fmt/format.h>

#include <Eigen/Geometry>
#include <algorithm>
#include <cmath>
#include <numbers>
#include <stdexcept>

#include "trees/ForestReference.hpp"  // sample_mac_velocity, cell_centred_velocity

namespace fw::trees {
namespace {

constexpr double kPi = std::numbers::pi;
constexpr double kMaxFlutterAngle = 0.5 * kPi;  // theta is clamped to [-pi/2, pi/2]
constexpr double kMaxSubStepCells = 0.5;        // a flying leaf moves at most half a cell per sub-step
constexpr double kDegToRad = kPi / 180.0;

[[noreturn]] void fail(const std::string& what) {
  throw std::invalid_argument("LeafReference: " + what);
}

Eigen::Vector3d rotate(const Eigen::Vector3d& v, const Eigen::Vector3d& axis, double angle) {
  return Eigen::AngleAxisd(angle, axis) * v;
}

// The solids and the ground that flying leaves land on, and the domain's sides they wrap or exit through.
class Terrain {
 public:
  Terrain(const fluid::GridSpec& spec, const std::vector<std::uint8_t>& solid) : spec_(spec), solid_(solid) {}

  /// Below the ground or in a solid cell. Outside the grid's sides nothing is solid (exits come first).
  bool blocked(const Eigen::Vector3d& x) const {
    if (x.z() < spec_.origin[2]) return true;
    if (solid_.empty()) return false;
    int cell[3];
    const int n[3] = {spec_.nx, spec_.ny, spec_.nz};
    for (int a = 0; a < 3; ++a) {
      cell[a] = int(std::floor((x(a) - spec_.origin[std::size_t(a)]) / spec_.h));
      if (cell[a] < 0 || cell[a] >= n[a]) return false;
    }
    return solid_[std::size_t(cell[0]) +
                  std::size_t(spec_.nx) * (cell[1] + std::size_t(spec_.ny) * cell[2])] != 0;
  }

  /// z of the top face of the layer that holds x: the ground (origin z) for a point below it.
  double top_face(const Eigen::Vector3d& x) const {
    const int k = std::max(-1, int(std::floor((x.z() - spec_.origin[2]) / spec_.h)));
    return spec_.origin[2] + (k + 1) * spec_.h;
  }

  /// Wraps q (and p with it, so that the sub-step keeps its shape) through periodic sides; false when q
  /// left through any other side (the ground is no side: below it is solid).
  bool inside_or_wrapped(Eigen::Vector3d& p, Eigen::Vector3d& q) const {
    const int n[3] = {spec_.nx, spec_.ny, spec_.nz};
    for (int a = 0; a < 2; ++a) {
      const double lo = spec_.origin[std::size_t(a)], length = n[a] * spec_.h;
      if (q(a) >= lo && q(a) < lo + length) continue;
      if (!spec_.periodic(a)) return false;
      double shift = -length * std::floor((q(a) - lo) / length);
      if (q(a) + shift >= lo + length) shift -= length;  // rounding just below lo
      q(a) += shift;
      p(a) += shift;
    }
    return q.z() < spec_.origin[2] + spec_.nz * spec_.h;
  }

 private:
  const fluid::GridSpec& spec_;
  const std::vector<std::uint8_t>& solid_;
};

// Moves a flying leaf by `travel` in sub-steps of at most half a cell (docs/leaves.md, "Landing and exits").
// Sub-steps only find solids and sides; the velocity was updated once for the whole step.
void move(WorldLeaf& leaf, const Terrain& terrain, const fluid::GridSpec& spec, Eigen::Vector3d travel) {
  const int sub_steps = std::max(1, int(std::ceil(travel.norm() / (kMaxSubStepCells * spec.h))));
  for (int s = 0; s < sub_steps; ++s) {
    Eigen::Vector3d p = leaf.position, q = p + travel / sub_steps;
    if (!terrain.inside_or_wrapped(p, q)) {
      leaf.state = LeafState::exited;
      leaf.position = q;
      leaf.velocity.setZero();
      return;
    }
    if (!terrain.blocked(q)) {
      leaf.position = q;
      continue;
    }
    // Solid below: the sub-step started above the blocking cell's top face, and the point on it is free.
    const Eigen::Vector3d on_top(q.x(), q.y(), terrain.top_face(q));
    if (p.z() >= on_top.z() && !terrain.blocked(on_top)) {
      leaf.state = LeafState::landed;
      leaf.position = on_top;
      leaf.velocity.setZero();
      return;
    }
    // A wall from the side: stay at the wall at the sub-step's new height, fall on without horizontal speed.
    leaf.velocity.x() = leaf.velocity.y() = 0.0;
    travel.x() = travel.y() = 0.0;
    const Eigen::Vector3d down(p.x(), p.y(), q.z());
    if (!terrain.blocked(down)) {
      leaf.position = down;
      continue;
    }
    // Falling straight into the cell below p: land on its top face (the bottom of p's free cell).
    leaf.state = LeafState::landed;
    leaf.position = Eigen::Vector3d(p.x(), p.y(), terrain.top_face(down));
    leaf.velocity.setZero();
    return;
  }
}

// Oliapuram's pseudo-branch (docs/leaves.md): I theta'' + 2 zeta I omega theta' + I omega^2 theta = tau.
// The torque tau(theta, theta') is linearised about the step's start, tau ~ tau0 - D (theta' - theta'0)
// - K (theta - theta0): D (the air's damping of the blade's own motion) and the stabilising part of K (the
// wind turning the blade edge-on) join the oscillator's damping and stiffness, and the exact integrator of
// the trees (exact_modal_step, trees/ForestReference.hpp) steps the whole linear oscillator with its
// right-hand side held. At the start of the step this is the model's equation; integrating the air's terms
// with the oscillator keeps the step stable for any dt even where they far exceed the petiole's own
// stiffness and damping (a 4 cm^2 leaf at 10 m/s: K / I up to 60 omega^2).
void flutter_pseudo_branch(WorldLeaf& leaf, const LeafSettings& settings, const Eigen::Vector3d& wind,
                           double dt) {
  const double r = leaf.lever;
  const double q = 0.5 * kAirDensity * kLeafNormalForceCoefficient * leaf.area;
  const Eigen::Vector3d n = rotate(leaf.rest_normal, leaf.hinge, leaf.theta);
  const Eigen::Vector3d c = leaf.hinge.cross(rotate(leaf.petiole, leaf.hinge, leaf.theta));
  const double kappa = c.dot(n);  // the same for every theta: c and n turn together about the hinge
  const double un = wind.dot(n) - r * leaf.theta_rate * kappa;
  const double tau0 = r * kappa * q * std::abs(un) * un;
  const double damping = 2.0 * q * std::abs(un) * r * r * kappa * kappa;  // -dtau/dtheta'
  const double stiffness = std::max(0.0, -2.0 * r * kappa * q * std::abs(un) * wind.dot(leaf.hinge.cross(n)));

  const double inertia = leaf.mass * (r * r + leaf.side * leaf.side / 12.0);
  const double omega = 2.0 * kPi * settings.frequency;
  const double held = (tau0 + damping * leaf.theta_rate + stiffness * leaf.theta) / inertia;
  radau_oscillator_step(leaf.theta, leaf.theta_rate, held, omega * omega + stiffness / inertia,
                        2.0 * settings.damping_ratio * omega + damping / inertia, dt);
  if (std::abs(leaf.theta) > kMaxFlutterAngle) {  // the stop: the blade rests against it
    leaf.theta = std::copysign(kMaxFlutterAngle, leaf.theta);
    leaf.theta_rate = 0.0;
  }
  leaf.position = leaf.anchor + r * rotate(leaf.petiole, leaf.hinge, leaf.theta);
  leaf.normal = rotate(leaf.rest_normal, leaf.hinge, leaf.theta);
}

// Ota/Yildiz's three sine angles at time t, scaled by g(U) = min(1, |u| / U_ref). The rotations act on the
// rest petiole and normal in this order: the roll theta_R about the rest petiole first, then theta_V about
// the rest hinge, then theta_H about +z through the anchor: Rot = R_z(theta_H) R_hinge(theta_V)
// R_petiole(theta_R).
void flutter_stochastic(WorldLeaf& leaf, const LeafSettings& settings, const Eigen::Vector3d& wind,
                        double t) {
  const double g = std::min(1.0, wind.norm() / settings.reference_speed);
  double angle[3];
  for (int i = 0; i < 3; ++i) {
    angle[i] = settings.amplitudes_deg[std::size_t(i)] * kDegToRad * g *
               std::sin(2.0 * kPi * leaf.frequency[std::size_t(i)] * t + leaf.phase[std::size_t(i)]);
  }
  const double theta_h = angle[0], theta_v = angle[1], theta_r = angle[2] + settings.roll_coupling * angle[0];
  const Eigen::Matrix3d turn =
      (Eigen::AngleAxisd(theta_h, Eigen::Vector3d::UnitZ()) * Eigen::AngleAxisd(theta_v, leaf.hinge) *
       Eigen::AngleAxisd(theta_r, leaf.petiole))
          .toRotationMatrix();
  leaf.position = leaf.anchor + leaf.lever * (turn * leaf.petiole);
  leaf.normal = turn * leaf.rest_normal;
}

// m dv/dt = -m g e_z + 1/2 rho C_D a |u - v| (u - v), the drag implicit with |u - v| from the step's start.
void fly(WorldLeaf& leaf, const LeafSettings& settings, const Terrain& terrain, const fluid::GridSpec& spec,
         const fluid::MacVelocity& wind, double dt) {
  const Eigen::Vector3d u = sample_mac_velocity(spec, wind, leaf.position);
  const double relative = (u - leaf.velocity).norm();
  const double k = kAirDensity * settings.flight_drag_coefficient / (2.0 * settings.mass_per_area);  // 1/m
  leaf.velocity = (leaf.velocity + dt * (-kGravity * Eigen::Vector3d::UnitZ() + k * relative * u)) /
                  (1.0 + dt * k * relative);
  const double tumble_rate = 2.0 * kPi * kLeafTumbleStrouhal * relative / leaf.side;  // rad/s, visual only
  leaf.normal = rotate(leaf.normal, leaf.tumble_axis, tumble_rate * dt).normalized();
  move(leaf, terrain, spec, dt * leaf.velocity);
}

}  // namespace

void radau_oscillator_step(double& x, double& v, double f, double w2, double gamma, double dt) {
  // y = (x - f/w2, dt v) obeys y' = M y / dt with M = [[0, 1], [-p, -g]]; the step is y1 = D^-1 N y0 with
  // N = I + M/3 and D = I - 2M/3 + M^2/6, R(z) = (1 + z/3) / (1 - 2z/3 + z^2/6).
  const double p = w2 * dt * dt, g = gamma * dt;
  const double x_rest = f / w2;
  const double y0 = x - x_rest, y1 = dt * v;
  const double b0 = y0 + y1 / 3.0, b1 = -p / 3.0 * y0 + (1.0 - g / 3.0) * y1;
  const double d00 = 1.0 - p / 6.0, d01 = -2.0 / 3.0 - g / 6.0;
  const double d10 = 2.0 * p / 3.0 + p * g / 6.0, d11 = 1.0 + 2.0 * g / 3.0 + (g * g - p) / 6.0;
  const double det = d00 * d11 - d01 * d10;
  x = x_rest + (d11 * b0 - d01 * b1) / det;
  v = (d00 * b1 - d10 * b0) / det / dt;
}

double terminal_speed(const LeafSettings& settings) {
  return std::sqrt(2.0 * settings.mass_per_area * kGravity /
                   (kAirDensity * settings.flight_drag_coefficient));
}

double blade_force(double area, const Eigen::Vector3d& normal, const Eigen::Vector3d& wind) {
  return 0.5 * kAirDensity * kLeafNormalForceCoefficient * area * std::abs(wind.dot(normal)) * wind.norm();
}

LeafReference::LeafReference(const Forest& forest, const std::vector<SpeciesLeaves>& leaves_per_species) {
  if (leaves_per_species.size() != forest.species().size()) {
    fail(fmt::format("{} species leaves for {} forest species", leaves_per_species.size(),
                     forest.species().size()));
  }
  for (const SpeciesLeaves& sp : leaves_per_species) species_settings_.push_back(sp.settings());
  for (int k = 0; k < forest.instance_count(); ++k) {
    const TreeInstance& t = forest.instances()[std::size_t(k)];
    const SpeciesLeaves& sp = leaves_per_species[std::size_t(t.species)];
    const Eigen::Matrix3d turn = forest.rotation(k);
    const double s = t.scale;
    for (const RestLeaf& rest : sp.leaves()) {
      WorldLeaf leaf;
      leaf.tree = k;
      leaf.species = t.species;
      leaf.anchor = t.position + s * (turn * rest.anchor);
      leaf.petiole = turn * rest.petiole;
      leaf.hinge = turn * rest.hinge;
      leaf.rest_normal = turn * rest.normal;
      leaf.tumble_axis = turn * rest.tumble_axis;
      leaf.lever = s * sp.lever();
      leaf.side = s * sp.side();
      leaf.area = s * s * sp.settings().area;
      leaf.mass = s * s * sp.mass();
      leaf.strength = rest.strength;
      leaf.phase = rest.phase;
      leaf.frequency = rest.frequency;
      leaf.position = leaf.anchor + leaf.lever * leaf.petiole;
      leaf.normal = leaf.rest_normal;
      leaves_.push_back(leaf);
    }
  }
}

LeafCounts LeafReference::counts() const {
  LeafCounts c;
  for (const WorldLeaf& leaf : leaves_) {
    switch (leaf.state) {
      case LeafState::attached:
        ++c.attached;
        break;
      case LeafState::flying:
        ++c.flying;
        break;
      case LeafState::landed:
        ++c.landed;
        break;
      case LeafState::exited:
        ++c.exited;
        break;
    }
  }
  c.shed = c.flying + c.landed + c.exited;
  return c;
}

void LeafReference::step(const fluid::GridSpec& spec, const std::vector<std::uint8_t>& solid,
                         const fluid::MacVelocity& wind, double time, double dt) {
  if (!std::isfinite(dt) || dt < 0.0) fail(fmt::format("dt must be finite and >= 0, got {}", dt));
  if (!solid.empty() && solid.size() != spec.cell_count())
    fail(fmt::format("solid has {} cells, the grid {}", solid.size(), spec.cell_count()));
  const Terrain terrain(spec, solid);
  for (WorldLeaf& leaf : leaves_) {
    const LeafSettings& settings = species_settings_[std::size_t(leaf.species)];
    if (leaf.state == LeafState::flying) {
      fly(leaf, settings, terrain, spec, wind, dt);
      continue;
    }
    if (leaf.state != LeafState::attached) continue;  // landed and exited leaves never move again
    // The wind of the cell that holds the rest blade centre: the grid resolves nothing below two cells, and
    // one value per cell is what lets the device step a million attached leaves cheaply (docs/leaves.md).
    const Eigen::Vector3d u = cell_centred_velocity(spec, wind, leaf.anchor + leaf.lever * leaf.petiole);
    // Shed on the step's wind's force on the blade in its pose at the step's start (the stochastic angles at
    // `time`, scaled by this wind); the leaf flies from the next step on, from that pose, at rest.
    if (settings.model == FlutterModel::stochastic) flutter_stochastic(leaf, settings, u, time);
    if (blade_force(leaf.area, leaf.normal, u) > leaf.strength) {
      leaf.state = LeafState::flying;
      leaf.velocity.setZero();
      continue;
    }
    if (settings.model == FlutterModel::pseudo_branch) flutter_pseudo_branch(leaf, settings, u, dt);
    if (settings.model == FlutterModel::stochastic) flutter_stochastic(leaf, settings, u, time + dt);
  }
}

}  // namespace fw::trees
