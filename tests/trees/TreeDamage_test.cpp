// trees/TreeDamage: the critical moments of a stem, the loads of a scaled tree, and the failure rule.
#include "trees/TreeDamage.hpp"

#include <catch2/catch.hpp>

#include <cmath>
#include <numbers>
#include <vector>

#include "tests/support/SmallSpecies.hpp"

namespace {

using fw::trees::StemLoads;
using fw::trees::TreeState;

const fw::trees::Material kWood{1.0e10, 3.85e9, 900.0};

StemLoads tapered_pole_loads() {
  std::vector<fw::trees::SkeletonNode> nodes;
  for (int i = 0; i <= 8; ++i) nodes.push_back({i - 1, Eigen::Vector3d(0.0, 0.0, 1.5 * i), 0.2 - 0.02 * i});
  const auto pole = fw::trees::Skeleton::from_nodes(std::move(nodes));
  const fw::trees::BeamModel model(pole, kWood);
  fw::trees::ModalSettings settings;
  settings.mode_count = 6;
  return StemLoads::compute(pole, model, fw::trees::ModalBasis::compute(model, settings));
}

}  // namespace

TEST_CASE("TreeDamage: a tapered pole's critical moments are M_b of each section and M_o of its volume",
          "[trees]") {
  const StemLoads stem = tapered_pole_loads();
  const auto strength = fw::trees::strength_preset(fw::trees::StrengthPreset::norway_spruce);
  const fw::trees::CriticalMoments critical = fw::trees::critical_moments(stem, strength);
  REQUIRE(critical.breaking.size() == 8);
  for (int j = 0; j < 8; ++j) {
    const double d = 2.0 * (0.2 - 0.02 * j);
    CHECK(critical.breaking[std::size_t(j)] ==
          Approx(0.9 * 36e6 * std::numbers::pi * d * d * d / 32.0).epsilon(1e-12));
  }
  // Frustums of radii 0.2 .. 0.04 over 1.5 m each.
  double volume = 0.0;
  for (int i = 0; i < 8; ++i) {
    const double a = 0.2 - 0.02 * i, b = a - 0.02;
    volume += std::numbers::pi * 1.5 * (a * a + a * b + b * b) / 3.0;
  }
  CHECK(critical.overturning == Approx(128.5 * 850.0 * volume).epsilon(1e-12));
  CHECK(critical.weakest_section() == 7);  // the thinnest section below the top
  CHECK(critical.least() == Approx(std::min(critical.breaking[7], critical.overturning)));
}

TEST_CASE("TreeDamage: a tree's loads at scale s are those of the tree grown by s against its own strength",
          "[trees]") {
  const fw::trees::Skeleton tree = fw::test::asymmetric_skeleton();
  const fw::trees::BeamModel model(tree, kWood);
  fw::trees::ModalSettings settings;
  settings.mode_count = 6;
  const auto modes = fw::trees::ModalBasis::compute(model, settings);
  const StemLoads stem = StemLoads::compute(tree, model, modes);
  const auto strength = fw::trees::strength_preset(fw::trees::StrengthPreset::scots_pine);
  constexpr double s = 1.4;
  const auto grown = tree.transformed(Eigen::Matrix3d::Identity(), Eigen::Vector3d::Zero(), s);
  const fw::trees::BeamModel grown_model(grown, kWood);
  const StemLoads grown_stem = StemLoads::compute(grown, grown_model, modes.scaled(s));
  Eigen::VectorXd q(6);
  q << 0.4, -0.3, 0.2, 0.1, -0.05, 0.02;
  const auto load = fw::trees::tree_load(stem, fw::trees::critical_moments(stem, strength), s, q);
  const auto direct =
      fw::trees::tree_load(grown_stem, fw::trees::critical_moments(grown_stem, strength), 1.0, q);
  // Similarity is exact algebra: the two differ by the rounding of two assemblies.
  CHECK((load.utilisation - direct.utilisation).norm() < 1e-9 * direct.utilisation.norm());
  CHECK(load.overturning == Approx(direct.overturning).epsilon(1e-9));
  CHECK(load.root_moment == Approx(direct.root_moment).epsilon(1e-9));
}

TEST_CASE("TreeDamage: a tree fails once, by the larger ratio, and keeps its maxima", "[trees]") {
  const StemLoads stem = tapered_pole_loads();
  fw::trees::TreeDamageRecord record;
  fw::trees::TreeLoad load;
  load.utilisation = Eigen::Vector3d(0.5, 0.8, 0.7);
  load.overturning = 0.6;
  load.root_moment = 1000.0;
  CHECK_FALSE(fw::trees::record_load(record, load, 1.0, {9.0, 0.0, 0.0}, 1.0, stem));
  CHECK(record.state == TreeState::standing);
  CHECK(record.max_utilisation == 0.8);

  load.utilisation = Eigen::Vector3d(0.9, 1.3, 1.1);
  load.overturning = 1.2;
  load.root_moment = 2000.0;
  CHECK(fw::trees::record_load(record, load, 2.5, {20.0, 3.0, 0.0}, 2.0, stem));
  CHECK(record.state == TreeState::broken);  // 1.3 at section 1 beats 1.2 at the root
  CHECK(record.failed_section == 1);
  CHECK(record.break_height == Approx(2.0 * 1.5));  // scale 2 x section 1's 1.5 m
  CHECK(record.time == 2.5);
  CHECK(record.top_wind == Eigen::Vector3d(20.0, 3.0, 0.0));
  CHECK(record.max_base_moment == 2000.0);

  // Later and larger loads raise the maxima but not the failure.
  load.overturning = 3.0;
  CHECK_FALSE(fw::trees::record_load(record, load, 3.0, {30.0, 0.0, 0.0}, 2.0, stem));
  CHECK(record.state == TreeState::broken);
  CHECK(record.time == 2.5);
  CHECK(record.max_utilisation == 3.0);

  fw::trees::TreeDamageRecord uprooted;
  load.utilisation = Eigen::Vector3d(0.9, 1.1, 1.0);
  load.overturning = 1.4;
  CHECK(fw::trees::record_load(uprooted, load, 4.0, {25.0, 0.0, 0.0}, 1.0, stem));
  CHECK(uprooted.state == TreeState::overturned);
  CHECK(uprooted.failed_section == -1);
  CHECK(uprooted.break_height == 0.0);
  CHECK(std::string(fw::trees::tree_state_name(uprooted.state)) == "overturned");
}
