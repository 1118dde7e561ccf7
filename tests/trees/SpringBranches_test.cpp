// trees/SpringBranches and trees/BranchPose: Ota's cantilever springs bend each element by its own load as a
// flat spring does, up to the cap; a hanging element's tip moves downwind (Yildiz's fix); the sine sways a
// bent element more; and the pose keeps every element's length.
#include "trees/SpringBranches.hpp"

#include <catch2/catch.hpp>

#include <cmath>
#include <numbers>
#include <vector>

#include "tests/support/BranchModels.hpp"
#include "trees/BranchPose.hpp"
#include "trees/Skeleton.hpp"
#include "trees/TreeGenerator.hpp"

namespace {

using fw::test::uniform_loads;

using fw::trees::BranchElements;
using fw::trees::Material;
using fw::trees::Skeleton;
using fw::trees::SkeletonNode;
using fw::trees::SpringSettings;
using fw::trees::WindBasisSettings;

const Material kWood{1.0e10, 3.85e9, 900.0};

// A trunk up the z axis and one branch hanging from its top, straight down: a weeping tree's twig.
Skeleton trunk_and_hanging_branch(double radius) {
  return Skeleton::from_nodes({{-1, {0.0, 0.0, 0.0}, 0.1},
                               {0, {0.0, 0.0, 2.0}, 0.08},
                               {1, {0.5, 0.0, 2.0}, radius},
                               {2, {0.5, 0.0, 1.0}, radius}});
}

SpringSettings no_sway() {
  SpringSettings settings;
  settings.sway_amplitude = 0.0;
  return settings;
}

}  // namespace

TEST_CASE("SpringBranches: an element bends by atan(P / (k L)) about its axis x load, k = E D^4 / (4 L^3)",
          "[trees]") {
  const Skeleton stick = Skeleton::from_nodes({{-1, {0.0, 0.0, 0.0}, 0.01}, {0, {0.0, 0.0, 1.5}, 0.01}});
  const WindBasisSettings drag;
  const BranchElements elements = BranchElements::of(stick, kWood, drag);
  const double D = 0.02, L = 1.5;
  CHECK(elements[1].spring_stiffness ==
        Approx(kWood.youngs_modulus * std::pow(D, 4) / (4.0 * std::pow(L, 3))));
  const Eigen::Vector3d wind(0.0, 12.0, 0.0);
  const std::vector<Eigen::Vector3d> loads = uniform_loads(elements, wind);
  const double P = loads[1].norm();
  CHECK(P == Approx(0.5 * drag.air_density * drag.branch_drag_coefficient * D * L * 144.0));
  for (double scale : {1.0, 2.5}) {
    // At scale s the load grows as s^2 (drag per metre and length), k as s and L as s: the same angle.
    std::vector<Eigen::Vector3d> scaled = loads;
    for (Eigen::Vector3d& load : scaled) load *= scale * scale;
    const auto angles = fw::trees::spring_angles(elements, no_sway(), scale, scaled, {0.0, 0.0}, 0.0);
    const double expected = std::atan(P / elements[1].spring_stiffness / L);
    CHECK(angles[1].norm() == Approx(expected).epsilon(1e-12));
    // About z x y = -x: the tip moves along +y, with the wind.
    CHECK(angles[1].normalized().isApprox(Eigen::Vector3d(-1.0, 0.0, 0.0)));
    const Eigen::MatrixX3d u = fw::trees::branch_displacements(elements, scale, angles);
    CHECK(u(1, 1) == Approx(scale * L * std::sin(expected)));
  }
}

TEST_CASE("SpringBranches: the bend stops at max_angle_deg, and the wind along an element bends nothing",
          "[trees]") {
  const Skeleton stick = Skeleton::from_nodes({{-1, {0.0, 0.0, 0.0}, 0.002}, {0, {0.0, 0.0, 1.0}, 0.002}});
  const BranchElements elements = BranchElements::of(stick, kWood, WindBasisSettings{});
  SpringSettings settings = no_sway();
  settings.max_angle_deg = 15.0;
  const auto bent = fw::trees::spring_angles(elements, settings, 1.0,
                                             uniform_loads(elements, {30.0, 0.0, 0.0}), {0.0, 0.0}, 0.0);
  CHECK(bent[1].norm() == Approx(15.0 * std::numbers::pi / 180.0));
  const auto along = fw::trees::spring_angles(elements, settings, 1.0,
                                              uniform_loads(elements, {0.0, 0.0, 30.0}), {0.0, 0.0}, 0.0);
  CHECK(along[1].norm() == 0.0);
}

TEST_CASE("SpringBranches: a hanging element's tip moves downwind, its angle from the vertical decreasing",
          "[trees]") {
  const Skeleton tree = trunk_and_hanging_branch(0.004);
  const BranchElements elements = BranchElements::of(tree, kWood, WindBasisSettings{});
  const auto angles = fw::trees::spring_angles(
      elements, no_sway(), 1.0, uniform_loads(elements, {10.0, 0.0, 0.0}), std::vector<double>(4, 0.0), 0.0);
  const Eigen::MatrixX3d u = fw::trees::branch_displacements(elements, 1.0, angles);
  // Yildiz's weeping tree: turned about the world's y axis as an upright segment is, the hanging twig's tip
  // would swing into the wind (-x). Here it swings with it, and rises: it turns towards the horizontal.
  const Eigen::Vector3d twig =
      tree.node(3).position + u.row(3).transpose() - tree.node(2).position - u.row(2).transpose();
  CHECK(twig.x() > 0.0);
  CHECK(twig.z() > -1.0);
  CHECK(twig.norm() == Approx(1.0).epsilon(1e-12));  // its length kept
}

TEST_CASE("SpringBranches: the sine sways a bent element by sway_amplitude theta / theta_max of its load",
          "[trees]") {
  const Skeleton stick = Skeleton::from_nodes({{-1, {0.0, 0.0, 0.0}, 0.004}, {0, {0.0, 0.0, 1.0}, 0.004}});
  const BranchElements elements = BranchElements::of(stick, kWood, WindBasisSettings{});
  SpringSettings settings;
  settings.sway_amplitude = 0.3;
  settings.sway_frequency_hz = 0.25;
  const auto loads = uniform_loads(elements, {6.0, 0.0, 0.0});
  const double phase = 0.7;
  const double bend = loads[1].norm() / elements[1].spring_stiffness / elements[1].length;
  const double theta_max = settings.max_angle_deg * std::numbers::pi / 180.0;
  REQUIRE(std::atan(bend) < theta_max);
  const double a = settings.sway_amplitude * std::atan(bend) / theta_max;
  for (double t : {0.0, 0.5, 1.3, 2.9}) {
    const auto angles = fw::trees::spring_angles(elements, settings, 1.0, loads, {0.0, phase}, t);
    const double expected = std::atan(bend * (1.0 + a * std::sin(2.0 * std::numbers::pi * 0.25 * t + phase)));
    CHECK(angles[1].norm() == Approx(expected).epsilon(1e-12));
  }
  // The phases: a hash of the tree and the entry, in [0, 2 pi), different from tree to tree.
  const std::vector<double> a0 = fw::trees::spring_phases(0, 50), a1 = fw::trees::spring_phases(1, 50);
  int same = 0;
  for (std::size_t j = 0; j < a0.size(); ++j) {
    CHECK(a0[j] >= 0.0);
    CHECK(a0[j] < 2.0 * std::numbers::pi);
    same += a0[j] == a1[j];
  }
  CHECK(same == 0);
}

TEST_CASE("BranchPose: every element keeps its rest length at any angles, and small angles turn it linearly",
          "[trees]") {
  fw::trees::GeneratorSettings settings;
  settings.preset = "weeping";
  settings.height = 6.0;
  const Skeleton tree = fw::trees::generate_tree(settings);
  const BranchElements elements = BranchElements::of(tree, kWood, WindBasisSettings{});
  std::vector<Eigen::Vector3d> angles(static_cast<std::size_t>(elements.size()), Eigen::Vector3d::Zero());
  for (int j = 1; j < elements.size(); ++j)
    angles[std::size_t(j)] = Eigen::Vector3d(std::sin(j), std::cos(3.0 * j), std::sin(0.5 * j)) * 0.4;
  const double s = 1.7;
  const Eigen::MatrixX3d u = fw::trees::branch_displacements(elements, s, angles);
  for (int j = 1; j < elements.size(); ++j) {
    const fw::trees::BranchElement& e = elements[j];
    const Eigen::Vector3d moved = s * e.rest + (u.row(e.node) - u.row(e.parent_node)).transpose();
    CHECK(moved.norm() == Approx(s * e.length).epsilon(1e-12));
  }
  // One joint turned by a small angle: its subtree turns rigidly about the joint, u = theta x (x - x_joint).
  std::vector<Eigen::Vector3d> one(angles.size(), Eigen::Vector3d::Zero());
  const int joint = elements.size() / 2;
  one[std::size_t(joint)] = Eigen::Vector3d(1e-7, -2e-7, 0.5e-7);
  const Eigen::MatrixX3d small = fw::trees::branch_displacements(elements, 1.0, one);
  const Eigen::Vector3d pivot = tree.node(elements[joint].parent_node).position;
  const Eigen::Vector3d tip = tree.node(elements[joint].node).position;
  const Eigen::Vector3d expected = one[std::size_t(joint)].cross(tip - pivot);
  CHECK((small.row(elements[joint].node).transpose() - expected).norm() < 1e-6 * expected.norm());
}
