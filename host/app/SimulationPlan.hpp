// Everything a run needs, resolved on the host from a validated scenario before any device is touched: the
// wind grid's setup (grid, solids, profile, gusts, inflow turbulence), what changes over time, every
// species' modal and wind basis (through the disk cache) and its leaves, the placed tree instances, the
// coupling of trees and wind, the outputs, and the device memory each part will take. Nothing past the plan
// reads the scenario; `check`, `run`, `bench coupled` and the validation tests all build it here.
//
//   fw::io::Scenario scenario = fw::io::load_scenario("scenarios/gust.yaml");
//   fw::trees::BasisCache cache(fw::trees::BasisCache::default_directory());
//   fw::host::SimulationPlan plan = fw::host::plan_simulation(scenario, &cache, &std::cerr);
//   plan.forest.instance_count();   plan.wind.spec.cell_count();   plan.inputs.ambient_wind(30.0);
//   plan.coupling.leaves[0].count();  plan.leaf_count;     // species 0's leaves, all trees' leaves
//   plan.memory.total();                                  // bytes of device memory, by part in parts()
//   fw::host::CoupledStep coupled(cc, plan);               // the plan must outlive the step
//
// The plan is made by one small builder per part (host/app/plan/PlanBuilders.hpp): wind, turbulence,
// species and leaves, forest, coupling, outputs; each builder's file states its conventions where
// docs/design.md leaves a choice. Every check a builder can make without a device it makes,
// with the stages' own validation, so that a scenario `check` accepts does not fail `run` on anything
// `check` could have known. Errors: std::invalid_argument for input errors (exit code 2, "FILE:LINE: KEY:
// ..." where the error is in a file), trees::ModalError or std::runtime_error otherwise.
#pragma once

#include <Eigen/Core>

#include <cstddef>
#include <cstdint>
#include <optional>
#include <ostream>
#include <string>
#include <vector>

#include "fluid/Decomposition.hpp"
#include "fluid/TurbulenceBox.hpp"
#include "host/app/CouplingSettings.hpp"
#include "host/app/DeviceMemory.hpp"
#include "host/app/TimeInputs.hpp"
#include "host/stages/WindGrid.hpp"
#include "io/gis/TreeInventory.hpp"
#include "io/settings/OutputSettings.hpp"
#include "io/settings/SiteSettings.hpp"
#include "io/writers/ManifestWriter.hpp"
#include "trees/BasisCache.hpp"
#include "trees/Forest.hpp"
#include "trees/StandDensity.hpp"
#include "trees/TreeDamage.hpp"

namespace fw::io {
struct Scenario;  // io/Scenario.hpp
}  // namespace fw::io

namespace fw::host {

/// Where a run came from, for run.json and the scenario copy in the output folder.
struct ScenarioRecord {
  std::string name;
  std::string file_name;  ///< the scenario file's name, without its folder
  std::string text;       ///< the file's bytes
  std::uint64_t seed = 0;
  /// Where the run stands on the Earth (a terrain.raster's CRS and domain.origin in it); none without.
  std::optional<io::SiteSettings> site;
};

/// One stand of the scenario (forest.stands[k]) as planned: which trees are its own and how dense they stand.
struct StandPlan {
  std::string species;     ///< the scenario's species name
  int species_index = 0;   ///< into the scenario's forest.species
  int forest_species = 0;  ///< into forest.species(): the species' basis, or the stand's own (below)
  int first_instance = 0;  ///< its trees are the instances [first_instance, first_instance + density.trees)
  Eigen::Vector2d min = Eigen::Vector2d::Zero(), max = Eigen::Vector2d::Zero();  ///< its region, m
  /// forest.stands[k].leaf_area_index, when the file gives it: the stand's trees are then a basis of their
  /// own whose crowns carry crown_leaf_area_index, so that the stand's LAI is the figure given.
  std::optional<double> leaf_area_index;
  double crown_leaf_area_index = 0.0;  ///< one-sided leaf area per crown hull area of its trees (Foliage)
  trees::StandDensity density;         ///< LAI and FAI (trees/StandDensity.hpp), from plan_coupling
};

/// What a plan is for. A run's plan holds everything the run needs; `check`'s holds what `check` reports and
/// validates, and estimates from formulas what only the run builds: the inflow turbulence box is sized,
/// validated and priced from its spec, not synthesised (a 1024 x 512 x 512-point box took 67 s and 3.2 GB),
/// each species' leaves are counted, not generated (trees::SpeciesLeaves::counted), and the canopy is
/// rasterised on the cells the trees reach, not the whole grid (canopy_density). Everything else is
/// the same, so that a scenario `check` accepts does not fail `run` on anything `check` could have known.
enum class PlanFor { run, check };

/// A forest species' strength (forest.species[].strength) and what it means for its trees at scale 1
/// (host/app/plan/DamagePlan.cpp; docs/damage.md): what `check` prints and run.json records.
struct SpeciesStrength {
  trees::TreeStrength strength;
  std::string source;  ///< "sitka_spruce (soil A, mean rooting)", "given", ...
  trees::CriticalMoments critical;
  trees::StaticCriticalWind static_wind;  ///< the model's own, in a uniform wind
  double static_break_height = -1.0;  ///< m above the root: where the uniform wind breaks it (-1: overturns)
  double height = 0.0;                ///< m
  double dbh = 0.0;                   ///< m, 1.3 m above the root
  double hale_wind = 0.0;  ///< m/s: the mean canopy-top wind whose peak base moment is the base's critical
};

/// The forest inventory as planned (forest.inventory; docs/gis.md): its trees fitted to their sizes.
struct InventoryPlan {
  std::string file;
  int placed = 0;                          ///< inside the domain: the last `placed` instances
  std::vector<io::InventoryTree> outside;  ///< outside the domain, as the file gives them: not placed
  double largest_dbh_error = 0.0;          ///< max |fitted dbh / measured - 1| over its trees
};

struct SimulationPlan {
  ScenarioRecord scenario;
  PlanFor purpose = PlanFor::run;
  double end_time = 0.0;  ///< s: the run covers [0, end_time]
  double spin_up = 0.0;   ///< s: the wind spins up from -spin_up to 0 first (CoupledStep::start); 0: none
  WindGridSetup wind;     ///< ambient set for t = 0; wind.turbulence built for PlanFor::run only
  /// The inflow turbulence box's spec, with or without the box itself (wind.turbulence); none without
  /// wind.turbulence.
  std::optional<fluid::TurbulenceBoxSpec> turbulence_box;
  double peak_wind = 0.0;       ///< m/s: peak_wind_speed of the plan's inputs, what its steps are planned at
  std::size_t solid_cells = 0;  ///< cells wind.solid marks solid, counted once (a grid may have 2^31)
  /// The wind grid's x-y blocks over the run's ranks (one block in one process): domain.decomposition, else
  /// chosen; its halo from the scheme and the largest Courant number the run will take.
  fluid::Decomposition decomposition;
  TimeInputs inputs;  ///< the ambient wind, the inflow turbulence's sigma_u, the unresolved intensity
  trees::Forest forest;
  CouplingSettings coupling;
  /// Per forest species (forest.species()): its basis, its trees, the cache; the scenario's species first,
  /// in file order, then one for each stand that gives its own leaf area index.
  std::vector<io::SpeciesSummary> species;
  /// Per forest species, like `species`: its strength, nullopt when the scenario gives none.
  std::vector<std::optional<SpeciesStrength>> strengths;
  std::vector<StandPlan> stands;  ///< per forest.stands[] entry, in file order
  std::optional<InventoryPlan> inventory;
  /// Per instance, its id in the inventory; empty without an inventory, "" for a tree not from it.
  std::vector<std::string> tree_ids;
  long leaf_count = 0;  ///< leaves of all instances: the sum over trees of their species' count
  /// per cell, frontal area density a (1/m); empty without trees, and in a plan for check (which
  /// rasterises the trees on the cells they reach only, host/app/plan/CouplingPlan.cpp)
  std::vector<float> canopy_density;
  std::size_t canopy_cells = 0;  ///< cells with a > 0 (in float), whatever the plan is for
  /// The trees' drag slows the wind (forest.two_way_coupling, with trees): coupling.drag_density holds it in
  /// a plan for a run.
  bool two_way_coupling = false;
  double canopy_dropped_area = 0.0;  ///< m^2 of frontal area outside the domain
  io::OutputSettings output;         ///< folder, frame interval, which writers and fields, probes
  double probe_interval = 0.0;       ///< s between probe samples; 0: every step
  DeviceMemory memory;               ///< what each stage will allocate, by part
  /// What the plan accepts but the user should hear of (a stand denser than forests are), one line each,
  /// "FILE:LINE: KEY: ...", without a "warning: " prefix: `check` prints them on stderr, `run` in its log.
  std::vector<std::string> warnings;
};

/// Builds the plan for a run over `ranks` MPI ranks, or for `check` (PlanFor). `cache` may be null (no disk
/// cache); `log` (may be null) gets one line per species.
SimulationPlan plan_simulation(const io::Scenario& scenario, const trees::BasisCache* cache,
                               std::ostream* log, int ranks = 1, PlanFor purpose = PlanFor::run);

/// What `forestwind check` prints: the grid and its boundaries, the turbulence, each species and its trees,
/// the forest, each stand's leaf and frontal area index, the device memory by part, the time steps and the
/// outputs, all read from the plan (the plan's warnings are the caller's to print).
void print_plan(const SimulationPlan& plan, std::ostream& out);

/// The largest wind speed the plan's inputs give, m/s: the ambient wind's largest speed over the run
/// (sampled every second, or at kPeakWindSamples times evenly over a longer run, and at the end) times the
/// inflow profile's largest factor over the cell centres, plus the strongest gust's peak. What an automatic
/// time step will be limited by; a turbulent flow's largest face speed exceeds it. plan_simulation keeps it
/// in plan.peak_wind.
double peak_wind_speed(const SimulationPlan& plan);
/// The most times peak_wind_speed samples the ambient wind: every second of a run up to 27.8 hours long, in
/// a fraction of a second of `check` (a muparser expression evaluates in well under a microsecond).
inline constexpr double kPeakWindSamples = 1e5;

/// The time step `check` plans with, s: time.dt when fixed; with dt auto the CFL step at plan.peak_wind
/// along one axis (the largest component and the sum of the components agree), the shortest step the
/// ambient wind and gusts allow. ceil(end / dt) is then about the run's steps, or fewer when turbulence
/// speeds the flow past the peak.
double planned_dt(const SimulationPlan& plan);

/// The spin-up's steps `check` plans with: ceil(spin_up / planned_dt), 0 without a spin-up; as many or
/// fewer with dt auto, whose spin-up steps at the t = 0 wind.
long planned_spin_up_steps(const SimulationPlan& plan);

}  // namespace fw::host
