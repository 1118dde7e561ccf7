// Everything a run needs, built on the host from a validated scenario before the device is touched: the wind
// grid's setup (grid, solids, profile, gusts), every species' modal and wind basis (through the disk cache),
// the placed tree instances, and the canopy drag field for two-way coupling.
//
//   fw::io::Scenario scenario = fw::io::load_scenario("scenarios/gust.yaml");
//   fw::trees::BasisCache cache(fw::trees::BasisCache::default_directory());
//   fw::host::SimulationPlan plan = fw::host::plan_simulation(scenario, &cache, &std::cerr);
//   plan.forest.instance_count();   plan.wind.spec.cell_count();   plan.estimated_device_bytes;
//
// Conventions where DESIGN.md leaves a choice: "auto" boundaries are resolved once, for the wind at t = 0; a
// tree's root stands on the ground under it (the terrain's height, else the domain floor) unless the file
// gives z; a stand's or a tree's yaw turns its species' skeleton counter-clockwise about +z; gusts add
// velocity along the ambient wind at their start time. Errors in species files (a .tree or QSM table that
// does not parse) are std::invalid_argument "FILE:LINE: KEY: ..."; a modal solve that fails is
// trees::ModalError.
#pragma once

#include <cstddef>
#include <ostream>
#include <string>
#include <vector>

#include "host/stages/WindGrid.hpp"
#include "io/Scenario.hpp"
#include "trees/BasisCache.hpp"
#include "trees/Forest.hpp"

namespace fw::host {

struct SpeciesSummary {
  std::string name;
  int nodes = 0;
  int modes = 0;
  int samples = 0;
  int trees = 0;                   ///< instances of this species
  double first_hz = 0.0;           ///< lowest natural frequency at scale 1
  std::string cache = "disabled";  ///< "hit", "miss", "corrupt_recomputed" or "disabled"
  double seconds = 0.0;            ///< time to obtain the basis (load or compute)
};

struct SimulationPlan {
  io::Scenario scenario;
  WindGridSetup wind;  ///< ambient set for t = 0
  trees::Forest forest;
  std::vector<SpeciesSummary> species;
  std::vector<int> instance_species;  ///< species index of every instance (same order as forest.instances())
  std::vector<float> drag_density;    ///< per cell, Cd a (1/m); empty without two-way coupling or trees
  std::vector<float> canopy_density;  ///< per cell, frontal area density a (1/m); empty without trees
  double canopy_dropped_area = 0.0;   ///< m^2 of frontal area outside the domain
  std::size_t estimated_device_bytes = 0;
};

/// Builds the plan. `cache` may be null (no disk cache); `log` (may be null) gets one line per species.
/// Throws std::invalid_argument for input errors (exit code 2), trees::ModalError / std::runtime_error
/// otherwise.
SimulationPlan plan_simulation(const io::Scenario& scenario, const trees::BasisCache* cache,
                               std::ostream* log);

/// The FwGust of a gust event (travel resolved, direction along the ambient wind at its start).
/// A species' skeleton: generated, or read from its .tree or TreeQSM file. A file that does not parse throws
/// std::invalid_argument naming that file's line (an input error, exit code 2).
trees::Skeleton species_skeleton(const io::Species& species);

FwGust to_device_gust(const io::GustEvent& event, const std::array<double, 3>& wind_at_start);

}  // namespace fw::host
