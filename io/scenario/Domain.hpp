// The readers of a scenario's domain and boundaries sections (Domain.cpp), which load_scenario (Load.cpp)
// calls in this order, the boundaries with the domain read.
//
//   read_domain(loader, top.require<"domain">(), scenario.domain);
//   read_boundaries(loader, *boundaries, scenario.domain, scenario.boundaries,
//                   scenario.ground_roughness_length);
#pragma once

#include <array>

#include "fluid/InflowProfile.hpp"
#include "io/scenario/Reader.hpp"
#include "io/settings/BoundaryChoice.hpp"
#include "io/settings/DomainSettings.hpp"

namespace fw::io::reader {

void read_domain(const Loader& loader, const Field& field, DomainSettings& domain);
/// The faces' conditions, by FW_FACE_*, and boundaries.roughness_length when given.
void read_boundaries(const Loader& loader, const Field& field, const DomainSettings& domain,
                     std::array<BoundaryChoice, 6>& boundaries, double& ground_roughness_length);
/// The roughness length of a rough ground that boundaries.roughness_length leaves out: the log profile's,
/// else the schema's default; it too must lie below h / 2. `boundaries_field` is the file's boundaries map.
/// Called once the wind (its profile) is read.
void resolve_ground_roughness(const Loader& loader, const Field& boundaries_field,
                              const DomainSettings& domain, const std::array<BoundaryChoice, 6>& boundaries,
                              const fluid::InflowProfile& profile, double& ground_roughness_length);

}  // namespace fw::io::reader
