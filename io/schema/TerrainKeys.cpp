// The prose docs/scenario.md prints for each key of kTerrainKeys (render_scenario_docs,
// io/ScenarioSchema.cpp): its meaning, and its default, allowed values and limits in words where its type
// does not say them. Here, not in the header, so that no reader of the keys compiles their prose.
#include "io/schema/TerrainKeys.hpp"

#include "io/schema/BoundReasons.hpp"

namespace fw::io::schema {

namespace {

constexpr KeyDocs kDocs[] = {
    {.path = "terrain.heightmap",
     .allowed = "a readable PGM or ESRI ASCII grid; relative to the scenario's folder",
     .description = "The height field."},
    {.path = "terrain.cell_size",
     .default_note = "required for a PGM; ignored for an ESRI grid",
     .constraint = "checked for an ESRI grid too",
     .bounds_why = why::kEarth,
     .description = "Distance between PGM pixels."},
    {.path = "terrain.max_height",
     .default_note = "required for a PGM; ignored for an ESRI grid",
     .constraint = "checked for an ESRI grid too",
     .bounds_why = why::kRelief,
     .description = "Height that the PGM's maxval stands for."},
};

}  // namespace

std::span<const KeyDocs> terrain_docs() {
  return kDocs;
}

}  // namespace fw::io::schema
