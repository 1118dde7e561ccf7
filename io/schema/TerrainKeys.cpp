// The prose docs/scenario.md prints for each key of kTerrainKeys (render_scenario_docs,
// io/ScenarioSchema.cpp): its meaning, and its default, allowed values and limits in words where its type
// does not say them. Here, not in the header, so that no reader of the keys compiles their prose.
#include "io/schema/TerrainKeys.hpp"

#include "io/schema/BoundReasons.hpp"

namespace fw::io::schema {

namespace {

constexpr KeyDocs kDocs[] = {
    {.path = "terrain.heightmap",
     .default_note = "none; give it or `raster`",
     .allowed = "a readable PGM image (P2 or P5); relative to the scenario's folder",
     .description = "The height field as an image, without georeference: its south-west corner at the "
                    "domain's, its pixels `cell_size` apart, its brightest `max_height` above the floor."},
    {.path = "terrain.raster",
     .default_note = "none; give it or `heightmap`",
     .allowed = "a readable raster GDAL reads (GeoTIFF, ESRI ASCII grid, ...), north-up, square pixels, "
                "in a projected CRS or none, with data under the whole domain; relative to the scenario's "
                "folder",
     .description = "A digital elevation model, elevations in metres. It makes the run's site "
                    "(docs/gis.md): `domain.origin` is then in the raster's CRS, the domain's south-west "
                    "corner and its floor's elevation, and every other position of the scenario is local, "
                    "metres from that corner."},
    {.path = "terrain.cell_size",
     .default_note = "required for a PGM; refused with a raster",
     .bounds_why = why::kEarth,
     .description = "Distance between PGM pixels."},
    {.path = "terrain.max_height",
     .default_note = "required for a PGM; refused with a raster",
     .bounds_why = why::kRelief,
     .description = "Height that the PGM's maxval stands for."},
};

}  // namespace

std::span<const KeyDocs> terrain_docs() {
  return kDocs;
}

}  // namespace fw::io::schema
