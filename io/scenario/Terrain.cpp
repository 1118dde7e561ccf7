// terrain: the heightmap under the wind grid, from a PGM image or from a georeferenced raster (the site).
//
// A raster's treatment (docs/gis.md, "Terrain from a raster"): its pixels must be north-up and square, in a
// projected CRS (metres) or none, and must cover the domain with data. The pixels whose centres bilinear
// interpolation over the domain reads become the heightmap, their elevations less the floor's, in
// coordinates local to the domain's corner.
#include "io/scenario/Terrain.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <cmath>
#include <exception>
#include <limits>
#include <optional>
#include <utility>
#include <vector>

#include "io/ScenarioError.hpp"
#include "io/gis/GeoRaster.hpp"
#include "io/schema/TerrainKeys.hpp"

namespace fw::io::reader {

namespace {

// How far (in pixels) the domain may reach past the raster's edge, for the rounding of corners given in
// decimal metres.
constexpr double kEdgeTolerancePixels = 1e-6;
// Square pixels: |dx| and |dy| equal to this relative part (a GeoTIFF stores them as doubles).
constexpr double kSquareTolerance = 1e-9;

TerrainSettings read_heightmap(const Loader& loader, const Field& heightmap,
                               const Section<schema::kTerrainKeys, "terrain">& map,
                               const DomainSettings& domain) {
  TerrainSettings terrain;
  terrain.heightmap = loader.readable_file(heightmap);
  auto read_image = [&](double cell_size, double max_height) {
    try {
      return fluid::Heightmap::read(terrain.heightmap.string(), cell_size, max_height);
    } catch (const std::exception& error) {
      loader.expected(heightmap, fmt::format("a PGM image ({})", error.what()));
    }
  };
  // The file is to blame before its scale: a GeoTIFF given here is told to go to terrain.raster.
  const auto cell_size = map.get<"cell_size">(), max_height = map.get<"max_height">();
  if (!cell_size || !max_height) read_image(1.0, 0.0);
  const std::string reason = "needed for a PGM heightmap";
  terrain.cell_size = loader.number(map.require<"cell_size">(reason));
  terrain.max_height = loader.number(map.require<"max_height">(reason));
  const std::optional<fluid::Heightmap> read = read_image(terrain.cell_size, terrain.max_height);
  const fluid::Heightmap& image = *read;
  // An image has no georeference: its south-west corner goes to the domain's, wherever the origin is.
  std::vector<double> heights;
  heights.reserve(std::size_t(image.columns()) * std::size_t(image.rows()));
  for (int row = 0; row < image.rows(); ++row)
    for (int column = 0; column < image.columns(); ++column) heights.push_back(image.sample(column, row));
  const double half = 0.5 * image.cell_size();
  terrain.map = fluid::Heightmap(image.columns(), image.rows(), image.cell_size(),
                                 {domain.origin[0] + half, domain.origin[1] + half}, std::move(heights));
  return terrain;
}

// The raster's pixel-space box around the domain: the smallest and largest column and row positions of its
// four corners.
struct PixelBox {
  double column_min, column_max, row_min, row_max;
};

PixelBox domain_in_pixels(const GeoRaster& raster, const DomainSettings& domain) {
  const auto top = domain.max_corner();
  PixelBox box{std::numeric_limits<double>::infinity(), -std::numeric_limits<double>::infinity(),
               std::numeric_limits<double>::infinity(), -std::numeric_limits<double>::infinity()};
  for (double x : {domain.origin[0], top[0]})
    for (double y : {domain.origin[1], top[1]}) {
      const auto [column, row] = raster.pixel_of(x, y);
      box.column_min = std::min(box.column_min, column);
      box.column_max = std::max(box.column_max, column);
      box.row_min = std::min(box.row_min, row);
      box.row_max = std::max(box.row_max, row);
    }
  return box;
}

// The first and last pixel whose centre bilinear interpolation between `low` and `high` (pixel positions)
// reads, within 0 .. count - 1.
std::pair<int, int> centres_read(double low, double high, int count) {
  const int first = std::clamp(int(std::floor(low - 0.5)), 0, count - 1);
  const int last = std::clamp(int(std::ceil(high - 0.5)), 0, count - 1);
  return {first, last};
}

TerrainSettings read_raster(const Loader& loader, const Field& field, DomainSettings& domain) {
  TerrainSettings terrain;
  SiteSettings& site = terrain.site.emplace();
  site.raster = loader.readable_file(field);
  GeoRaster raster;
  try {
    raster = GeoRaster::read(site.raster.string());
  } catch (const GeoRasterError& error) {
    loader.expected(field, fmt::format("a georeferenced raster GDAL reads ({})", error.what()));
  }
  const GeoTransform& t = raster.transform();
  if (t.rotated())
    loader.expected(field,
                    fmt::format("a north-up raster (its geotransform turns it: rotation terms {} and {}; "
                                "warp it north-up first, e.g. gdalwarp in.tif out.tif)",
                                t.rx, t.ry));
  site.crs = raster.crs();
  if (site.crs && site.crs->geographic)
    loader.expected(field, fmt::format("a raster in a projected CRS, in metres ({} is in degrees of latitude "
                                       "and longitude; reproject it, e.g. gdalwarp -t_srs EPSG:326NN for UTM "
                                       "zone NN north)",
                                       site.crs_label()));
  const double pixel = std::abs(t.dx);
  if (std::abs(std::abs(t.dy) - pixel) > kSquareTolerance * pixel)
    loader.expected(
        field, fmt::format("square pixels (these are {} x {} m; resample, e.g. gdalwarp -tr {} {})", pixel,
                           std::abs(t.dy), pixel, pixel));

  const PixelBox box = domain_in_pixels(raster, domain);
  const double tolerance = kEdgeTolerancePixels;
  if (box.column_min < -tolerance || box.row_min < -tolerance ||
      box.column_max > raster.columns() + tolerance || box.row_max > raster.rows() + tolerance) {
    const auto a = raster.position(0, 0), b = raster.position(raster.columns(), raster.rows());
    const auto top = domain.max_corner();
    throw ScenarioError(
        loader.file(), domain.origin_line, "domain.origin",
        fmt::format(
            "a domain inside the terrain raster expected: {} covers x {} .. {}, y {} .. {}; the domain "
            "reaches x {} .. {}, y {} .. {}",
            site.raster.filename().string(), std::min(a[0], b[0]), std::max(a[0], b[0]), std::min(a[1], b[1]),
            std::max(a[1], b[1]), domain.origin[0], top[0], domain.origin[1], top[1]));
  }
  const auto [first_column, last_column] = centres_read(box.column_min, box.column_max, raster.columns());
  const auto [first_row, last_row] = centres_read(box.row_min, box.row_max, raster.rows());
  const int columns = last_column - first_column + 1, rows = last_row - first_row + 1;
  // The heightmap's column 0 is the west, its row 0 the south, whichever way the raster's run.
  const bool east = t.dx > 0.0, north = t.dy < 0.0;
  auto raster_column = [&](int i) { return east ? first_column + i : last_column - i; };
  auto raster_row = [&](int j) { return north ? last_row - j : first_row + j; };
  std::vector<double> heights;
  heights.reserve(std::size_t(columns) * std::size_t(rows));
  double lowest = std::numeric_limits<double>::infinity();
  for (int j = 0; j < rows; ++j)
    for (int i = 0; i < columns; ++i) {
      const int c = raster_column(i), r = raster_row(j);
      if (raster.is_nodata(c, r)) {
        const auto centre = raster.position(c + 0.5, r + 0.5);
        loader.expected(field,
                        fmt::format("elevations under the whole domain (its pixel at x {}, y {}, column "
                                    "{}, row {}, is nodata; fill it, e.g. gdal_fillnodata.py)",
                                    centre[0], centre[1], c, r));
      }
      lowest = std::min(lowest, raster.sample(c, r));
      heights.push_back(raster.sample(c, r) - domain.origin[2]);
    }
  if (lowest < domain.origin[2])
    throw ScenarioError(
        loader.file(), domain.origin_line, "domain.origin",
        fmt::format("a floor at or below the ground expected: the terrain under the domain falls to {} m, "
                    "below the floor's elevation z = {} m; give a z of at most {} m",
                    lowest, domain.origin[2], std::floor(lowest)));
  const auto south_west = raster.position(raster_column(0) + 0.5, raster_row(0) + 0.5);
  site.origin = domain.origin;
  terrain.map =
      fluid::Heightmap(columns, rows, pixel, {south_west[0] - site.origin[0], south_west[1] - site.origin[1]},
                       std::move(heights));
  domain.origin = {0.0, 0.0, 0.0};  // the run computes in local coordinates from here on
  return terrain;
}

}  // namespace

TerrainSettings read_terrain(const Loader& loader, const Field& field, DomainSettings& domain) {
  const Section<schema::kTerrainKeys, "terrain"> map(loader, field);
  const auto heightmap = map.get<"heightmap">();
  const auto raster = map.get<"raster">();
  if (heightmap && raster)
    loader.expected(*raster, "either terrain.heightmap (a PGM image) or terrain.raster, not both");
  if (raster) {
    for (const auto& pgm_only : {map.get<"cell_size">(), map.get<"max_height">()})
      if (pgm_only)
        loader.expected(*pgm_only,
                        "no PGM scale with a raster (its elevations are metres, its pixels placed "
                        "by its geotransform)");
    return read_raster(loader, *raster, domain);
  }
  if (!heightmap) map.require<"raster">("or a terrain.heightmap");
  return read_heightmap(loader, *heightmap, map, domain);
}

}  // namespace fw::io::reader
