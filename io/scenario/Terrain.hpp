// The reader of a scenario's terrain (Terrain.cpp), which load_scenario (Load.cpp) calls once the domain is
// read: a PGM is placed at the domain's corner.
//
//   scenario.terrain = read_terrain(loader, *terrain, scenario.domain);
#pragma once

#include "io/scenario/Reader.hpp"
#include "io/settings/DomainSettings.hpp"
#include "io/settings/TerrainSettings.hpp"

namespace fw::io::reader {

TerrainSettings read_terrain(const Loader& loader, const Field& field, const DomainSettings& domain);

}  // namespace fw::io::reader
