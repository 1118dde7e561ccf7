// The reader of a scenario's output section (Output.cpp), which load_scenario (Load.cpp) calls last: the
// default folder names the scenario, probes stand inside the domain, and the intervals of frames, probe rows
// and checkpoints give at most one a step of the longest run (io/schema/Bounds.hpp) up to time.end.
//
//   scenario.output = read_output(loader, output, scenario.name, scenario.domain, scenario.time.end);
#pragma once

#include <string>

#include "io/scenario/Reader.hpp"
#include "io/settings/DomainSettings.hpp"
#include "io/settings/OutputSettings.hpp"

namespace fw::io::reader {

OutputSettings read_output(const Loader& loader, const Field& field, const std::string& scenario_name,
                           const DomainSettings& domain, double end);

}  // namespace fw::io::reader
