// The reader of a scenario's time section (Time.cpp), which load_scenario (Load.cpp) calls.
//
//   read_time(loader, top.require<"time">(), scenario.time);
#pragma once

#include "io/scenario/Reader.hpp"
#include "io/settings/TimeSettings.hpp"

namespace fw::io::reader {

void read_time(const Loader& loader, const Field& field, TimeSettings& time);

}  // namespace fw::io::reader
