// The readers of the scenario's sections, one file each in io/scenario/, called by load_scenario
// (io/scenario/Load.cpp) in this order. Each reads its map of the file into the Scenario, with the sections
// read before it at hand (the domain, the boundaries, the wind), and throws ScenarioError for what is wrong.
#pragma once

#include <cstdint>
#include <vector>

#include "io/Scenario.hpp"
#include "io/scenario/Reader.hpp"

namespace fw::io::reader {

void read_time(const Loader& loader, const Field& field, TimeSettings& time);  // Time.cpp

// Domain.cpp
void read_domain(const Loader& loader, const Field& field, DomainSettings& domain);
void read_boundaries(const Loader& loader, const Field& field, Scenario& scenario);
/// The roughness length of a rough ground that boundaries.roughness_length leaves out: the log profile's,
/// else the schema's default; it too must lie below h / 2. `boundaries` is the file's boundaries map. Called
/// once the wind (its profile) is read.
void resolve_ground_roughness(const Loader& loader, const Field& boundaries, Scenario& scenario);

void read_wind(const Loader& loader, const Field& field, Scenario& scenario);  // Wind.cpp
/// wind.turbulence, once the domain and the seed are read (Turbulence.cpp).
TurbulenceSettings read_turbulence(const Loader& loader, const Field& field, const Scenario& scenario);

void read_events(const Loader& loader, const Field& field, Scenario& scenario);     // Events.cpp
void read_obstacles(const Loader& loader, const Field& field, Scenario& scenario);  // Obstacles.cpp
void read_terrain(const Loader& loader, const Field& field, Scenario& scenario);    // Terrain.cpp

void read_forest(const Loader& loader, const Field& field, Scenario& scenario);  // Forest.cpp
/// One item of forest.species, after the species `earlier` (Species.cpp).
Species read_species(const Loader& loader, const Field& item, const std::vector<Species>& earlier,
                     std::uint64_t global_seed);

void read_solver(const Loader& loader, const Field& field, SolverSettings& solver);  // Solver.cpp
void read_output(const Loader& loader, const Field& field, Scenario& scenario);      // Output.cpp

}  // namespace fw::io::reader
