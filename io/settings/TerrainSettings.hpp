// The terrain section of a scenario (docs/scenario.md, "terrain"): a PGM heightmap, or a raster GDAL reads
// with the site it places the run on, read at load. Its keys are io/schema/TerrainKeys.hpp's, none with a
// default.
//
//   if (terrain.map) solids.add_terrain(*terrain.map);
#pragma once

#include <filesystem>
#include <optional>

#include "fluid/Heightmap.hpp"
#include "io/settings/SiteSettings.hpp"

namespace fw::io {

struct TerrainSettings {
  std::filesystem::path heightmap;  ///< a PGM, resolved against the scenario folder; empty with a raster
  double cell_size = 0.0;           ///< m between PGM pixels (0 with a raster)
  double max_height = 0.0;          ///< m for the PGM's maxval (0 with a raster)
  /// terrain.raster's: the raster, its CRS and domain.origin in it. The scenario's positions are then local,
  /// metres from the domain's corner, and the domain's origin is (0, 0, 0).
  std::optional<SiteSettings> site;
  /// The heights above the domain floor in the run's coordinates, read and checked at load (always set): a
  /// PGM's south-west corner at the domain's (origin x, origin y); a raster's pixels under the domain, its
  /// elevations less the floor's.
  std::optional<fluid::Heightmap> map;
};

}  // namespace fw::io
