// The reader of a scenario's forest (Forest.cpp), which load_scenario (Load.cpp) calls once the domain and
// the terrain are read: trees stand inside the domain, on the terrain.
//
//   scenario.forest = read_forest(loader, *forest, scenario.domain, scenario.terrain, scenario.seed);
#pragma once

#include <cstdint>
#include <optional>

#include "io/scenario/Reader.hpp"
#include "io/settings/DomainSettings.hpp"
#include "io/settings/ForestSettings.hpp"
#include "io/settings/TerrainSettings.hpp"

namespace fw::io::reader {

/// `seed`: the scenario's, from which the stands', skeletons' and leaves' defaults derive.
ForestSettings read_forest(const Loader& loader, const Field& field, const DomainSettings& domain,
                           const std::optional<TerrainSettings>& terrain, std::uint64_t seed);

}  // namespace fw::io::reader
