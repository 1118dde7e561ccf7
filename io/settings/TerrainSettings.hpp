// The terrain section of a scenario (docs/scenario.md, "terrain"): the heightmap, read at load. Its keys are
// io/schema/TerrainKeys.hpp's, none with a default.
//
//   if (terrain.map) solids.add_terrain(*terrain.map);
#pragma once

#include <filesystem>
#include <optional>

#include "fluid/Heightmap.hpp"

namespace fw::io {

struct TerrainSettings {
  std::filesystem::path heightmap;  ///< resolved against the scenario folder
  double cell_size = 0.0;           ///< m between samples (PGM; ignored for ESRI grids, 0 when not given)
  double max_height = 0.0;          ///< m for the PGM's maxval (PGM; ignored for ESRI grids)
  /// The heightmap, read and checked at load (always set). A PGM's south-west corner is placed at the
  /// domain's (origin x, origin y); an ESRI grid keeps the placement of its header.
  std::optional<fluid::Heightmap> map;
};

}  // namespace fw::io
