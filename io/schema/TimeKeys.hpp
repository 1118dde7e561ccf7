// The keys of a scenario's time section: the end of the run, its step (or auto), the CFL number of an
// automatic step and the wind's spin-up.
//
//   schema::key(schema::kTimeKeys, "time.cfl").number;   // 0.8: io::TimeSettings' default
//
// Each map's keys stand in the order the loader's messages and the docs list them. Each key's prose is in
// TimeKeys.cpp (time_docs).
#pragma once

#include <span>

#include "io/schema/Bounds.hpp"
#include "io/schema/Key.hpp"

namespace fw::io::schema {

inline constexpr Key kTimeKeys[] = {
    {.path = "time.end",
     .type = Type::number,
     .unit = "s",
     .required = true,
     .bound = Bound::positive,
     .at_most = bounds::kMaxRunTime},
    {.path = "time.dt",
     .type = Type::number_or_auto,
     .unit = "s",
     .bound = Bound::positive,
     .at_most = bounds::kMaxStep,
     .word = "auto"},
    {.path = "time.cfl",
     .type = Type::number,
     .bound = Bound::positive,
     .at_most = bounds::kMaxCfl,
     .number = 0.8},
    {.path = "time.spin_up",
     .type = Type::number,
     .unit = "s",
     .bound = Bound::non_negative,
     .at_most = bounds::kMaxRunTime,
     .number = 0.0},
};

/// The prose of each key of kTimeKeys (TimeKeys.cpp), which schema::docs (io/ScenarioSchema.hpp) finds by its
/// path.
std::span<const KeyDocs> time_docs();

}  // namespace fw::io::schema
