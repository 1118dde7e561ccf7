// The keys of a scenario's obstacles: each item of the list is one box, cylinder or sphere.
//
//   schema::key(schema::kObstacleKeys, "obstacles[].box.yaw").unit;   // "degrees"
//
// Each map's keys stand in the order the loader's messages and the docs list them. Each key's prose is in
// ObstacleKeys.cpp (obstacle_docs).
#pragma once

#include <span>

#include "io/schema/Bounds.hpp"
#include "io/schema/Key.hpp"

namespace fw::io::schema {

inline constexpr Key kObstacleKeys[] = {
    {.path = "obstacles[].box"},
    {.path = "obstacles[].box.name", .type = Type::text, .required = true, .noun = "a name"},
    {.path = "obstacles[].box.center",
     .type = Type::point3,
     .unit = "m",
     .required = true,
     .at_least = -bounds::kEarthCircumference,
     .at_most = bounds::kEarthCircumference},
    {.path = "obstacles[].box.size",
     .type = Type::point3,
     .unit = "m",
     .required = true,
     .bound = Bound::positive,
     .at_most = bounds::kEarthCircumference},
    {.path = "obstacles[].box.yaw",
     .type = Type::number,
     .unit = "degrees",
     .at_least = -bounds::kMaxYawDeg,
     .at_most = bounds::kMaxYawDeg,
     .number = 0.0},
    {.path = "obstacles[].cylinder"},
    {.path = "obstacles[].cylinder.name", .type = Type::text, .required = true, .noun = "a name"},
    {.path = "obstacles[].cylinder.base",
     .type = Type::point3,
     .unit = "m",
     .required = true,
     .at_least = -bounds::kEarthCircumference,
     .at_most = bounds::kEarthCircumference},
    {.path = "obstacles[].cylinder.radius",
     .type = Type::number,
     .unit = "m",
     .required = true,
     .bound = Bound::positive,
     .at_most = bounds::kEarthCircumference},
    {.path = "obstacles[].cylinder.height",
     .type = Type::number,
     .unit = "m",
     .required = true,
     .bound = Bound::positive,
     .at_most = bounds::kEarthCircumference},
    {.path = "obstacles[].sphere"},
    {.path = "obstacles[].sphere.name", .type = Type::text, .required = true, .noun = "a name"},
    {.path = "obstacles[].sphere.center",
     .type = Type::point3,
     .unit = "m",
     .required = true,
     .at_least = -bounds::kEarthCircumference,
     .at_most = bounds::kEarthCircumference},
    {.path = "obstacles[].sphere.radius",
     .type = Type::number,
     .unit = "m",
     .required = true,
     .bound = Bound::positive,
     .at_most = bounds::kEarthCircumference},
};

/// The prose of each key of kObstacleKeys (ObstacleKeys.cpp), which schema::docs (io/ScenarioSchema.hpp)
/// finds by its path.
std::span<const KeyDocs> obstacle_docs();

}  // namespace fw::io::schema
