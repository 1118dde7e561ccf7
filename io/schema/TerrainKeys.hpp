// The keys of a scenario's terrain section: the heightmap and, for a PGM, its scale.
//
//   schema::key(schema::kTerrainKeys, "terrain.heightmap").required;   // true
//
// Each map's keys stand in the order the loader's messages and the docs list them. Each key's prose is in
// TerrainKeys.cpp (terrain_docs).
#pragma once

#include <span>

#include "io/schema/Bounds.hpp"
#include "io/schema/Key.hpp"

namespace fw::io::schema {

inline constexpr Key kTerrainKeys[] = {
    {.path = "terrain.heightmap",
     .type = Type::file,
     .required = true,
     .noun = "a file path (PGM or ESRI ASCII grid)"},
    {.path = "terrain.cell_size",
     .type = Type::number,
     .unit = "m",
     .bound = Bound::positive,
     .at_most = bounds::kEarthCircumference},
    {.path = "terrain.max_height",
     .type = Type::number,
     .unit = "m",
     .bound = Bound::non_negative,
     .at_most = bounds::kMaxRelief},
};

/// The prose of each key of kTerrainKeys (TerrainKeys.cpp), which schema::docs (io/ScenarioSchema.hpp) finds
/// by its path.
std::span<const KeyDocs> terrain_docs();

}  // namespace fw::io::schema
