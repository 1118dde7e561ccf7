// viz/GroundSlice: a field at a height above each column's ground, on a grid whose values are known in z:
// terrain lifts the sample, an overhang and a column of solid have none, heights past the top have none.
#include "viz/GroundSlice.hpp"

#include <catch2/catch.hpp>

#include <cmath>

#include "io/gis/GeoRaster.hpp"
#include "tests/support/TempDir.hpp"

using fw::viz::WindGrid;

namespace {

// 3 x 2 columns of 6 cells of 2 m; "speed" in cell (i, j, k) is 10 k + i (so linear in z); solids:
// column (0, 0) 2 cells of terrain, column (2, 1) solid to the top, column (1, 1) an overhang at k = 3.
WindGrid test_grid() {
  WindGrid wind;
  wind.cells = {3, 2, 6};
  wind.origin = {100.0, 200.0, 0.0};
  wind.cell_size = 2.0;
  wind.file = "wind_000001.vti";
  WindGrid::Array speed{"speed", 1, {}};
  wind.solid.assign(3 * 2 * 6, 0);
  for (int k = 0; k < 6; ++k)
    for (int j = 0; j < 2; ++j)
      for (int i = 0; i < 3; ++i) speed.values.push_back(float(10 * k + i));
  wind.arrays.push_back(speed);
  for (int k = 0; k < 2; ++k) wind.solid[wind.index(0, 0, k)] = 1;
  for (int k = 0; k < 6; ++k) wind.solid[wind.index(2, 1, k)] = 1;
  wind.solid[wind.index(1, 1, 3)] = 1;
  return wind;
}

}  // namespace

TEST_CASE("GroundSlice: the field at a height above each column's ground, linear between cell centres",
          "[viz]") {
  const WindGrid wind = test_grid();
  // 3 m above the ground: 1.5 cells, so cell-centre level ground + 1.0.
  const fw::viz::GroundSlice slice = fw::viz::ground_slice(wind, "speed", 3.0);
  CHECK(slice.columns == 3);
  CHECK(slice.rows == 2);
  CHECK(slice.origin == std::array<double, 2>{100.0, 200.0});
  CHECK(slice.value(1, 0) == Approx(10.0 + 1));  // flat: level 1.0, cell 1
  CHECK(slice.value(2, 0) == Approx(10.0 + 2));
  CHECK(slice.value(0, 0) == Approx(30.0));  // on 2 cells of terrain: level 3.0
  CHECK(std::isnan(slice.value(2, 1)));      // solid to the top: no ground to stand on
  CHECK(slice.value(0, 1) == Approx(10.0));
  // Between two cell centres: 4 m above a flat column is level 1.5, halfway between cells 1 and 2.
  CHECK(fw::viz::ground_slice(wind, "speed", 4.0).value(1, 0) == Approx(16.0));
  // Below the first fluid cell's centre: that cell's value (10 cm above the terrain of column (0, 0)).
  CHECK(fw::viz::ground_slice(wind, "speed", 0.1).value(0, 0) == Approx(20.0));
  // The overhang at k = 3 in column (1, 1): a sample that reaches it has none, one below it has its value.
  CHECK(std::isnan(fw::viz::ground_slice(wind, "speed", 6.0).value(1, 1)));
  CHECK(fw::viz::ground_slice(wind, "speed", 5.0).value(1, 1) == Approx(21.0));
  // Past the top cell's centre (level 5.0 on flat ground is 11 m): none.
  CHECK(fw::viz::ground_slice(wind, "speed", 11.0).value(1, 0) == Approx(51.0));
  CHECK(std::isnan(fw::viz::ground_slice(wind, "speed", 11.5).value(1, 0)));
  CHECK(slice.valid_count() == 5);
}

TEST_CASE("GroundSlice: an unknown field and a bad height are refused with what there is", "[viz]") {
  using Catch::Matchers::Contains;
  const WindGrid wind = test_grid();
  CHECK_THROWS_WITH(fw::viz::ground_slice(wind, "pressure", 10.0),
                    Contains("export: no field 'pressure' in wind_000001.vti: choose one of speed"));
  CHECK_THROWS_WITH(fw::viz::ground_slice(wind, "speed", -1.0), Contains("--height"));
  CHECK_THROWS_AS(fw::viz::ground_slice(wind, "speed", NAN), std::invalid_argument);
}

TEST_CASE("GroundSlice: as a GeoTIFF, north row first, in the domain's coordinates, without a value nodata",
          "[viz]") {
  const fw::viz::GroundSlice slice = fw::viz::ground_slice(test_grid(), "speed", 3.0);
  const fw::test::TempDir dir("fw_ground_slice");
  const std::string path = dir.path() + "/speed.tif";
  fw::io::write_geotiff(path, fw::viz::geo_grid(slice, 12.5));
  const fw::io::GeoRaster back = fw::io::GeoRaster::read(path);
  CHECK_FALSE(back.crs().has_value());
  CHECK(back.transform().x0 == 100.0);
  CHECK(back.transform().y0 == 204.0);  // the north edge: 200 m + 2 rows of 2 m
  // The centre of column (i, j) lies at (100 + 2 i + 1, 200 + 2 j + 1).
  for (int j = 0; j < 2; ++j)
    for (int i = 0; i < 3; ++i) {
      INFO("column " << i << ", " << j);
      if (std::isnan(slice.value(i, j))) {
        CHECK(back.is_nodata(i, 1 - j));
        continue;
      }
      CHECK(back.value_at(101.0 + 2 * i, 201.0 + 2 * j) == slice.value(i, j));
    }
}

TEST_CASE("GroundSlice: with a site, the GeoTIFF is in its CRS, at its origin plus the local position",
          "[viz]") {
  const fw::viz::GroundSlice slice = fw::viz::ground_slice(test_grid(), "speed", 3.0);
  fw::io::SiteSettings site;
  site.origin = {512040.0, 5401040.0, 421.0};
  fw::io::CoordinateSystem& crs = site.crs.emplace();
  crs.wkt = "EPSG:32632";  // GDAL takes any user input: the writer sets it, the reader gives its WKT back
  crs.epsg = 32632;
  const fw::test::TempDir dir("fw_ground_slice");
  const std::string path = dir.path() + "/speed.tif";
  fw::io::write_geotiff(path, fw::viz::geo_grid(slice, 12.5, &site));
  const fw::io::GeoRaster back = fw::io::GeoRaster::read(path);
  REQUIRE(back.crs().has_value());
  CHECK(back.crs()->epsg == 32632);
  CHECK(back.transform().x0 == 512040.0 + 100.0);
  CHECK(back.transform().y0 == 5401040.0 + 204.0);
  CHECK(back.transform().dx == 2.0);
  for (int j = 0; j < 2; ++j)
    for (int i = 0; i < 3; ++i) {
      INFO("column " << i << ", " << j);
      if (std::isnan(slice.value(i, j))) continue;
      CHECK(back.value_at(512040.0 + 101.0 + 2 * i, 5401040.0 + 201.0 + 2 * j) == slice.value(i, j));
    }
}
