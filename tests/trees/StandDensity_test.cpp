// A stand's leaf area index: the forests' range, and the crown leaf area index that gives a stand of placed,
// scaled and turned trees the leaf area index asked for.
#include "trees/StandDensity.hpp"

#include <catch2/catch.hpp>

#include <Eigen/Geometry>

#include <stdexcept>
#include <vector>

#include "tests/support/SmallSpecies.hpp"
#include "trees/Foliage.hpp"

using fw::trees::crown_leaf_area_index;
using fw::trees::PlacedTree;
using fw::trees::StandDensity;

TEST_CASE("StandDensity: a stand is forest-like from 0.3 to 12 m^2 of leaf per m^2 of ground, ends included",
          "[stand]") {
  StandDensity density;
  density.ground_area = 100.0;
  const auto with_lai = [&](double lai) {
    density.leaf_area = lai * density.ground_area;
    return density.forest_like();
  };
  CHECK(with_lai(4.0));
  CHECK(with_lai(StandDensity::kForestLeafAreaIndexLow));
  CHECK(with_lai(StandDensity::kForestLeafAreaIndexHigh));
  CHECK_FALSE(with_lai(0.29));
  CHECK_FALSE(with_lai(12.5));
  CHECK_FALSE(with_lai(0.0));
  // The figures themselves: per the region's ground, and per the columns' ground.
  density.leaf_area = 350.0;
  CHECK(density.leaf_area_index() == 3.5);
  CHECK(density.frontal_area_index() == 0.0);  // no column
  density.column_ground_area = 96.0;
  density.column_frontal_area = 384.0;
  CHECK(density.frontal_area_index() == 4.0);
  // The largest leaf area index a stand may be given lies above the forests' range.
  CHECK(StandDensity::kMaxLeafAreaIndex > StandDensity::kForestLeafAreaIndexHigh);
}

TEST_CASE(
    "StandDensity: crowns at crown_leaf_area_index give the stand its leaf area index, at any scale and yaw",
    "[stand]") {
  const fw::trees::Skeleton tree = fw::test::asymmetric_skeleton();
  const double crown_area = fw::trees::Foliage::of(tree, 1.0).crown_projected_area;
  REQUIRE(crown_area > 0.0);
  std::vector<PlacedTree> placed;
  for (int k = 0; k < 7; ++k) {
    PlacedTree t;
    t.position = {3.0 * k, 1.5 * (k % 3)};
    t.yaw_rad = 0.9 * k;
    t.scale = 0.8 + 0.07 * k;
    placed.push_back(t);
  }
  constexpr double kGround = 60.0, kStandLai = 2.5;  // m^2; m^2/m^2
  const double crown_lai = crown_leaf_area_index(kStandLai, kGround, crown_area, placed);
  // The foliage of each tree as the canopy computes it, on its world skeleton (turned, moved, scaled).
  double leaf_area = 0.0;
  for (const PlacedTree& t : placed) {
    const fw::trees::Skeleton world =
        tree.transformed(Eigen::AngleAxisd(t.yaw_rad, Eigen::Vector3d::UnitZ()).toRotationMatrix(),
                         Eigen::Vector3d(t.position.x(), t.position.y(), 0.0), t.scale);
    leaf_area += fw::trees::Foliage::of(world, crown_lai).leaf_area;
  }
  // The hulls of turned copies equal the species' but for rounding: 1e-12 relative.
  CHECK(leaf_area / kGround == Approx(kStandLai).epsilon(1e-12));

  // What it refuses: no leaf area index, or one past the limit; no ground; no trees; a crown without area.
  CHECK_THROWS_AS(crown_leaf_area_index(0.0, kGround, crown_area, placed), std::invalid_argument);
  CHECK_THROWS_AS(crown_leaf_area_index(StandDensity::kMaxLeafAreaIndex * 1.01, kGround, crown_area, placed),
                  std::invalid_argument);
  CHECK_NOTHROW(crown_leaf_area_index(StandDensity::kMaxLeafAreaIndex, kGround, crown_area, placed));
  CHECK_THROWS_AS(crown_leaf_area_index(kStandLai, 0.0, crown_area, placed), std::invalid_argument);
  CHECK_THROWS_AS(crown_leaf_area_index(kStandLai, kGround, crown_area, {}), std::invalid_argument);
  CHECK_THROWS_AS(crown_leaf_area_index(kStandLai, kGround, 0.0, placed), std::invalid_argument);
}
