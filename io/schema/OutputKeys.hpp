// The keys of a scenario's output section: the folder, the intervals of frames and probes, the VTK, VDB and
// leaf outputs, the probes and the checkpoints.
//
//   schema::key(schema::kOutputKeys, "output.interval").number;   // 1 s between frames
//
// Each map's keys stand in the order the loader's messages and the docs list them. Each key's prose is in
// OutputKeys.cpp (output_docs).
#pragma once

#include <span>
#include <string_view>

#include "io/schema/Bounds.hpp"
#include "io/schema/Key.hpp"
#include "trees/SpeciesLeaves.hpp"

namespace fw::io::schema {

inline constexpr std::string_view kVtkFieldWords[] = {"velocity",  "pressure", "speed",
                                                      "vorticity", "solid",    "canopy_density"};
inline constexpr std::string_view kVdbGridWords[] = {"vel", "speed", "leaves"};

/// The words of output.leaves.attached and the stride each stands for (io::OutputSettings).
inline constexpr std::string_view kLeafStrideWords[] = {"all", "none"};
inline constexpr int kLeafStrides[] = {1, 0};

inline constexpr Key kOutputKeys[] = {
    {.path = "output.directory",
     .type = Type::directory,
     .word = "out/<scenario>",
     .noun = "a directory path"},
    {.path = "output.interval",
     .type = Type::number,
     .unit = "s",
     .bound = Bound::positive,
     .at_most = bounds::kMaxRunTime,
     .number = 1.0},
    {.path = "output.probe_interval",
     .type = Type::number_or_auto,
     .unit = "s",
     .bound = Bound::positive,
     .at_most = bounds::kMaxRunTime,
     .word = "auto"},
    {.path = "output.vtk"},
    {.path = "output.vtk.wind", .type = Type::boolean, .flag = true},
    {.path = "output.vtk.trees", .type = Type::boolean, .flag = true},
    {.path = "output.vtk.wind_every",
     .type = Type::integer,
     .lowest = 1,
     .highest = bounds::kMaxRunFrames,
     .number = 1},
    {.path = "output.vtk.trees_every",
     .type = Type::integer,
     .lowest = 1,
     .highest = bounds::kMaxRunFrames,
     .number = 1},
    {.path = "output.vtk.fields", .type = Type::word_set, .words = kVtkFieldWords, .chosen = kVtkFieldWords},
    {.path = "output.vdb"},
    {.path = "output.vdb.enabled", .type = Type::boolean, .flag = false},
    {.path = "output.vdb.grids", .type = Type::word_set, .words = kVdbGridWords, .chosen = kVdbGridWords},
    {.path = "output.vdb.every",
     .type = Type::integer,
     .lowest = 1,
     .highest = bounds::kMaxRunFrames,
     .number = 1},
    {.path = "output.leaves"},
    {.path = "output.leaves.attached",
     .type = Type::integer_or_word,
     .lowest = 1,
     .highest = int(trees::SpeciesLeaves::kMaxCount),
     .words = kLeafStrideWords,
     .word = "all"},
    {.path = "output.leaves.vtk", .type = Type::boolean, .flag = true},
    {.path = "output.leaves.every",
     .type = Type::integer,
     .lowest = 1,
     .highest = bounds::kMaxRunFrames,
     .number = 1},
    {.path = "output.probes", .type = Type::list, .noun = "a list of probes"},
    {.path = "output.probes[].name", .type = Type::text, .required = true, .noun = "a probe name"},
    {.path = "output.probes[].position",
     .type = Type::point3,
     .unit = "m",
     .required = true,
     .at_least = -bounds::kEarthCircumference,
     .at_most = bounds::kEarthCircumference},
    {.path = "output.statistics"},
    {.path = "output.statistics.interval",
     .type = Type::number,
     .unit = "s",
     .required = true,
     .bound = Bound::positive,
     .at_most = bounds::kMaxRunTime},
    {.path = "output.statistics.averaging",
     .type = Type::number_or_auto,
     .unit = "s",
     .bound = Bound::non_negative,
     .at_most = bounds::kMaxRunTime,
     .word = "auto"},
    {.path = "output.statistics.sample_every",
     .type = Type::integer,
     .lowest = 1,
     .highest = bounds::kMaxRunFrames,
     .number = 1},
    {.path = "output.statistics.series_every",
     .type = Type::integer,
     .lowest = 1,
     .highest = bounds::kMaxRunFrames,
     .number = 1},
    {.path = "output.statistics.stands", .type = Type::boolean, .flag = false},
    {.path = "output.statistics.regions", .type = Type::list, .noun = "a list of regions"},
    {.path = "output.statistics.regions[].name",
     .type = Type::text,
     .required = true,
     .noun = "a region name"},
    {.path = "output.statistics.regions[].min",
     .type = Type::point2,
     .unit = "m",
     .required = true,
     .at_least = -bounds::kEarthCircumference,
     .at_most = bounds::kEarthCircumference},
    {.path = "output.statistics.regions[].max",
     .type = Type::point2,
     .unit = "m",
     .required = true,
     .at_least = -bounds::kEarthCircumference,
     .at_most = bounds::kEarthCircumference},
    {.path = "output.checkpoint"},
    {.path = "output.checkpoint.interval",
     .type = Type::number,
     .unit = "s",
     .required = true,
     .bound = Bound::positive,
     .at_most = bounds::kMaxRunTime},
    {.path = "output.checkpoint.keep",
     .type = Type::integer,
     .lowest = 1,
     .highest = bounds::kMaxRunFrames,
     .number = 2},
};

/// The prose of each key of kOutputKeys (OutputKeys.cpp), which schema::docs (io/ScenarioSchema.hpp) finds by
/// its path.
std::span<const KeyDocs> output_docs();

}  // namespace fw::io::schema
