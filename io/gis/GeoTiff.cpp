#include "io/gis/GeoTiff.hpp"

#include <fmt/format.h>
#include <gdal_priv.h>
#include <ogr_spatialref.h>

#include "base/AtomicFile.hpp"
#include "io/gis/Gdal.hpp"

namespace fw::io {

void write_geotiff(const std::filesystem::path& path, const GeoGrid& grid) {
  const std::string name = path.string();
  if (grid.columns < 1 || grid.rows < 1 ||
      grid.values.size() != std::size_t(grid.columns) * std::size_t(grid.rows))
    throw GeoRasterError(
        fmt::format("{}: {} values for {} x {} pixels", name, grid.values.size(), grid.columns, grid.rows));
  gdal::register_drivers();
  const gdal::QuietErrors quiet;
  OGRSpatialReference crs;
  if (!grid.crs_wkt.empty() && crs.SetFromUserInput(grid.crs_wkt.c_str()) != OGRERR_NONE)
    throw GeoRasterError(
        fmt::format("{}: a CRS GDAL understands expected ({})", name, gdal::QuietErrors::last_message()));
  try {
    base::require_output_folder("write_geotiff", path);
  } catch (const std::runtime_error& e) {
    throw GeoRasterError(e.what());
  }
  base::AtomicFile file(path);
  {
    GDALDriver* driver = GetGDALDriverManager()->GetDriverByName("GTiff");
    if (!driver) throw GeoRasterError(fmt::format("{}: GDAL's GTiff driver expected, it has none", name));
    const char* const options[] = {"COMPRESS=DEFLATE", "PREDICTOR=3", "TILED=YES", nullptr};
    const gdal::Dataset dataset(driver->Create(file.temporary_path().c_str(), grid.columns, grid.rows, 1,
                                               GDT_Float32, const_cast<char**>(options)));
    if (!dataset)
      throw GeoRasterError(fmt::format("{}: cannot write it ({})", name, gdal::QuietErrors::last_message()));
    double transform[6] = {grid.transform.x0, grid.transform.dx, grid.transform.rx,
                           grid.transform.y0, grid.transform.ry, grid.transform.dy};
    dataset->SetGeoTransform(transform);
    if (!grid.crs_wkt.empty()) dataset->SetSpatialRef(&crs);
    GDALRasterBand* band = dataset->GetRasterBand(1);
    if (grid.nodata) band->SetNoDataValue(*grid.nodata);
    if (!grid.description.empty()) band->SetDescription(grid.description.c_str());
    // RasterIO takes one buffer for both directions; GF_Write only reads it.
    float* values = const_cast<float*>(grid.values.data());
    if (band->RasterIO(GF_Write, 0, 0, grid.columns, grid.rows, values, grid.columns, grid.rows, GDT_Float32,
                       0, 0) != CE_None)
      throw GeoRasterError(fmt::format("{}: cannot write it ({})", name, gdal::QuietErrors::last_message()));
  }  // closing the dataset flushes it
  if (CPLGetLastErrorType() >= CE_Failure)
    throw GeoRasterError(fmt::format("{}: cannot write it ({})", name, gdal::QuietErrors::last_message()));
  file.commit();
}

}  // namespace fw::io
