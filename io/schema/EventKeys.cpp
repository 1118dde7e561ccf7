// The prose docs/scenario.md prints for each key of kEventKeys (render_scenario_docs, io/ScenarioSchema.cpp):
// its meaning, and its default, allowed values and limits in words where its type does not say them. Here,
// not in the header, so that no reader of the keys compiles their prose.
#include "io/schema/EventKeys.hpp"

#include "io/schema/BoundReasons.hpp"

namespace fw::io::schema {

namespace {

constexpr KeyDocs kDocs[] = {
    {.path = "events[].gust", .default_note = "required in each item", .description = "One gust."},
    {.path = "events[].gust.start",
     .bounds_why = why::kRunTime,
     .description = "Time at which the gust begins."},
    {.path = "events[].gust.duration", .bounds_why = why::kRunTime, .description = "Length of the envelope."},
    {.path = "events[].gust.peak_speed",
     .bounds_why = why::kWindSpeed,
     .description = "Extra speed at the envelope's peak and the ball's centre. A plain number, not an "
                    "expression."},
    {.path = "events[].gust.center",
     .constraint = "may lie outside the domain",
     .bounds_why = why::kEarth,
     .description = "Position of the ball's centre at `start`."},
    {.path = "events[].gust.radius", .bounds_why = why::kEarth, .description = "Radius R of the Gaussian."},
    {.path = "events[].gust.travel",
     .bounds_why = why::kWindSpeed,
     .description = "Velocity of the ball. `with_wind` takes the ambient wind vector at the reference height "
                    "at time `start` and keeps it constant."},
};

}  // namespace

std::span<const KeyDocs> event_docs() {
  return kDocs;
}

}  // namespace fw::io::schema
