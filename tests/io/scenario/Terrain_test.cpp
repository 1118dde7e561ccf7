// terrain.raster: a raster GDAL reads places the run on its site (io/scenario/Terrain.cpp, docs/gis.md).
#include <fmt/format.h>
#include <catch2/catch.hpp>

#include <array>
#include <string>
#include <vector>

#include "io/Scenario.hpp"
#include "io/gis/GeoTiff.hpp"
#include "tests/support/ScenarioErrors.hpp"
#include "tests/support/TempDir.hpp"

namespace {

// A UTM zone 32 N raster: north-west corner (500,000 m E, 5,400,000 m N), 4 m pixels, 30 x 20 (120 x 80 m).
constexpr double kWest = 500000.0, kNorth = 5400000.0, kPixel = 4.0;
constexpr int kColumns = 30, kRows = 20;

// A plane, 412 m at the corner, rising 1 in 50 east and 1 in 80 north: bilinear interpolation reproduces it,
// so a height read back differs from it by the float32 rounding of the file's elevations alone.
double plane(double x, double y) {
  return 412.0 + (x - kWest) / 50.0 + (y - kNorth) / 80.0;
}

struct RasterOptions {
  std::string crs = "EPSG:32632";
  double rotation = 0.0;
  double dy = -kPixel;
  bool nodata = false;  // pixel (column 10, row 10) nodata
};

std::string write_dem(const fw::test::TempDir& dir, const std::string& name, const RasterOptions& options) {
  fw::io::GeoGrid grid{.columns = kColumns,
                       .rows = kRows,
                       .transform = {kWest, kPixel, options.rotation, kNorth, options.rotation, options.dy},
                       .crs_wkt = options.crs,
                       .values = {},
                       .nodata = -9999.0,
                       .description = "elevation (m)"};
  for (int r = 0; r < kRows; ++r)
    for (int c = 0; c < kColumns; ++c)
      grid.values.push_back(float(plane(kWest + (c + 0.5) * kPixel, kNorth + (r + 0.5) * options.dy)));
  if (options.nodata) grid.values[std::size_t(10 + kColumns * 10)] = -9999.0f;
  const std::string path = dir.path() + "/" + name;
  fw::io::write_geotiff(path, grid);
  return path;
}

// A scenario over the raster: the domain's south-west corner at (500,020, 5,399,940), 64 x 40 m, floor at
// `floor` m; a hand-placed tree at local (30, 20) without z. Lines: domain 3, terrain 5.
std::string site_scenario(const std::string& terrain, const std::string& origin = "[500020, 5399940, 400]",
                          const std::string& size = "[64, 40, 32]") {
  return fmt::format(
      "scenario: site\n"
      "time: {{end: 1.0}}\n"
      "domain: {{origin: {}, size: {}, cell_size: 4.0}}\n"
      "wind: {{speed: 5.0, direction: 270}}\n"
      "terrain: {}\n"
      "forest:\n"
      "  species:\n"
      "    - {{name: stick, skeleton: {{generate: {{preset: conifer, height: 10, seed: 1}}}}}}\n"
      "  trees:\n"
      "    - {{species: stick, position: [30, 20]}}\n",
      origin, size, terrain);
}

}  // namespace

TEST_CASE(
    "terrain: a raster makes the site, the run local to the domain's corner, its heights over the floor",
    "[scenario]") {
  fw::test::TempDir dir("fw_terrain");
  write_dem(dir, "dem.tif", {});
  const fw::io::Scenario s =
      fw::io::load_scenario(dir.write("site.yaml", site_scenario("{raster: dem.tif}")));
  const fw::io::SiteSettings* site = s.site();
  REQUIRE(site != nullptr);
  CHECK(site->origin == std::array<double, 3>{500020, 5399940, 400});
  REQUIRE(site->crs.has_value());
  CHECK(site->crs->epsg == 32632);
  CHECK(site->crs_label() == "EPSG:32632 (WGS 84 / UTM zone 32N)");
  CHECK(s.domain.origin == std::array<double, 3>{0, 0, 0});
  const fw::fluid::Heightmap& map = *s.terrain->map;
  // The elevation at given coordinates within 1 mm (float32 keeps 412 m to 0.03 mm).
  for (const auto& [x, y] : std::vector<std::array<double, 2>>{{0, 0}, {63.9, 39.9}, {17.3, 22.1}, {64, 0}}) {
    INFO("local (" << x << ", " << y << ")");
    CHECK(map.height_at(x, y) == Approx(plane(500020 + x, 5399940 + y) - 400).margin(1e-3));
  }
  // The tree without z stands on the ground under it.
  REQUIRE(s.forest.trees.size() == 1);
  CHECK(s.forest.trees[0].position[2] == Approx(plane(500050, 5399960) - 400).margin(1e-3));
}

TEST_CASE("terrain: a raster without a CRS places the site in the raster's own coordinates", "[scenario]") {
  fw::test::TempDir dir("fw_terrain");
  // ESRI ASCII grid, north row first: 4 x 3 pixels of 10 m from (100, 200); no .prj beside it, so no CRS.
  dir.write("ground.asc",
            "ncols 4\nnrows 3\nxllcorner 100\nyllcorner 200\ncellsize 10\nNODATA_value -9999\n"
            "9 9 9 9\n5 6 7 8\n1 2 3 4\n");
  const fw::io::Scenario s = fw::io::load_scenario(
      dir.write("plain.yaml", site_scenario("{raster: ground.asc}", "[100, 200, 0]", "[40, 20, 32]")));
  REQUIRE(s.site() != nullptr);
  CHECK_FALSE(s.site()->crs.has_value());
  CHECK(s.site()->crs_label() == "none");
  const fw::fluid::Heightmap& map = *s.terrain->map;
  // Pixel centres at local x 5, 15, 25, 35 and y 5 (south row), 15 (middle); tolerance: doubles, 1e-12 m.
  CHECK(map.height_at(5, 5) == Approx(1.0).margin(1e-12));
  CHECK(map.height_at(35, 15) == Approx(8.0).margin(1e-12));
  CHECK(map.height_at(20, 10) == Approx(4.5).margin(1e-12));
}

TEST_CASE("terrain: each raster the run cannot stand on is refused at the key to blame", "[scenario]") {
  fw::test::TempDir dir("fw_terrain");
  write_dem(dir, "dem.tif", {});
  write_dem(dir, "rotated.tif", {.rotation = 0.5});
  write_dem(dir, "degrees.tif", {.crs = "EPSG:4326"});
  write_dem(dir, "holes.tif", {.nodata = true});
  write_dem(dir, "oblong.tif", {.dy = -2.0});
  dir.write("text.tif", "not a raster\n");
  fw::test::expect_scenario_error(dir, "rotated", site_scenario("{raster: rotated.tif}"), 5, "terrain.raster",
                                  "a north-up raster");
  fw::test::expect_scenario_error(dir, "geographic", site_scenario("{raster: degrees.tif}"), 5,
                                  "terrain.raster",
                                  "a raster in a projected CRS, in metres (EPSG:4326 (WGS 84) is in degrees");
  // Pixel (10, 10)'s centre: x 500042, y 5399958, under the domain.
  fw::test::expect_scenario_error(
      dir, "nodata", site_scenario("{raster: holes.tif}"), 5, "terrain.raster",
      "elevations under the whole domain (its pixel at x 500042, y 5399958, column 10, row 10, is "
      "nodata");
  fw::test::expect_scenario_error(
      dir, "oblong", site_scenario("{raster: oblong.tif}", "[500020, 5399962, 400]", "[64, 32, 32]"), 5,
      "terrain.raster", "square pixels (these are 4 x 2 m");
  fw::test::expect_scenario_error(dir, "not_a_raster", site_scenario("{raster: text.tif}"), 5,
                                  "terrain.raster", "a georeferenced raster GDAL reads");
  // The raster covers x 500000 .. 500120, y 5399920 .. 5400000.
  fw::test::expect_scenario_error(
      dir, "past_east", site_scenario("{raster: dem.tif}", "[500060, 5399940, 400]"), 3, "domain.origin",
      "a domain inside the terrain raster expected: dem.tif covers x 500000 .. 500120, y 5399920 .. "
      "5400000; the domain reaches x 500060 .. 500124");
  fw::test::expect_scenario_error(dir, "floor_too_high",
                                  site_scenario("{raster: dem.tif}", "[500020, 5399940, 412]"), 3,
                                  "domain.origin", "the terrain under the domain falls to");
  fw::test::expect_scenario_error(dir, "both", site_scenario("{raster: dem.tif, heightmap: hills.pgm}"), 5,
                                  "terrain.raster",
                                  "either terrain.heightmap (a PGM image) or terrain.raster, not both");
  fw::test::expect_scenario_error(dir, "scale", site_scenario("{raster: dem.tif, max_height: 10}"), 5,
                                  "terrain.max_height", "no PGM scale with a raster");
  fw::test::expect_scenario_error(dir, "neither", site_scenario("{}"), 5, "terrain.raster",
                                  "or a terrain.heightmap");
}
