// A single-band float32 GeoTIFF written through GDAL, as QGIS and ArcGIS open it: the grid's geotransform
// (io/gis/GeoRaster.hpp's convention), its CRS when it has one, its nodata value, DEFLATE-compressed. The
// file appears under its name only once complete (base::AtomicFile).
//
//   fw::io::GeoGrid grid;
//   grid.columns = 100, grid.rows = 50;
//   grid.transform = {x0, 2.0, 0.0, y0, 0.0, -2.0};      // north up, 2 m pixels
//   grid.crs_wkt = site_crs.wkt;                        // empty: no CRS (local coordinates)
//   grid.values = speeds;                               // columns * rows, row 0 the north row
//   fw::io::write_geotiff("speed_10m.tif", grid);
#pragma once

#include <filesystem>
#include <optional>
#include <string>
#include <vector>

#include "io/gis/GeoRaster.hpp"

namespace fw::io {

struct GeoGrid {
  int columns = 0, rows = 0;
  GeoTransform transform;
  std::string crs_wkt;           ///< the CRS as WKT (or anything GDAL's SetFromUserInput takes); empty: none
  std::vector<float> values;     ///< columns * rows, row-major, row 0 north
  std::optional<double> nodata;  ///< the value that marks a pixel without data
  std::string description;       ///< the band's, e.g. "wind speed at 10 m above the terrain (m/s)"
};

/// Writes `grid` to `path`. Throws GeoRasterError("PATH: ...") for a grid whose sizes do not fit, a CRS
/// GDAL does not understand, or a write that fails (no file is left then).
void write_geotiff(const std::filesystem::path& path, const GeoGrid& grid);

}  // namespace fw::io
