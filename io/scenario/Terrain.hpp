// The reader of a scenario's terrain (Terrain.cpp), which load_scenario (Load.cpp) calls right after the
// domain, before anything is placed in it: a PGM is placed at the domain's corner; a raster GDAL reads
// (terrain.raster) makes the run's site, and the domain's origin becomes the local (0, 0, 0).
//
//   scenario.terrain = read_terrain(loader, *terrain, scenario.domain);
#pragma once

#include "io/scenario/Reader.hpp"
#include "io/settings/DomainSettings.hpp"
#include "io/settings/TerrainSettings.hpp"

namespace fw::io::reader {

/// Reads the terrain; with a raster, moves domain.origin into the site and sets it to (0, 0, 0).
TerrainSettings read_terrain(const Loader& loader, const Field& field, DomainSettings& domain);

}  // namespace fw::io::reader
