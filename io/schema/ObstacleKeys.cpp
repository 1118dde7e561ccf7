// The prose docs/scenario.md prints for each key of kObstacleKeys (render_scenario_docs,
// io/ScenarioSchema.cpp): its meaning, and its default, allowed values and limits in words where its type
// does not say them. Here, not in the header, so that no reader of the keys compiles their prose.
#include "io/schema/ObstacleKeys.hpp"

#include "io/schema/BoundReasons.hpp"

namespace fw::io::schema {

namespace {

constexpr KeyDocs kDocs[] = {
    {.path = "obstacles[].box",
     .description = "A box, possibly turned about the vertical axis through its centre."},
    {.path = "obstacles[].box.name", .description = "Name, used in messages. Names need not be unique."},
    {.path = "obstacles[].box.center", .bounds_why = why::kEarth, .description = "Centre of the box."},
    {.path = "obstacles[].box.size",
     .bounds_why = why::kEarth,
     .description = "Full edge lengths along the box's own axes (before yaw)."},
    {.path = "obstacles[].box.yaw",
     .bounds_why = why::kYaw,
     .description = "Rotation about +z, counter-clockwise seen from above."},
    {.path = "obstacles[].cylinder", .description = "A vertical cylinder standing on its base."},
    {.path = "obstacles[].cylinder.name", .description = "Name, used in messages."},
    {.path = "obstacles[].cylinder.base",
     .bounds_why = why::kEarth,
     .description = "Centre of the bottom disc."},
    {.path = "obstacles[].cylinder.radius", .bounds_why = why::kEarth, .description = "Radius."},
    {.path = "obstacles[].cylinder.height",
     .bounds_why = why::kEarth,
     .description = "Extent upward from the base."},
    {.path = "obstacles[].sphere", .description = "A sphere."},
    {.path = "obstacles[].sphere.name", .description = "Name, used in messages."},
    {.path = "obstacles[].sphere.center", .bounds_why = why::kEarth, .description = "Centre."},
    {.path = "obstacles[].sphere.radius", .bounds_why = why::kEarth, .description = "Radius."},
};

}  // namespace

std::span<const KeyDocs> obstacle_docs() {
  return kDocs;
}

}  // namespace fw::io::schema
