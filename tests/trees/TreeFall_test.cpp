// trees/TreeFall: a failed tree topples like a rigid rod and ends lying on the ground downwind, a broken top
// beside its stump.
#include "trees/TreeFall.hpp"

#include <catch2/catch.hpp>

#include <cmath>
#include <numbers>
#include <vector>

#include "trees/Gravity.hpp"

namespace {

using fw::trees::TreeState;

// A pole of 10 equal elements, 20 m, its species with a few modes, one instance at (5, 7, 0) of scale 1.
fw::trees::Forest pole_forest() {
  std::vector<fw::trees::SkeletonNode> nodes;
  for (int i = 0; i <= 10; ++i) nodes.push_back({i - 1, Eigen::Vector3d(0.0, 0.0, 2.0 * i), 0.2 - 0.015 * i});
  fw::trees::SpeciesSettings settings;
  settings.modal.mode_count = 4;
  settings.wind.samples = 1;
  std::vector<fw::trees::SpeciesBasis> species = {
      fw::trees::SpeciesBasis::compute(fw::trees::Skeleton::from_nodes(std::move(nodes)), settings)};
  return fw::trees::Forest(std::move(species), {{0, {5.0, 7.0, 0.0}, 0.3, 1.0}});
}

}  // namespace

TEST_CASE("TreeFall: a rod topples from its start angle to flat in the time its equation gives", "[trees]") {
  // Small angles: theta grows as theta0 cosh(t / tau), tau = sqrt(2 L / (3 g)); the rod is flat a little
  // after tau acosh(pi / 2 / theta0) (the sine's saturation slows the last part less than that: between
  // 0.9 and 1.2 of it).
  constexpr double L = 20.0;
  const double tau = std::sqrt(2.0 * L / (3.0 * fw::trees::kGravity));
  const double small_angle = tau * std::acosh(std::numbers::pi / 2.0 / fw::trees::kFallStartAngle);
  const double duration = fw::trees::fall_duration(L);
  CHECK(duration > 0.9 * small_angle);
  CHECK(duration < 1.2 * small_angle);
  CHECK(fw::trees::fall_angle(0.0, L) == fw::trees::kFallStartAngle);
  CHECK(fw::trees::fall_angle(0.5 * duration, L) < fw::trees::fall_angle(0.8 * duration, L));
  CHECK(fw::trees::fall_angle(duration + 5.0, L) == std::numbers::pi / 2.0);
  // Early on the small-angle law holds (to 1% at theta < 0.2 rad).
  CHECK(fw::trees::fall_angle(0.3 * tau, L) ==
        Approx(fw::trees::kFallStartAngle * std::cosh(0.3)).epsilon(0.01));
  // A shorter rod falls sooner, as sqrt(L).
  CHECK(fw::trees::fall_duration(5.0) == Approx(0.5 * duration).epsilon(1e-3));
}

TEST_CASE("TreeFall: an overturned tree lies flat downwind, a broken top beside its stump", "[trees]") {
  const fw::trees::Forest forest = pole_forest();
  const auto geometry = fw::trees::FallGeometry::of(forest.species_of(0));
  const Eigen::Matrix3d rotation = forest.rotation(0);
  const Eigen::MatrixX3d rest = [&] {
    Eigen::MatrixX3d r(11, 3);
    for (int n = 0; n <= 10; ++n)
      r.row(n) = (rotation * forest.species_of(0).skeleton().node(n).position).transpose();
    return r;
  }();
  fw::trees::TreeDamageRecord uprooted;
  uprooted.state = TreeState::overturned;
  uprooted.time = 10.0;
  uprooted.top_wind = Eigen::Vector3d(3.0, 4.0, 1.0);  // falls toward (0.6, 0.8)
  const double later = 10.0 + fw::trees::fall_duration(20.0) + 1.0;
  const fw::trees::FallPose flat = fw::trees::fall_pose(uprooted, geometry, 1.0, later);
  CHECK(flat.pivot == 0);
  CHECK(flat.angle == std::numbers::pi / 2.0);
  const Eigen::MatrixX3d u = fw::trees::fall_displacements(forest, 0, flat);
  for (int n = 0; n <= 10; ++n) {
    INFO("node " << n);
    const Eigen::Vector3d lying = rest.row(n).transpose() + u.row(n).transpose();
    // Node n at height 2n lies 2n along (0.6, 0.8) on the ground (1e-12: rounding of a rotation).
    CHECK((lying - Eigen::Vector3d(0.6 * 2.0 * n, 0.8 * 2.0 * n, 0.0)).norm() < 1e-12);
  }

  fw::trees::TreeDamageRecord broken;
  broken.state = TreeState::broken;
  broken.failed_section = 4;  // node 4, 8 m up
  broken.break_height = 8.0;
  broken.time = 10.0;
  broken.top_wind = Eigen::Vector3d(-5.0, 0.0, 0.0);
  const fw::trees::FallPose top = fw::trees::fall_pose(broken, geometry, 1.0, later);
  CHECK(top.pivot == 4);
  CHECK(top.drop == Approx(8.0));
  const Eigen::MatrixX3d v = fw::trees::fall_displacements(forest, 0, top);
  for (int n = 0; n <= 4; ++n) CHECK(v.row(n).norm() == 0.0);  // the stump stands
  for (int n = 5; n <= 10; ++n) {
    INFO("node " << n);
    const Eigen::Vector3d lying = rest.row(n).transpose() + v.row(n).transpose();
    CHECK((lying - Eigen::Vector3d(-2.0 * (n - 4), 0.0, 0.0)).norm() < 1e-12);  // on the ground, westward
  }
  // Halfway the top has not reached the ground.
  const fw::trees::FallPose falling = fw::trees::fall_pose(broken, geometry, 1.0, 10.0 + 0.5);
  CHECK(falling.angle < std::numbers::pi / 2.0);
  CHECK(falling.drop < 8.0);
}
