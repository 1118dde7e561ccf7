// The prose docs/scenario.md prints for each key of kTopLevelKeys (render_scenario_docs,
// io/ScenarioSchema.cpp): its meaning, and its default, allowed values and limits in words where its type
// does not say them. Here, not in the header, so that no reader of the keys compiles their prose.
#include "io/schema/TopLevelKeys.hpp"

namespace fw::io::schema {

namespace {

constexpr KeyDocs kDocs[] = {
    {.path = "scenario",
     .constraint = "no `/` or `\\`, no control characters, not `.` or `..`",
     .description = "Name of the scenario. Used as the folder name in the default output directory "
                    "`out/<scenario>`."},
    {.path = "seed",
     .description = "Global seed, recorded in `run.json`. Seeds the file does not give derive from it: stand "
                    "k is laid out with `seed + k`, species k generates its skeleton with `seed + 1 + k` and "
                    "its leaves with `seed + 2^32 + k`."},
    {.path = "time", .description = "Simulated time span, time step and wind spin-up."},
    {.path = "domain", .description = "The wind grid."},
    {.path = "boundaries", .description = "Boundary condition per face."},
    {.path = "wind", .description = "The ambient wind."},
    {.path = "events", .description = "Gust events."},
    {.path = "obstacles", .description = "Solid obstacles."},
    {.path = "terrain", .default_note = "none (flat floor)", .description = "Terrain."},
    {.path = "forest", .default_note = "no trees", .description = "The forest."},
    {.path = "solver", .description = "Wind solver settings."},
    {.path = "output", .description = "What to write, and where."},
};

}  // namespace

std::span<const KeyDocs> top_level_docs() {
  return kDocs;
}

}  // namespace fw::io::schema
