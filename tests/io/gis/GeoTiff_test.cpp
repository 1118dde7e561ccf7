// io/gis/GeoTiff: a grid written as a GeoTIFF reads back through GDAL (io/gis/GeoRaster) with its
// geotransform, its CRS, its nodata and every value; without a CRS it has none; bad grids leave no file.
#include "io/gis/GeoTiff.hpp"

#include <ogr_spatialref.h>
#include <catch2/catch.hpp>

#include <cmath>
#include <filesystem>
#include <string>

#include "tests/support/TempDir.hpp"

using fw::io::GeoGrid;
using fw::io::GeoRaster;
using fw::io::GeoRasterError;

namespace {

// UTM zone 32 N as WKT, the way a site's CRS reaches the writer.
std::string utm32n_wkt() {
  OGRSpatialReference srs;
  REQUIRE(srs.importFromEPSG(32632) == OGRERR_NONE);
  char* text = nullptr;
  REQUIRE(srs.exportToWkt(&text) == OGRERR_NONE);
  const std::string wkt = text;
  CPLFree(text);
  return wkt;
}

// 7 x 5 pixels of 3 m, north-west corner at (612,345.5 m E, 5,301,234 m N); values with a fraction float32
// keeps exactly, and one nodata pixel.
GeoGrid site_grid() {
  GeoGrid grid;
  grid.columns = 7;
  grid.rows = 5;
  grid.transform = {612345.5, 3.0, 0.0, 5301234.0, 0.0, -3.0};
  for (int r = 0; r < grid.rows; ++r)
    for (int c = 0; c < grid.columns; ++c)
      grid.values.push_back(10.0f + 0.25f * float(c) - 0.125f * float(r));
  grid.nodata = -9999.0;
  grid.values[3] = -9999.0f;
  grid.description = "wind speed at 10 m above the terrain (m/s)";
  return grid;
}

}  // namespace

TEST_CASE("GeoTiff: a written grid reads back with its geotransform, CRS, nodata and every value", "[io]") {
  const fw::test::TempDir dir("fw_geotiff");
  GeoGrid grid = site_grid();
  grid.crs_wkt = utm32n_wkt();
  const std::string path = dir.path() + "/speed_10m.tif";
  fw::io::write_geotiff(path, grid);
  const GeoRaster back = GeoRaster::read(path);
  CHECK(back.columns() == grid.columns);
  CHECK(back.rows() == grid.rows);
  CHECK(back.transform().x0 == grid.transform.x0);
  CHECK(back.transform().y0 == grid.transform.y0);
  CHECK(back.transform().dx == grid.transform.dx);
  CHECK(back.transform().dy == grid.transform.dy);
  CHECK_FALSE(back.transform().rotated());
  REQUIRE(back.crs().has_value());
  CHECK(back.crs()->epsg == 32632);
  CHECK(back.nodata() == -9999.0);
  CHECK(back.is_nodata(3, 0));
  for (int r = 0; r < grid.rows; ++r)
    for (int c = 0; c < grid.columns; ++c)  // float32 both ways: exact
      CHECK(back.sample(c, r) == double(grid.values[std::size_t(c + grid.columns * r)]));
  // Nothing else was left in the folder: the temporary was renamed into place.
  CHECK(std::distance(std::filesystem::directory_iterator(dir.path()),
                      std::filesystem::directory_iterator{}) == 1);
}

TEST_CASE("GeoTiff: a grid without a CRS is written without one, in its local coordinates", "[io]") {
  const fw::test::TempDir dir("fw_geotiff");
  GeoGrid grid = site_grid();
  grid.transform = {0.0, 3.0, 0.0, 15.0, 0.0, -3.0};
  const std::string path = dir.path() + "/local.tif";
  fw::io::write_geotiff(path, grid);
  const GeoRaster back = GeoRaster::read(path);
  CHECK_FALSE(back.crs().has_value());
  CHECK(back.transform().y0 == 15.0);
  CHECK(back.value_at(1.5 + 3.0, 15.0 - 1.5) == Approx(10.25).epsilon(1e-12));
}

TEST_CASE("GeoTiff: sizes that do not fit, a CRS GDAL does not know and a missing folder leave no file",
          "[io]") {
  using Catch::Matchers::Contains;
  const fw::test::TempDir dir("fw_geotiff");
  const std::string path = dir.path() + "/bad.tif";
  GeoGrid short_grid = site_grid();
  short_grid.values.pop_back();
  CHECK_THROWS_WITH(fw::io::write_geotiff(path, short_grid), Contains("bad.tif") && Contains("34 values"));
  GeoGrid unknown = site_grid();
  unknown.crs_wkt = "EPSG:999999";
  CHECK_THROWS_WITH(fw::io::write_geotiff(path, unknown), Contains("a CRS GDAL understands"));
  CHECK_THROWS_AS(fw::io::write_geotiff(dir.path() + "/no/such/folder/x.tif", site_grid()), GeoRasterError);
  CHECK(std::filesystem::is_empty(dir.path()));
}
