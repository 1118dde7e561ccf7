// io/gis/GeoRaster: rasters written here through GDAL with a known geotransform and CRS read back with them,
// and the elevation at given CRS coordinates within 1 mm; ESRI ASCII grids through the same reader; nodata,
// rotation and geographic CRSs reported; unreadable files named.
#include "io/gis/GeoRaster.hpp"

#include <gdal_priv.h>
#include <ogr_spatialref.h>
#include <catch2/catch.hpp>

#include <array>
#include <cmath>
#include <string>
#include <vector>

#include "tests/support/TempDir.hpp"

using fw::io::GeoRaster;
using fw::io::GeoRasterError;

namespace {

// A UTM zone 32 N site: the north-west corner at (500,000 m E, 5,400,000 m N), 2 m pixels, 60 x 40.
constexpr double kWest = 500000.0, kNorth = 5400000.0, kPixel = 2.0;
constexpr int kColumns = 60, kRows = 40;

// Elevation as a plane plus a gentle slope: bilinear interpolation reproduces a plane exactly, so the read
// values are the file's to float32 rounding and the interpolation adds nothing. 412 m above sea level, the
// slope 1 in 50 east and 1 in 80 north.
double plane(double x, double y) {
  return 412.0 + (x - kWest) / 50.0 + (y - kNorth) / 80.0;
}

// Writes a float32 GeoTIFF of plane() at the pixel centres, `epsg` its CRS (0: none), `rotation` its
// geotransform's rotation terms, pixel (0, 0) nodata when `nodata` is set.
std::string write_geotiff(const std::string& path, int epsg, double rotation = 0.0, bool nodata = false) {
  GDALAllRegister();
  GDALDriver* driver = GetGDALDriverManager()->GetDriverByName("GTiff");
  REQUIRE(driver != nullptr);
  GDALDataset* dataset = driver->Create(path.c_str(), kColumns, kRows, 1, GDT_Float32, nullptr);
  REQUIRE(dataset != nullptr);
  double transform[6] = {kWest, kPixel, rotation, kNorth, rotation, -kPixel};
  dataset->SetGeoTransform(transform);
  if (epsg != 0) {
    OGRSpatialReference srs;
    REQUIRE(srs.importFromEPSG(epsg) == OGRERR_NONE);
    dataset->SetSpatialRef(&srs);
  }
  std::vector<float> values(std::size_t(kColumns) * kRows);
  for (int r = 0; r < kRows; ++r)
    for (int c = 0; c < kColumns; ++c)
      values[std::size_t(c + kColumns * r)] =
          float(plane(kWest + (c + 0.5) * kPixel, kNorth - (r + 0.5) * kPixel));
  GDALRasterBand* band = dataset->GetRasterBand(1);
  if (nodata) {
    band->SetNoDataValue(-9999.0);
    values[0] = -9999.0f;
  }
  REQUIRE(band->RasterIO(GF_Write, 0, 0, kColumns, kRows, values.data(), kColumns, kRows, GDT_Float32, 0,
                         0) == CE_None);
  GDALClose(GDALDataset::ToHandle(dataset));
  return path;
}

}  // namespace

TEST_CASE("GeoRaster: a GeoTIFF in UTM gives its geotransform, its CRS and the elevation within 1 mm",
          "[io]") {
  const fw::test::TempDir dir("fw_georaster");
  const GeoRaster dem = GeoRaster::read(write_geotiff(dir.path() + "/dem.tif", 32632));
  CHECK(dem.columns() == kColumns);
  CHECK(dem.rows() == kRows);
  CHECK(dem.transform().x0 == kWest);
  CHECK(dem.transform().y0 == kNorth);
  CHECK(dem.transform().dx == kPixel);
  CHECK(dem.transform().dy == -kPixel);
  CHECK_FALSE(dem.transform().rotated());
  REQUIRE(dem.crs().has_value());
  CHECK(dem.crs()->epsg == 32632);
  CHECK_FALSE(dem.crs()->geographic);
  CHECK(dem.crs()->name.find("UTM zone 32N") != std::string::npos);
  CHECK(dem.crs()->wkt.find("PROJCRS") == 0);  // WKT2
  CHECK_FALSE(dem.nodata().has_value());
  // Points between pixel centres, at UTM northings of 5.4e6 m: float32 pixels hold 412-414 m to 3e-5 m,
  // and the bilinear weights are computed in double, so 1 mm is the bound with room.
  for (const auto& [x, y] : {std::array{500003.7, 5399998.2}, std::array{500061.0, 5399930.5},
                             std::array{500117.9, 5399921.1}, std::array{500001.0, 5399999.0}}) {
    INFO("at (" << x << ", " << y << ")");
    CHECK(std::abs(dem.value_at(x, y) - plane(x, y)) < 1e-3);
  }
  // The pixel centre of (column 10, row 5) is its value, and position() / pixel_of() invert each other.
  const auto centre = dem.position(10.5, 5.5);
  CHECK(centre[0] == kWest + 21.0);
  CHECK(centre[1] == kNorth - 11.0);
  CHECK(dem.value_at(centre[0], centre[1]) == dem.sample(10, 5));
  const auto back = dem.pixel_of(centre[0], centre[1]);
  CHECK(back[0] == Approx(10.5).margin(1e-9));
  CHECK(back[1] == Approx(5.5).margin(1e-9));
  // Outside the lattice of pixel centres (the outer half pixel included): an error naming the file.
  CHECK_THROWS_AS(dem.value_at(kWest + 0.5, kNorth - 10.0), GeoRasterError);
  CHECK_THROWS_WITH(dem.value_at(kWest + 500.0, kNorth - 10.0), Catch::Matchers::Contains("dem.tif"));
}

TEST_CASE("GeoRaster: an ESRI ASCII grid reads through GDAL, without a CRS, its nodata flagged", "[io]") {
  const fw::test::TempDir dir("fw_georaster");
  const std::string path = dir.write(
      "hills.asc",
      "ncols 3\nnrows 2\nxllcorner 100\nyllcorner 200\ncellsize 5\nNODATA_value -1\n1 2 -1\n4 5 6\n");
  const GeoRaster grid = GeoRaster::read(path);
  CHECK(grid.columns() == 3);
  CHECK(grid.rows() == 2);
  CHECK(grid.transform().x0 == 100.0);
  CHECK(grid.transform().y0 == 210.0);  // the north edge: yllcorner + nrows * cellsize
  CHECK_FALSE(grid.crs().has_value());
  REQUIRE(grid.nodata().has_value());
  CHECK(grid.is_nodata(2, 0));
  CHECK_FALSE(grid.is_nodata(0, 0));
  CHECK(grid.sample(0, 1) == 4.0);  // row 0 is the north row
  // Between the centres of (0, 0), (1, 0), (0, 1), (1, 1): the bilinear mean.
  CHECK(grid.value_at(105.0, 205.0) == Approx(3.0).epsilon(1e-12));
  // Next to the nodata pixel: refused, naming the pixel.
  CHECK_THROWS_WITH(grid.value_at(110.0, 205.0), Catch::Matchers::Contains("nodata"));
}

TEST_CASE("GeoRaster: rotation terms, a geographic CRS and nodata are reported", "[io]") {
  const fw::test::TempDir dir("fw_georaster");
  CHECK(GeoRaster::read(write_geotiff(dir.path() + "/rotated.tif", 32632, 0.1)).transform().rotated());
  const GeoRaster degrees = GeoRaster::read(write_geotiff(dir.path() + "/wgs84.tif", 4326));
  REQUIRE(degrees.crs().has_value());
  CHECK(degrees.crs()->geographic);
  CHECK(degrees.crs()->epsg == 4326);
  const GeoRaster holed = GeoRaster::read(write_geotiff(dir.path() + "/holed.tif", 32632, 0.0, true));
  CHECK(holed.nodata() == -9999.0);
  CHECK(holed.is_nodata(0, 0));
  CHECK_FALSE(holed.is_nodata(1, 0));
  CHECK_THROWS_WITH(holed.value_at(kWest + 2.0, kNorth - 2.0), Catch::Matchers::Contains("nodata"));
  CHECK_FALSE(GeoRaster::read(write_geotiff(dir.path() + "/bare.tif", 0)).crs().has_value());
}

TEST_CASE("GeoRaster: a missing file, a file GDAL cannot read and a raster without georeference are named",
          "[io]") {
  using Catch::Matchers::Contains;
  const fw::test::TempDir dir("fw_georaster");
  const std::string missing = dir.path() + "/missing.tif";
  CHECK_THROWS_WITH(GeoRaster::read(missing), Contains(missing) && Contains("a raster GDAL reads expected"));
  CHECK_THROWS_AS(GeoRaster::read(dir.write("notes.txt", "not a raster\n")), GeoRasterError);
  // A PGM image has pixels but no place on the ground.
  const std::string image = dir.write("image.pgm", std::string("P5\n2 2\n255\n\x01\x02\x03\x04", 15));
  CHECK_THROWS_WITH(GeoRaster::read(image), Contains("no geotransform"));
}
