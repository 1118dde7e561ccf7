// The keys of a scenario's terrain section: a PGM heightmap and its scale, or a raster GDAL reads.
//
//   schema::key(schema::kTerrainKeys, "terrain.raster").type;   // Type::file
//
// Each map's keys stand in the order the loader's messages and the docs list them. Each key's prose is in
// TerrainKeys.cpp (terrain_docs).
#pragma once

#include <span>

#include "io/schema/Bounds.hpp"
#include "io/schema/Key.hpp"

namespace fw::io::schema {

inline constexpr Key kTerrainKeys[] = {
    {.path = "terrain.heightmap", .type = Type::file, .noun = "a file path (PGM image)"},
    {.path = "terrain.raster",
     .type = Type::file,
     .noun = "a file path (a raster GDAL reads: GeoTIFF, ESRI ASCII grid, ...)"},
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
