// The keys of a scenario file's top-level map: the scenario's name and seed, and the key of each section's
// map (time, domain, ..., output). A section's own keys are in its table beside this one (io/schema/
// TimeKeys.hpp, ...).
//
//   schema::key(schema::kTopLevelKeys, "wind").required;   // true: a scenario without wind does not load
//
// Each map's keys stand in the order the loader's messages and the docs list them. Each key's prose is in
// TopLevelKeys.cpp (top_level_docs).
#pragma once

#include <span>

#include "io/schema/Key.hpp"

namespace fw::io::schema {

inline constexpr Key kTopLevelKeys[] = {
    {.path = "scenario", .type = Type::text, .required = true, .noun = "a scenario name"},
    {.path = "seed", .type = Type::seed},
    {.path = "time", .required = true},
    {.path = "domain", .required = true},
    {.path = "boundaries"},
    {.path = "wind", .required = true},
    {.path = "events", .type = Type::choice_list, .noun = "a list of events (- gust: {...})"},
    {.path = "obstacles",
     .type = Type::choice_list,
     .noun = "a list of obstacles (- box|cylinder|sphere: {...})"},
    {.path = "terrain"},
    {.path = "forest"},
    {.path = "solver"},
    {.path = "output"},
};

/// The prose of each key of kTopLevelKeys (TopLevelKeys.cpp), which schema::docs (io/ScenarioSchema.hpp)
/// finds by its path.
std::span<const KeyDocs> top_level_docs();

}  // namespace fw::io::schema
