#include "trees/RigidBranches.hpp"

#include <fmt/format.h>

#include <cmath>
#include <stdexcept>

#include "kernels/shared_types.h"

namespace fw::trees {
namespace {

Eigen::Matrix3d skew(const Eigen::Vector3d& r) {
  Eigen::Matrix3d m;
  m << 0.0, -r.z(), r.y(), r.z(), 0.0, -r.x(), -r.y(), r.x(), 0.0;
  return m;
}

// A spatial inertia about a joint, in blocks: [[A, B], [B^T, M]] (angular rows first).
struct Inertia {
  Eigen::Matrix3d A = Eigen::Matrix3d::Zero(), B = Eigen::Matrix3d::Zero(), M = Eigen::Matrix3d::Zero();
};

// A spatial force about a joint: moment n and force f.
struct Force {
  Eigen::Vector3d n = Eigen::Vector3d::Zero(), f = Eigen::Vector3d::Zero();
};

// What the downward pass needs of a joint: its articulated inertia's angular columns (A, B), the inverse
// of its joint term D and its joint force u.
struct JointSolve {
  Eigen::Matrix3d A, B, D_inverse;
  Eigen::Vector3d u;
};

// Entry j's rod about its joint at scale s: centre c = s rest / 2, mass s^3 m, inertia about the centre
// (m L^2 / 12) across the axis and the rod's own along it.
Inertia rod_inertia(const BranchElement& e, double s) {
  const double s3 = s * s * s, s5 = s3 * s * s;
  const Eigen::Vector3d axis = e.rest / e.length;
  const Eigen::Matrix3d along = axis * axis.transpose();
  const double mass = s3 * e.mass;
  const Eigen::Matrix3d centre_inertia =
      s5 *
      (e.mass * e.length * e.length / 12.0 * (Eigen::Matrix3d::Identity() - along) + e.axial_inertia * along);
  const Eigen::Matrix3d c = skew(0.5 * s * e.rest);
  return {centre_inertia - mass * c * c, mass * c, mass * Eigen::Matrix3d::Identity()};
}

// The inertia and force moved from a child's joint to its parent's, r = child joint - parent joint.
void shift_into(const Inertia& child, const Force& force, const Eigen::Vector3d& r, Inertia& parent,
                Force& parent_force) {
  const Eigen::Matrix3d R = skew(r);
  parent.A += child.A - child.B * R + R * child.B.transpose() - R * child.M * R;
  parent.B += child.B + R * child.M;
  parent.M += child.M;
  parent_force.n += force.n + r.cross(force.f);
  parent_force.f += force.f;
}

}  // namespace

double rigid_damping(double zeta, double omega_1) {
  if (!(std::isfinite(zeta) && zeta >= 0.0 && std::isfinite(omega_1) && omega_1 > 0.0))
    throw std::invalid_argument(
        fmt::format("rigid_damping: zeta must be >= 0 and omega_1 > 0, got {} and {}", zeta, omega_1));
  return 2.0 * zeta / omega_1;
}

RigidBranches::RigidBranches(const BranchElements& elements, double scale, double damping)
    : elements_(elements), scale_(scale), damping_(damping) {
  if (!(std::isfinite(scale) && scale > 0.0))
    throw std::invalid_argument(
        fmt::format("RigidBranches: the scale must be finite and > 0, got {}", scale));
  if (!(std::isfinite(damping) && damping >= 0.0))
    throw std::invalid_argument(
        fmt::format("RigidBranches: the damping must be finite and >= 0, got {}", damping));
}

std::vector<Eigen::Vector3d> RigidBranches::joint_moments(const std::vector<Eigen::Vector3d>& loads) const {
  const int n = elements_.size();
  if (int(loads.size()) != n)
    throw std::invalid_argument(fmt::format("RigidBranches: {} loads for {} entries", loads.size(), n));
  std::vector<Force> beyond(static_cast<std::size_t>(n));
  for (int j = n - 1; j >= 1; --j) {
    const BranchElement& e = elements_[j];
    Force& here = beyond[std::size_t(j)];
    here.n += (0.5 * scale_ * e.rest).cross(loads[std::size_t(j)]);
    here.f += loads[std::size_t(j)];
    if (e.parent_entry > 0) {
      const Eigen::Vector3d r = scale_ * elements_[e.parent_entry].rest;
      Force& parent = beyond[std::size_t(e.parent_entry)];
      parent.n += here.n + r.cross(here.f);
      parent.f += here.f;
    }
  }
  std::vector<Eigen::Vector3d> moments(std::size_t(n), Eigen::Vector3d::Zero());
  for (int j = 1; j < n; ++j) moments[std::size_t(j)] = beyond[std::size_t(j)].n;
  return moments;
}

RigidBranchState RigidBranches::equilibrium(const std::vector<Eigen::Vector3d>& loads) const {
  const std::vector<Eigen::Vector3d> moments = joint_moments(loads);
  const double s3 = scale_ * scale_ * scale_;
  RigidBranchState state;
  state.angle.assign(moments.size(), Eigen::Vector3d::Zero());
  state.rate.assign(moments.size(), Eigen::Vector3d::Zero());
  for (int j = 1; j < elements_.size(); ++j)
    state.angle[std::size_t(j)] = (s3 * elements_[j].joint_stiffness).ldlt().solve(moments[std::size_t(j)]);
  return state;
}

void RigidBranches::step(const std::vector<Eigen::Vector3d>& loads, double dt,
                         RigidBranchState& state) const {
  const int n = elements_.size();
  if (int(loads.size()) != n || int(state.angle.size()) != n || int(state.rate.size()) != n)
    throw std::invalid_argument(fmt::format("RigidBranches: the loads and the state need {} entries", n));
  if (!(std::isfinite(dt) && dt >= 0.0))
    throw std::invalid_argument(fmt::format("RigidBranches: dt must be finite and >= 0, got {}", dt));
  const double s = scale_, s3 = s * s * s;
  // Up the tree: every joint's articulated inertia and force, children first.
  std::vector<Inertia> inertia(static_cast<std::size_t>(n));
  std::vector<Force> bias(static_cast<std::size_t>(n));
  std::vector<JointSolve> solve(static_cast<std::size_t>(n));
  for (int j = n - 1; j >= 1; --j) {
    const BranchElement& e = elements_[j];
    Inertia& I = inertia[std::size_t(j)];
    const Inertia rod = rod_inertia(e, s);
    I.A += rod.A, I.B += rod.B, I.M += rod.M;
    // The bias force is minus the external force: the drag at the centre.
    const Eigen::Vector3d& F = loads[std::size_t(j)];
    Force& p = bias[std::size_t(j)];
    p.n -= (0.5 * s * e.rest).cross(F);
    p.f -= F;
    const Eigen::Matrix3d K = s3 * e.joint_stiffness;
    const Eigen::Vector3d& theta = state.angle[std::size_t(j)];
    const Eigen::Vector3d& rate = state.rate[std::size_t(j)];
    // The joint torque at the weighted time, -K theta_w - C theta'_w, less its part in theta''.
    const double w = double(FW_RIGID_IMPLICIT_WEIGHT);
    const Eigen::Vector3d torque = -K * (theta + w * dt * rate) - damping_ * K * rate;
    const Eigen::Matrix3d D = I.A + (w * dt * damping_ + w * w * dt * dt) * K;
    JointSolve& js = solve[std::size_t(j)];
    js.A = I.A;
    js.B = I.B;
    js.D_inverse = D.inverse();
    js.u = torque - p.n;
    if (e.parent_entry > 0) {
      const Eigen::Matrix3d AD = I.A * js.D_inverse;
      const Eigen::Matrix3d BtD = I.B.transpose() * js.D_inverse;
      const Inertia articulated{I.A - AD * I.A, I.B - AD * I.B, I.M - BtD * I.B};
      const Force passed{p.n + AD * js.u, p.f + BtD * js.u};
      shift_into(articulated, passed, s * elements_[e.parent_entry].rest,
                 inertia[std::size_t(e.parent_entry)], bias[std::size_t(e.parent_entry)]);
    }
  }
  // Down the tree: every joint's acceleration from its parent's, the root fixed.
  std::vector<Eigen::Vector3d> angular(std::size_t(n), Eigen::Vector3d::Zero()),
      linear(std::size_t(n), Eigen::Vector3d::Zero());
  for (int j = 1; j < n; ++j) {
    const BranchElement& e = elements_[j];
    Eigen::Vector3d alpha = Eigen::Vector3d::Zero(), a = Eigen::Vector3d::Zero();
    if (e.parent_entry > 0) {
      alpha = angular[std::size_t(e.parent_entry)];
      a = linear[std::size_t(e.parent_entry)] + alpha.cross(s * elements_[e.parent_entry].rest);
    }
    const JointSolve& js = solve[std::size_t(j)];
    const Eigen::Vector3d joint = js.D_inverse * (js.u - js.A * alpha - js.B * a);
    angular[std::size_t(j)] = alpha + joint;
    linear[std::size_t(j)] = a;
    const double w = double(FW_RIGID_IMPLICIT_WEIGHT);
    const Eigen::Vector3d rate = state.rate[std::size_t(j)];
    state.rate[std::size_t(j)] += dt * joint;
    state.angle[std::size_t(j)] += dt * ((1.0 - w) * rate + w * state.rate[std::size_t(j)]);
  }
}

}  // namespace fw::trees
