#include <catch2/catch.hpp>

#include <filesystem>
#include <fstream>

#include "tests/support/Pictures.hpp"
#include "tests/support/RunFolders.hpp"
#include "tests/support/TempDir.hpp"
#include "viz/DamageMap.hpp"
#include "viz/RunFolder.hpp"

namespace fs = std::filesystem;
using fw::test::bytes;
using fw::test::colour_distance;

namespace {

// Inside a disc, away from its marks, the fill is one flat colour: the PNG's 8-bit rounding only.
constexpr int kColourTolerance = 1;
// Marks are black on a white halo: a pixel on one is darker than every fill and wind colour.
constexpr int kMarkDarkest = 40;

// A run of three frames at t = 0, 0.5, 1 s over a uniform 6 m/s wind (40 x 20 x 10 m), and its damage.csv:
// trees 8 m tall (discs 1.2 m in radius) at y = 10 m, and two 6 m tall at x = 34 m.
struct DamagedRun {
  fw::test::TempDir dir{"fw_viz"};
  fw::viz::DamageTable damage;
  DamagedRun() {
    fw::test::write_run(dir.path(), fw::test::UniformWind{}, {}, 3, 0.5);
    damage = fw::viz::read_damage_table(
        dir.write("damage.csv", fw::test::damage_csv({
                                    "0,spruce,6,10,8,0.3,standing,,,,1e4,5e4,6e4,0.5",
                                    "1,spruce,16,10,8,0.3,broken,0.2,3,21,1e5,5e4,6e4,1.3",
                                    "2,spruce,26,10,8,0.3,overturned,0.3,0,22,1e5,5e4,6e4,1.1",
                                    "3,spruce,34,5,6,0.2,broken,0.75,2,23,1e5,5e4,6e4,1.2",  // after frame 1
                                    "4,spruce,34,15,6,0.2,standing,,,,4e4,5e4,6e4,0.95",
                                })));
  }
  // Frame `index` drawn and read back.
  std::pair<fw::viz::DamageMap, fw::test::Picture> render(int index) const {
    const fw::viz::RunFolder run(dir.path());
    fw::viz::DamageMap map(run.load(run.select(index, std::nullopt)), damage, "storm", {});
    const fs::path png = fs::path(dir.path()) / "damage.png";
    map.canvas().write_png(png);
    return {std::move(map), fw::test::read_png(png)};
  }
};

// The pixel holding world point (x, y) shifted by (dx, dy) px.
std::array<int, 3> at(const fw::viz::DamageMap& map, const fw::test::Picture& image, double x, double y,
                      double dx = 0.0, double dy = 0.0) {
  const auto p = map.camera().to_pixel({x, y, 5.0});
  return image.at(int(p.x + dx), int(p.y + dy));
}

bool dark(const std::array<int, 3>& c) {
  return std::max({c[0], c[1], c[2]}) < kMarkDarkest;
}

std::array<int, 3> fill(double utilisation) {
  return bytes(fw::viz::ColourMap::named("utilisation").colour(utilisation, 0.0, fw::viz::kUtilisationTop));
}

}  // namespace

TEST_CASE("DamageMap: each tree is a disc of its utilisation's colour, failed ones marked where they stand",
          "[viz]") {
  const DamagedRun run;
  const auto [map, image] = run.render(1);  // t = 0.5 s
  CHECK(map.counts() == std::array<int, 3>{3, 1, 1});
  const double r = map.disc_radius(run.damage.trees[0]);
  CHECK(r == Approx(1.2 * map.camera().pixels_per_metre()));
  REQUIRE(r > 20.0);
  // Standing trees: the map's colour for their utilisation, at the centre and halfway out.
  for (const auto& [x, y, u] : {std::tuple{6.0, 10.0, 0.5}, std::tuple{34.0, 15.0, 0.95}}) {
    INFO("tree at " << x << ", " << y);
    CHECK(colour_distance(at(map, image, x, y), fill(u)) <= kColourTolerance);
    CHECK(colour_distance(at(map, image, x, y, 0.4 * r), fill(u)) <= kColourTolerance);
  }
  // Below 1 greys, from 1 reds: 0.95 and 1.1 differ in hue, not in shade.
  const auto grey = fill(0.95), red = fill(1.1);
  CHECK(std::abs(grey[0] - grey[2]) <= 2);
  CHECK(red[0] - red[2] > 120);
  // Broken (x = 16 m): an X through the centre and along the diagonals, the fill beside it.
  CHECK(dark(at(map, image, 16, 10)));
  CHECK(dark(at(map, image, 16, 10, 0.4 * r, 0.4 * r)));
  CHECK(dark(at(map, image, 16, 10, -0.4 * r, 0.4 * r)));
  CHECK_FALSE(dark(at(map, image, 16, 10, 0.3 * r, 0.0)));
  CHECK(colour_distance(at(map, image, 16, 10, 0.6 * r, 0.0), fill(1.3)) <= kColourTolerance);
  // Overturned (x = 26 m): a square about the centre, its fill outside it; no X along the diagonal.
  CHECK(dark(at(map, image, 26, 10)));
  CHECK(dark(at(map, image, 26, 10, 0.3 * r, 0.0)));
  CHECK(dark(at(map, image, 26, 10, 0.0, -0.3 * r)));
  CHECK_FALSE(dark(at(map, image, 26, 10, 0.6 * r, 0.6 * r)));
  CHECK(colour_distance(at(map, image, 26, 10, 0.8 * r, 0.0), fill(1.1)) <= kColourTolerance);
  // Between the trees, the wind slice: the top of the wind map (the slice's fastest, 6 m/s).
  CHECK(colour_distance(at(map, image, 11, 10), bytes(fw::viz::ColourMap::named("wind").colour(1.0))) <=
        kColourTolerance);
}

TEST_CASE("DamageMap: a tree that fails after the frame's time is drawn standing in it", "[viz]") {
  const DamagedRun run;
  {
    const auto [map, image] = run.render(1);  // t = 0.5 s: tree 3 breaks at 0.75 s
    const double r = map.disc_radius(run.damage.trees[3]);
    CHECK(colour_distance(at(map, image, 34, 5), fill(1.2)) <= kColourTolerance);  // no mark at its centre
    CHECK(colour_distance(at(map, image, 34, 5, 0.3 * r, 0.3 * r), fill(1.2)) <= kColourTolerance);
  }
  const auto [map, image] = run.render(2);  // t = 1 s
  CHECK(map.counts() == std::array<int, 3>{2, 2, 1});
  CHECK(dark(at(map, image, 34, 5)));
  // At t = 0 every tree stands.
  CHECK(run.render(0).first.counts() == std::array<int, 3>{5, 0, 0});
}

TEST_CASE("DamageMap: the key shows the utilisation scale, failure marked at 1", "[viz]") {
  const DamagedRun run;
  const auto [map, image] = run.render(1);
  // The utilisation bar sits in the place of the trees' colour bar: wine red at its top, light grey at its
  // bottom, and the black line at 1 between them.
  const fw::viz::Viewport place = fw::viz::colour_bar_place(fw::viz::RenderSettings{}, 1);
  const int column = int(place.x + 0.5 * place.width);
  int top = -1, line = -1, bottom = -1;
  for (int j = int(place.y); j < int(place.y + place.height); ++j) {
    const auto c = image.at(column, j);
    if (top < 0 && colour_distance(c, fill(fw::viz::kUtilisationTop)) <= 3) top = j;
    if (line < 0 && dark(c)) line = j;
    if (colour_distance(c, fill(0.0)) <= 3) bottom = j;
  }
  CHECK(top >= 0);
  CHECK(line > top);
  CHECK(bottom > line);
}

TEST_CASE("DamageMap: only the top view", "[viz]") {
  const DamagedRun run;
  const fw::viz::RunFolder folder(run.dir.path());
  fw::viz::RenderSettings side;
  side.view = fw::viz::ViewKind::side;
  CHECK_THROWS_WITH(fw::viz::DamageMap(folder.load(folder.frames().back()), run.damage, "x", side),
                    Catch::Contains("render: --field damage: draws the top view only"));
}
