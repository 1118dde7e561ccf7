// The reader of a scenario's events (Events.cpp), which load_scenario (Load.cpp) calls once the wind is
// read: a gust that travels with the wind takes the wind at its start.
//
//   scenario.events = read_events(loader, *events, scenario.wind);
#pragma once

#include <vector>

#include "io/scenario/Reader.hpp"
#include "io/settings/GustEvent.hpp"
#include "io/settings/WindSource.hpp"

namespace fw::io::reader {

std::vector<GustEvent> read_events(const Loader& loader, const Field& field, const WindSource& wind);

}  // namespace fw::io::reader
