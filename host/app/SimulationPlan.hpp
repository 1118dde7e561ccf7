// Everything a run needs, resolved on the host from a validated scenario before the device is touched: the
// wind grid's setup (grid, solids, profile, gusts), the ambient wind over time, every species' modal and wind
// basis (through the disk cache), every species' leaves, the placed tree instances, the canopy drag of
// two-way coupling and the output settings. Nothing past the plan reads the scenario.
//
//   fw::io::Scenario scenario = fw::io::load_scenario("scenarios/gust.yaml");
//   fw::trees::BasisCache cache(fw::trees::BasisCache::default_directory());
//   fw::host::SimulationPlan plan = fw::host::plan_simulation(scenario, &cache, &std::cerr);
//   plan.forest.instance_count();   plan.wind.spec.cell_count();   plan.ambient_wind(30.0);
//   plan.leaves[0].count();         plan.leaf_count;                // species 0's leaves, all trees' leaves
//
// Conventions where DESIGN.md leaves a choice: "auto" boundaries are resolved once, for the wind at t = 0; a
// tree's root stands on the ground under it (the terrain's height, else the domain floor) unless the file
// gives z; a stand's or a tree's yaw turns its species' skeleton counter-clockwise about +z; gusts add
// velocity along the ambient wind at their start time. Errors in species files (a .tree or QSM table that
// does not parse) are std::invalid_argument "FILE:LINE: KEY: ..."; a modal solve that fails is
// trees::ModalError.
#pragma once

#include <array>
#include <cstddef>
#include <cstdint>
#include <functional>
#include <ostream>
#include <string>
#include <vector>

#include "host/app/CoupledStep.hpp"
#include "host/stages/WindGrid.hpp"
#include "io/Scenario.hpp"
#include "io/writers/ManifestWriter.hpp"
#include "kernels/shared_types.h"
#include "trees/BasisCache.hpp"
#include "trees/Forest.hpp"
#include "trees/SpeciesLeaves.hpp"

namespace fw::host {

/// Where a run came from, for run.json and the scenario copy in the output folder.
struct ScenarioRecord {
  std::string name;
  std::string file_name;  ///< the scenario file's name, without its folder
  std::string text;       ///< the file's bytes
  std::uint64_t seed = 0;
};

struct SimulationPlan {
  ScenarioRecord scenario;
  double end_time = 0.0;  ///< s: the run covers [0, end_time]
  /// The ambient wind at time t (s): m/s at the reference height, x east, y north.
  std::function<std::array<double, 3>(double)> ambient_wind;
  WindGridSetup wind;  ///< ambient set for t = 0
  /// sigma_u of the inflow turbulence at time t (s), m/s; empty without wind.turbulence.
  std::function<double(double)> turbulence_sigma;
  /// sigma_u / U at time t (s) for the trees' unresolved turbulence; empty without it.
  std::function<double(double)> unresolved_intensity;
  double probe_interval = 0.0;  ///< s between probe samples; 0: every step
  CouplingSettings coupling;
  trees::Forest forest;
  std::vector<io::SpeciesSummary> species;
  /// Per forest species, in forest order: its leaves (docs/leaves.md) on the skeleton of its basis, in the
  /// skeleton frame; default-constructed (none) for a species without. coupling.leaves holds the same.
  std::vector<trees::SpeciesLeaves> leaves;
  long leaf_count = 0;                ///< leaves of all instances: the sum over trees of their species' count
  std::vector<float> canopy_density;  ///< per cell, frontal area density a (1/m); empty without trees
  double canopy_dropped_area = 0.0;   ///< m^2 of frontal area outside the domain
  io::OutputSettings output;          ///< folder, frame interval, which writers and fields
  std::size_t estimated_device_bytes = 0;
};

/// Builds the plan. `cache` may be null (no disk cache); `log` (may be null) gets one line per species.
/// Throws std::invalid_argument for input errors (exit code 2), trees::ModalError / std::runtime_error
/// otherwise.
SimulationPlan plan_simulation(const io::Scenario& scenario, const trees::BasisCache* cache,
                               std::ostream* log);

/// A species' skeleton: generated, or read from its .tree or TreeQSM file. A file that does not parse throws
/// std::invalid_argument naming that file's line (an input error, exit code 2).
trees::Skeleton species_skeleton(const io::Species& species);

/// Device memory of the leaves (host/stages/LeafStages): per leaf its state (1 byte), angle and rate (2
/// floats), site and instance (2 ints), position, velocity, normal and the frame's position and normal
/// (float4 each), and at most one site (its cell and its wind: 4 values); per species leaf its FW_REST_FIELDS
/// floats of the rest table and its element's 2 nodes.
inline constexpr std::size_t kDeviceBytesPerLeaf = 1 + 2 * 4 + 2 * 4 + 5 * 16 + 4 * 4;
inline constexpr std::size_t kDeviceBytesPerSpeciesLeaf = (FW_REST_FIELDS + 2) * 4;

/// The turbulence box points per grid cell along each axis (the box's spacing is h / this); the scenario
/// loader sizes the box with it too, so it lives with the box.
using fluid::kTurbulencePointsPerCell;
/// The unit-sigma_u inflow turbulence box of wind.turbulence on a grid of cell size h (m), points every h/2;
/// unequal sigma_u, sigma_v, sigma_w scale the box's components (along-wind on the horizontal axis closer to
/// the wind at t = 0).
fluid::TurbulenceBoxSpec inflow_turbulence_spec(const io::TurbulenceSettings& turbulence, double h,
                                                const std::array<double, 3>& wind_at_start);
fluid::TurbulenceBox inflow_turbulence_box(const io::TurbulenceSettings& turbulence, double h,
                                           const std::array<double, 3>& wind_at_start);

/// The FwGust of a gust event (travel resolved, direction along the ambient wind at its start).
FwGust to_device_gust(const io::GustEvent& event, const std::array<double, 3>& wind_at_start);

}  // namespace fw::host
