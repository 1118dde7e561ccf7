// The reader of a scenario's wind section (Wind.cpp), which load_scenario (Load.cpp) calls once the time,
// the domain and the boundaries are read.
//
//   scenario.wind = read_wind(loader, top.require<"wind">(), scenario.time.end, scenario.domain,
//                             scenario.boundaries, scenario.seed);
#pragma once

#include <array>
#include <cstdint>

#include "io/scenario/Reader.hpp"
#include "io/settings/BoundaryChoice.hpp"
#include "io/settings/DomainSettings.hpp"
#include "io/settings/WindSource.hpp"

namespace fw::io::reader {

/// `end`: time.end, over which the speed and direction must be finite; `seed`: the scenario's, the
/// turbulence's default.
WindSource read_wind(const Loader& loader, const Field& field, double end, const DomainSettings& domain,
                     const std::array<BoundaryChoice, 6>& boundaries, std::uint64_t seed);

}  // namespace fw::io::reader
