// A georeferenced raster read through GDAL: any format GDAL reads (GeoTIFF, ESRI ASCII grid, ...), its first
// band as doubles, with its geotransform, its coordinate reference system and its nodata value.
//
//   const fw::io::GeoRaster dem = fw::io::GeoRaster::read("site/dem.tif");
//   dem.crs().epsg;                                  // 32632: UTM zone 32 N, when the file names an EPSG
//   code double z = dem.value_at(500123.5, 5401234.0);    // m, bilinear between pixel centres, CRS
//   coordinates
//
// The geotransform is GDAL's: the CRS position of pixel corner (column c, row r), row 0 the north row of a
// north-up raster, is
//   x = x0 + c * dx + r * rx,   y = y0 + c * ry + r * dy,
// dy negative for north up; rx and ry are the rotation terms, zero for a raster aligned with the CRS axes.
// A pixel's value stands for its centre, (c + 1/2, r + 1/2).
//
// Every error, from GDAL or from this class, throws GeoRasterError("FILE: what was expected").
#pragma once

#include <array>
#include <optional>
#include <stdexcept>
#include <string>
#include <vector>

namespace fw::io {

class GeoRasterError : public std::runtime_error {
 public:
  using std::runtime_error::runtime_error;
};

/// GDAL's six geotransform coefficients (see the header).
struct GeoTransform {
  double x0 = 0.0, dx = 1.0, rx = 0.0;
  double y0 = 0.0, ry = 0.0, dy = -1.0;
  bool rotated() const { return rx != 0.0 || ry != 0.0; }
};

/// A raster's coordinate reference system.
struct CoordinateSystem {
  std::string wkt;          ///< WKT2 (2019), as GDAL exports it
  std::string name;         ///< e.g. "WGS 84 / UTM zone 32N"
  std::optional<int> epsg;  ///< the EPSG code, when the CRS (or its root) names one
  bool geographic = false;  ///< angles (degrees of latitude and longitude), not a projection in metres
};

class GeoRaster {
 public:
  /// Reads band 1 of `path`. Throws GeoRasterError("PATH: ...") when GDAL cannot open it as a raster, it
  /// has no band, or it has no geotransform.
  static GeoRaster read(const std::string& path);

  int columns() const { return columns_; }
  int rows() const { return rows_; }
  const GeoTransform& transform() const { return transform_; }
  /// The CRS, or none when the file carries none (a bare ESRI ASCII grid, a world file alone).
  const std::optional<CoordinateSystem>& crs() const { return crs_; }
  /// The band's nodata value, when it has one.
  const std::optional<double>& nodata() const { return nodata_; }
  const std::string& path() const { return path_; }

  /// Pixel (column, row), row 0 the first (north) row; nodata pixels hold the nodata value.
  double sample(int column, int row) const {
    return values_[std::size_t(column) + std::size_t(columns_) * std::size_t(row)];
  }
  bool is_nodata(int column, int row) const;

  /// The CRS position of a fractional pixel position (column, row in pixel units from the corner).
  std::array<double, 2> position(double column, double row) const;
  /// The fractional pixel position of a CRS point (the inverse of position()).
  std::array<double, 2> pixel_of(double x, double y) const;

  /// The value at CRS (x, y): bilinear between the four pixel centres around it. Throws GeoRasterError for
  /// a point outside the lattice of pixel centres or one a nodata pixel weighs on.
  double value_at(double x, double y) const;

 private:
  std::string path_;
  int columns_ = 0, rows_ = 0;
  GeoTransform transform_;
  std::optional<CoordinateSystem> crs_;
  std::optional<double> nodata_;
  std::vector<double> values_;  // row-major, row 0 north
};

}  // namespace fw::io
