// The reader of a scenario's wind.turbulence (Turbulence.cpp), which read_wind (Wind.cpp) calls: the box is
// sized in the domain's cells.
//
//   wind.turbulence = read_turbulence(loader, *turbulence, domain, seed);
#pragma once

#include <cstdint>

#include "io/scenario/Reader.hpp"
#include "io/settings/DomainSettings.hpp"
#include "io/settings/WindSource.hpp"

namespace fw::io::reader {

/// `seed`: the scenario's, the default of the turbulence's.
TurbulenceSettings read_turbulence(const Loader& loader, const Field& field, const DomainSettings& domain,
                                   std::uint64_t seed);

}  // namespace fw::io::reader
