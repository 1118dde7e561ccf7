// A field of a frame's wind grid at a height above the ground, one value per column: what a GIS user takes
// as a wind map (`forestwind export`), the WMO's 10 m wind over terrain.
//
//   const fw::viz::GroundSlice slice = fw::viz::ground_slice(frame.wind, "speed", 10.0);
//   slice.value(i, j);                  // m/s at 10 m above column (i, j)'s ground; NaN where none
//
// The ground of a column is the top of its solid cells counted up from the floor (terrain, or a building's
// roof where one stands); without a solid array, the floor. The value is linear in z between the column's
// cell centres; a height below its first fluid cell's centre takes that cell's value, and one above the top
// cell's centre, or between cells of which one is solid (an overhang), has none (NaN).
#pragma once

#include <array>
#include <string>
#include <vector>

#include "io/gis/GeoTiff.hpp"
#include "io/settings/SiteSettings.hpp"
#include "viz/RunFolder.hpp"

namespace fw::viz {

struct GroundSlice {
  std::string field;                       ///< the field's name, as WindGrid::field takes it
  std::string unit;                        ///< e.g. "m/s"
  double height = 0.0;                     ///< m above the ground
  int columns = 0, rows = 0;               ///< nx, ny
  std::array<double, 2> origin{0.0, 0.0};  ///< the domain's south-west corner (x, y), m
  double cell_size = 0.0;                  ///< h, m
  std::vector<float> values;               ///< nx * ny, x fastest, row 0 the SOUTH row; NaN: none
  float value(int i, int j) const { return values[std::size_t(j) * std::size_t(columns) + std::size_t(i)]; }
  /// The columns that have a value.
  std::size_t valid_count() const;
};

/// `field` of `wind` at `height` m (>= 0, finite) above the ground (see the header). Throws
/// std::invalid_argument("export: ...") for a field the frame lacks (naming those it has) or a bad height.
GroundSlice ground_slice(const WindGrid& wind, const std::string& field, double height);

/// The value io::write_geotiff marks columns without a value with (NaN in the slice).
inline constexpr double kGeoTiffNoData = -9999.0;

/// The slice as a GeoTIFF's grid: north row first, one pixel a column of cells, the band described by field,
/// height and `time` (s). In the domain's own coordinates without a site (no CRS); with one, at the site's
/// origin plus the local position, in its CRS (none when the site has none).
io::GeoGrid geo_grid(const GroundSlice& slice, double time, const io::SiteSettings* site = nullptr);

}  // namespace fw::viz
