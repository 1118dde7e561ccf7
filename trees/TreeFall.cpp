#include "trees/TreeFall.hpp"

#include <fmt/format.h>

#include <cmath>
#include <limits>
#include <numbers>
#include <stdexcept>

#include "trees/Gravity.hpp"

namespace fw::trees {

namespace {

constexpr double kFlat = std::numbers::pi / 2.0;

// One RK4 step of theta'' = k sin(theta).
void rk4_step(double k, double h, double& theta, double& rate) {
  const auto accel = [k](double t) { return k * std::sin(t); };
  const double a1 = rate, b1 = accel(theta);
  const double a2 = rate + 0.5 * h * b1, b2 = accel(theta + 0.5 * h * a1);
  const double a3 = rate + 0.5 * h * b2, b3 = accel(theta + 0.5 * h * a2);
  const double a4 = rate + h * b3, b4 = accel(theta + h * a3);
  theta += h / 6.0 * (a1 + 2.0 * a2 + 2.0 * a3 + a4);
  rate += h / 6.0 * (b1 + 2.0 * b2 + 2.0 * b3 + b4);
}

// The fall from kFallStartAngle for `elapsed` seconds, or until flat (elapsed infinite: its duration).
double integrate(double elapsed, double length, double* duration) {
  if (!(length > 0.0) || !std::isfinite(length))
    throw std::invalid_argument(
        fmt::format("TreeFall: the length must be finite and positive, got {}", length));
  const double k = 1.5 * kGravity / length;
  double theta = kFallStartAngle, rate = 0.0, t = 0.0;
  while (t < elapsed) {
    const double h = std::min(kFallStep, elapsed - t);
    rk4_step(k, h, theta, rate);
    t += h;
    if (theta >= kFlat) {
      if (duration) *duration = t;
      return kFlat;
    }
  }
  return theta;
}

}  // namespace

double fall_angle(double elapsed, double length) {
  if (!(elapsed > 0.0)) return kFallStartAngle;
  return integrate(elapsed, length, nullptr);
}

double fall_duration(double length) {
  double duration = 0.0;
  integrate(std::numeric_limits<double>::infinity(), length, &duration);
  return duration;
}

FallGeometry FallGeometry::of(const SpeciesBasis& species) {
  FallGeometry geometry;
  geometry.height = species.skeleton().height();
  geometry.root = species.skeleton().root();
  for (const StemSection& section : species.stem_loads().sections())
    geometry.section_nodes.push_back(section.node);
  return geometry;
}

FallPose fall_pose(const TreeDamageRecord& record, const FallGeometry& geometry, double scale, double time) {
  if (record.state == TreeState::standing)
    throw std::invalid_argument("TreeFall: a standing tree does not fall");
  const double height = scale * geometry.height;
  FallPose pose;
  const bool broken = record.state == TreeState::broken;
  pose.pivot = broken ? geometry.section_nodes.at(std::size_t(record.failed_section)) : geometry.root;
  const double length = broken ? std::max(height - record.break_height, 1e-3 * height) : height;
  pose.angle = fall_angle(time - record.time, length);
  const Eigen::Vector2d wind = record.top_wind.head<2>();
  if (wind.norm() > 0.0) pose.direction = wind.normalized();
  pose.drop = broken ? record.break_height * (1.0 - std::cos(pose.angle)) : 0.0;
  return pose;
}

std::vector<int> skeleton_tour(const Skeleton& skeleton) {
  std::vector<int> tour(2 * std::size_t(skeleton.size()), 0);
  // Depth first from the root, children in index order: preorder indices, then each subtree's end.
  std::vector<std::pair<int, bool>> stack{{skeleton.root(), false}};
  int next = 0;
  while (!stack.empty()) {
    auto [node, done] = stack.back();
    stack.pop_back();
    if (done) {
      tour[2 * std::size_t(node) + 1] = next;
      continue;
    }
    tour[2 * std::size_t(node)] = next++;
    stack.push_back({node, true});
    const auto children = skeleton.children(node);
    for (auto it = children.rbegin(); it != children.rend(); ++it) stack.push_back({*it, false});
  }
  return tour;
}

Eigen::MatrixX3d fall_displacements(const Forest& forest, int instance, const FallPose& pose) {
  const Skeleton& skeleton = forest.species_of(instance).skeleton();
  const TreeInstance& tree = forest.instances()[std::size_t(instance)];
  const std::vector<int> tour = skeleton_tour(skeleton);
  const Eigen::Matrix3d rotation = forest.rotation(instance);
  const Eigen::Vector3d axis(-pose.direction.y(), pose.direction.x(), 0.0);  // z x d
  const Eigen::AngleAxisd turn(pose.angle, axis);
  const Eigen::Vector3d pivot = tree.scale * rotation * skeleton.node(pose.pivot).position;
  const int first = tour[2 * std::size_t(pose.pivot)], past = tour[2 * std::size_t(pose.pivot) + 1];
  Eigen::MatrixX3d u = Eigen::MatrixX3d::Zero(skeleton.size(), 3);
  for (int n = 0; n < skeleton.size(); ++n) {
    const int order = tour[2 * std::size_t(n)];
    if (order <= first || order >= past) continue;
    const Eigen::Vector3d v = tree.scale * rotation * skeleton.node(n).position - pivot;
    u.row(n) = (turn * v - v - pose.drop * Eigen::Vector3d::UnitZ()).transpose();
  }
  return u;
}

}  // namespace fw::trees
