#include "trees/ForestLayout.hpp"

#include <catch2/catch.hpp>

#include <cmath>
#include <numbers>
#include <stdexcept>
#include <vector>

using fw::trees::place_stand;
using fw::trees::PlacedTree;
using fw::trees::StandLayout;
using fw::trees::StandSpec;

namespace {

StandSpec stand_of(StandLayout layout) {
  StandSpec stand;
  stand.species = 2;
  stand.min = {60.0, 20.0};
  stand.max = {160.0, 100.0};
  stand.layout = layout;
  stand.spacing = 6.0;
  stand.scale_min = 0.85;
  stand.scale_max = 1.15;
  stand.seed = 11;
  return stand;
}

}  // namespace

TEST_CASE("ForestLayout: a Poisson stand keeps every pair of trees at least the spacing apart", "[layout]") {
  const StandSpec stand = stand_of(StandLayout::poisson);
  const std::vector<PlacedTree> trees = place_stand(stand);
  const double area = 100.0 * 80.0;
  // Bridson sampling reaches about 0.6-0.7 trees per spacing^2; a hexagonal packing would hold 1.15.
  // Tolerance: at least 0.5 / spacing^2 and at most the hexagonal bound.
  CHECK(double(trees.size()) > 0.5 * area / (6.0 * 6.0));
  CHECK(double(trees.size()) < 1.155 * area / (6.0 * 6.0) + 50.0);
  double closest = 1e300;
  for (std::size_t a = 0; a < trees.size(); ++a) {
    for (std::size_t b = a + 1; b < trees.size(); ++b) {
      closest = std::min(closest, (trees[a].position - trees[b].position).norm());
    }
  }
  CHECK(closest >= 6.0);
  for (const PlacedTree& t : trees) {
    CHECK(t.species == 2);
    CHECK(t.position.x() >= 60.0);
    CHECK(t.position.x() <= 160.0);
    CHECK(t.position.y() >= 20.0);
    CHECK(t.position.y() <= 100.0);
    CHECK(t.scale >= 0.85);
    CHECK(t.scale <= 1.15);
    CHECK(t.yaw_rad >= 0.0);
    CHECK(t.yaw_rad < 2.0 * std::numbers::pi);
  }
}

TEST_CASE("ForestLayout: a Poisson stand leaves no large gaps", "[layout]") {
  const std::vector<PlacedTree> trees = place_stand(stand_of(StandLayout::poisson));
  // Every point of the region is within 2 spacings of a tree (Bridson stops only when no annulus 1-2 r around
  // any tree has room). Probe a lattice of points; tolerance: 2 spacings plus rounding.
  for (double x = 61.0; x < 160.0; x += 3.0) {
    for (double y = 21.0; y < 100.0; y += 3.0) {
      double nearest = 1e300;
      for (const PlacedTree& t : trees)
        nearest = std::min(nearest, (t.position - Eigen::Vector2d(x, y)).norm());
      CHECK(nearest <= 2.0 * 6.0 + 1e-9);
    }
  }
}

TEST_CASE("ForestLayout: a grid stand is a centred lattice at the spacing", "[layout]") {
  const std::vector<PlacedTree> trees = place_stand(stand_of(StandLayout::grid));
  // 100 m / 6 m -> 17 columns (96 m wide), 80 m / 6 m -> 14 rows (78 m tall), centred.
  REQUIRE(trees.size() == 17u * 14u);
  CHECK(trees.front().position.x() == Approx(62.0).epsilon(1e-12));
  CHECK(trees.front().position.y() == Approx(21.0).epsilon(1e-12));
  CHECK(trees.back().position.x() == Approx(158.0).epsilon(1e-12));
  CHECK(trees.back().position.y() == Approx(99.0).epsilon(1e-12));
  CHECK((trees[1].position - trees[0].position).norm() == Approx(6.0).epsilon(1e-12));
}

TEST_CASE("ForestLayout: the same seed gives the same stand, another seed another", "[layout]") {
  StandSpec stand = stand_of(StandLayout::poisson);
  const auto a = place_stand(stand);
  const auto b = place_stand(stand);
  REQUIRE(a.size() == b.size());
  for (std::size_t i = 0; i < a.size(); ++i) {
    CHECK(a[i].position == b[i].position);
    CHECK(a[i].yaw_rad == b[i].yaw_rad);
    CHECK(a[i].scale == b[i].scale);
  }
  stand.seed = 12;
  const auto c = place_stand(stand);
  CHECK((c.size() != a.size() || c[0].position != a[0].position));
}

TEST_CASE("ForestLayout: bad stands are rejected with the class name", "[layout]") {
  StandSpec stand = stand_of(StandLayout::grid);
  stand.spacing = 0.0;
  CHECK_THROWS_WITH(place_stand(stand), Catch::Contains("StandSpec: spacing"));
  stand = stand_of(StandLayout::grid);
  stand.max = stand.min;
  CHECK_THROWS_WITH(place_stand(stand), Catch::Contains("StandSpec: the region"));
  stand = stand_of(StandLayout::grid);
  stand.scale_min = 1.2;
  CHECK_THROWS_WITH(place_stand(stand), Catch::Contains("StandSpec: scales"));
  stand = stand_of(StandLayout::poisson);
  stand.spacing = 0.006;  // millimetres typed as metres
  CHECK_THROWS_WITH(place_stand(stand), Catch::Contains("is the spacing in metres?"));
}
