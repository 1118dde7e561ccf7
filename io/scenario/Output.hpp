// The reader of a scenario's output section (Output.cpp), which load_scenario (Load.cpp) calls last: the
// default folder names the scenario, and probes stand inside the domain.
//
//   scenario.output = read_output(loader, output, scenario.name, scenario.domain);
#pragma once

#include <string>

#include "io/scenario/Reader.hpp"
#include "io/settings/DomainSettings.hpp"
#include "io/settings/OutputSettings.hpp"

namespace fw::io::reader {

OutputSettings read_output(const Loader& loader, const Field& field, const std::string& scenario_name,
                           const DomainSettings& domain);

}  // namespace fw::io::reader
