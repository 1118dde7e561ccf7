#include "io/gis/GeoRaster.hpp"

#include <fmt/format.h>
#include <gdal_priv.h>
#include <ogr_spatialref.h>

#include <cmath>

#include "io/gis/Gdal.hpp"

namespace fw::io {

namespace {

CoordinateSystem coordinate_system(const OGRSpatialReference& srs) {
  CoordinateSystem crs;
  char* wkt = nullptr;
  const char* const options[] = {"FORMAT=WKT2_2019", nullptr};
  if (srs.exportToWkt(&wkt, options) == OGRERR_NONE && wkt) crs.wkt = wkt;
  CPLFree(wkt);
  if (const char* name = srs.GetName()) crs.name = name;
  const char* authority = srs.GetAuthorityName(nullptr);
  const char* code = srs.GetAuthorityCode(nullptr);
  if (authority && code && std::string(authority) == "EPSG") crs.epsg = std::stoi(code);
  crs.geographic = srs.IsGeographic() != 0;
  return crs;
}

}  // namespace

GeoRaster GeoRaster::read(const std::string& path) {
  gdal::register_drivers();
  const gdal::QuietErrors quiet;
  const gdal::Dataset dataset(GDALDataset::Open(path.c_str(), GDAL_OF_RASTER | GDAL_OF_READONLY));
  if (!dataset)
    throw GeoRasterError(
        fmt::format("{}: a raster GDAL reads expected ({})", path, gdal::QuietErrors::last_message()));
  if (dataset->GetRasterCount() < 1) throw GeoRasterError(fmt::format("{}: a raster band expected", path));
  GeoRaster raster;
  raster.path_ = path;
  raster.columns_ = dataset->GetRasterXSize();
  raster.rows_ = dataset->GetRasterYSize();
  double t[6];
  if (dataset->GetGeoTransform(t) != CE_None)
    throw GeoRasterError(fmt::format("{}: a georeferenced raster expected (it has no geotransform)", path));
  raster.transform_ = {t[0], t[1], t[2], t[3], t[4], t[5]};
  if (const OGRSpatialReference* srs = dataset->GetSpatialRef(); srs && !srs->IsEmpty())
    raster.crs_ = coordinate_system(*srs);

  GDALRasterBand* band = dataset->GetRasterBand(1);
  int has_nodata = 0;
  const double nodata = band->GetNoDataValue(&has_nodata);
  if (has_nodata) raster.nodata_ = nodata;
  raster.values_.resize(std::size_t(raster.columns_) * std::size_t(raster.rows_));
  if (band->RasterIO(GF_Read, 0, 0, raster.columns_, raster.rows_, raster.values_.data(), raster.columns_,
                     raster.rows_, GDT_Float64, 0, 0) != CE_None)
    throw GeoRasterError(
        fmt::format("{}: readable pixels expected ({})", path, gdal::QuietErrors::last_message()));
  return raster;
}

bool GeoRaster::is_nodata(int column, int row) const {
  const double v = sample(column, row);
  if (std::isnan(v)) return true;
  if (!nodata_) return false;
  // A NaN nodata marks NaN pixels, handled above; else the value itself.
  return !std::isnan(*nodata_) && v == *nodata_;
}

std::array<double, 2> GeoRaster::position(double column, double row) const {
  const GeoTransform& t = transform_;
  return {t.x0 + column * t.dx + row * t.rx, t.y0 + column * t.ry + row * t.dy};
}

std::array<double, 2> GeoRaster::pixel_of(double x, double y) const {
  // Invert the 2 x 2 linear part of the geotransform.
  const GeoTransform& t = transform_;
  const double det = t.dx * t.dy - t.rx * t.ry;
  const double ex = x - t.x0, ey = y - t.y0;
  return {(t.dy * ex - t.rx * ey) / det, (-t.ry * ex + t.dx * ey) / det};
}

double GeoRaster::value_at(double x, double y) const {
  const auto [pc, pr] = pixel_of(x, y);
  // Pixel centres lie at whole + 1/2 pixel positions.
  const double fc = pc - 0.5, fr = pr - 0.5;
  if (!(fc >= 0.0 && fr >= 0.0 && fc <= columns_ - 1.0 && fr <= rows_ - 1.0))
    throw GeoRasterError(
        fmt::format("{}: a point within the pixel centres expected, got ({}, {})", path_, x, y));
  const int c0 = std::min(int(fc), columns_ - 1), r0 = std::min(int(fr), rows_ - 1);
  const int c1 = std::min(c0 + 1, columns_ - 1), r1 = std::min(r0 + 1, rows_ - 1);
  const double a = fc - c0, b = fr - r0;
  // The four centres around the point and their weights; one of weight 0 (the point on a centre or its
  // row or column) takes no part, so a nodata pixel there does not matter.
  const std::array<std::array<int, 2>, 4> corners{{{c0, r0}, {c1, r0}, {c0, r1}, {c1, r1}}};
  const std::array<double, 4> weights{(1 - a) * (1 - b), a * (1 - b), (1 - a) * b, a * b};
  double value = 0.0;
  for (std::size_t n = 0; n < corners.size(); ++n) {
    if (weights[n] == 0.0) continue;
    const auto [c, r] = corners[n];
    if (is_nodata(c, r))
      throw GeoRasterError(fmt::format(
          "{}: data around ({}, {}) expected, pixel (column {}, row {}) is nodata", path_, x, y, c, r));
    value += weights[n] * sample(c, r);
  }
  return value;
}

}  // namespace fw::io
