// Where a run stands on the Earth (docs/gis.md, "Coordinates"): the terrain raster's coordinate reference
// system and the domain's corner in it. A scenario with a terrain.raster has a site; the run computes in
// local coordinates, metres from that corner, because float32 keeps only about half a metre at a UTM
// northing of 5,000 km.
//
//   if (const fw::io::SiteSettings* site = scenario.site())
//     auto [x, y, z] = site->to_site({12.0, 40.0, 3.0});   // the raster's CRS: easting, northing, elevation
#pragma once

#include <array>
#include <filesystem>
#include <optional>
#include <string>

#include "io/gis/GeoRaster.hpp"

namespace fw::io {

struct SiteSettings {
  /// The raster's CRS; none for a raster that carries none (a bare ESRI ASCII grid): the run then sits in
  /// the raster's own coordinates, whatever they are.
  std::optional<CoordinateSystem> crs;
  /// domain.origin as the file gives it: the domain's south-west corner (x, y) in the CRS and the
  /// elevation of its floor (z), m. Local (0, 0, 0).
  std::array<double, 3> origin{0, 0, 0};
  std::filesystem::path raster;  ///< the terrain raster, resolved against the scenario folder

  /// A local point (m from the corner) in the site's coordinates.
  std::array<double, 3> to_site(const std::array<double, 3>& local) const {
    return {origin[0] + local[0], origin[1] + local[1], origin[2] + local[2]};
  }
  /// The CRS in the words a GIS user reads: "EPSG:32632 (WGS 84 / UTM zone 32N)", "EPSG:32632" when the
  /// name is not known, or "none".
  std::string crs_label() const;
};

}  // namespace fw::io
