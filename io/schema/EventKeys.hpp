// The keys of a scenario's events: each item of the list is one gust.
//
//   schema::key(schema::kEventKeys, "events[].gust.travel").word;   // "with_wind"
//
// Each map's keys stand in the order the loader's messages and the docs list them. Each key's prose is in
// EventKeys.cpp (event_docs).
#pragma once

#include <span>

#include "io/schema/Bounds.hpp"
#include "io/schema/Key.hpp"

namespace fw::io::schema {

inline constexpr Key kEventKeys[] = {
    {.path = "events[].gust", .required = true},
    {.path = "events[].gust.start",
     .type = Type::number,
     .unit = "s",
     .required = true,
     .bound = Bound::non_negative,
     .at_most = bounds::kMaxRunTime},
    {.path = "events[].gust.duration",
     .type = Type::number,
     .unit = "s",
     .required = true,
     .bound = Bound::positive,
     .at_most = bounds::kMaxRunTime},
    {.path = "events[].gust.peak_speed",
     .type = Type::number,
     .unit = "m/s",
     .required = true,
     .bound = Bound::non_negative,
     .at_most = bounds::kMaxWindSpeed},
    {.path = "events[].gust.center",
     .type = Type::point3,
     .unit = "m",
     .required = true,
     .at_least = -bounds::kEarthCircumference,
     .at_most = bounds::kEarthCircumference},
    {.path = "events[].gust.radius",
     .type = Type::number,
     .unit = "m",
     .required = true,
     .bound = Bound::positive,
     .at_most = bounds::kEarthCircumference},
    {.path = "events[].gust.travel",
     .type = Type::velocity_or_with_wind,
     .unit = "m/s",
     .at_least = -bounds::kMaxWindSpeed,
     .at_most = bounds::kMaxWindSpeed,
     .word = "with_wind"},
};

/// The prose of each key of kEventKeys (EventKeys.cpp), which schema::docs (io/ScenarioSchema.hpp) finds by
/// its path.
std::span<const KeyDocs> event_docs();

}  // namespace fw::io::schema
