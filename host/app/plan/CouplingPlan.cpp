// The coupling's part of the plan: every tree's frontal area on the grid (the canopy density the wind
// frames show) and, with two-way coupling, the drag density the wind feels; each stand's leaf and frontal
// area index from the same rasterisation (trees/StandDensity.hpp), with a warning for a stand whose leaf
// area index no forest has; the modal integrator; the strong-wind correction of output frames; and the
// memory of the canopy drag and of Stam's forcing.
#include <fmt/format.h>

#include <algorithm>
#include <cmath>
#include <stdexcept>

#include "fluid/CanopyField.hpp"
#include "host/app/plan/PlanBuilders.hpp"
#include "host/stages/ForestStages.hpp"
#include "io/Scenario.hpp"
#include "io/ScenarioSchema.hpp"
#include "trees/CanopyDrag.hpp"

namespace fw::host {

namespace {

// "FILE:LINE: forest.stands[k]: ...": the stand's leaf area index lies outside forests', with the keys that
// set it.
std::string stand_warning(const io::Scenario& scenario, std::size_t k, const StandPlan& stand) {
  using trees::StandDensity;
  namespace schema = io::schema;
  const io::Stand& given = scenario.forest.stands[k];
  const double lai = stand.density.leaf_area_index();
  const bool dense = lai > StandDensity::kForestLeafAreaIndexHigh;
  std::string keys;
  if (stand.leaf_area_index) {
    keys = fmt::format(
        "{} {} sets it: {} it",
        schema::item_path(schema::key(schema::kForestKeys, "forest.stands[].leaf_area_index").path, k),
        *stand.leaf_area_index, dense ? "lower" : "raise");
  } else {
    const std::string spacing =
        schema::item_path(schema::key(schema::kForestKeys, "forest.stands[].spacing").path, k);
    const std::string crown =
        schema::item_path(schema::key(schema::kSpeciesKeys, "forest.species[].canopy.leaf_area_index").path,
                          std::size_t(stand.species_index));
    keys = fmt::format(
        "{} {} m and {} {} (per crown) set it: {} the spacing or {} the crowns' leaf area index, or give the "
        "stand's own {}",
        spacing, given.layout.spacing, crown, stand.crown_leaf_area_index, dense ? "widen" : "narrow",
        dense ? "lower" : "raise",
        schema::item_path(schema::key(schema::kForestKeys, "forest.stands[].leaf_area_index").path, k));
  }
  return fmt::format(
      "{}:{}: {}: the {} stand's leaf area index is {:.3g} m^2 of leaf per m^2 of ground, {} the {} to {} of "
      "forests; {}",
      scenario.file.string(), given.line, schema::item_path("forest.stands[]", k), stand.species, lai,
      dense ? "above" : "below", StandDensity::kForestLeafAreaIndexLow,
      StandDensity::kForestLeafAreaIndexHigh, keys);
}

// The cells the canopy is rasterised on: the whole grid for a run, whose wind feels it cell by cell. For
// check, the box of cells the trees' skeletons reach, one cell of margin on each side against rounding, and
// every stand's region (whose columns check counts): check's memory then follows the forest, not the grid
// (a 196-million-cell grid with three trees took 4.9 GB and 5 s), and every figure it reports is the whole
// grid's (fluid::CanopyField).
fluid::CellBox canopy_box(const SimulationPlan& plan) {
  const fluid::GridSpec& grid = plan.wind.spec;
  if (plan.purpose == PlanFor::run) return fluid::CellBox::whole(grid);
  Eigen::AlignedBox3d reach;  // m, world
  for (int k = 0; k < plan.forest.instance_count(); ++k) reach.extend(trees::instance_reach(plan.forest, k));
  for (const StandPlan& stand : plan.stands) {
    reach.extend(Eigen::Vector3d(stand.min.x(), stand.min.y(), grid.origin[2]));
    reach.extend(Eigen::Vector3d(stand.max.x(), stand.max.y(), grid.origin[2]));
  }
  return trees::cells_around(grid, reach);
}

}  // namespace

void plan_coupling(const io::Scenario& scenario, SimulationPlan& plan) {
  CouplingSettings& coupling = plan.coupling;
  coupling.integrator = scenario.forest.integrator;
  coupling.strong_wind_correction = scenario.forest.strong_wind_correction;
  coupling.drag_law = scenario.forest.drag_law;
  if (plan.forest.instance_count() == 0) return;
  // A fixed dt past the semi-implicit integrator's limit would stop the run at its first step.
  const fluid::WindSettings& settings = plan.wind.settings;
  if (coupling.integrator == trees::ModalIntegrator::semi_implicit && !(settings.cfl > 0.0)) {
    const double limit = plan.forest.semi_implicit_dt_limit();
    if (settings.dt >= limit)
      throw std::invalid_argument(
          fmt::format("{}: forest.integrator: semi-implicit Euler is unstable at time.dt = {} s for the "
                      "fastest tree mode "
                      "(stable below {:.4g} s); lower time.dt or use forest.integrator: exact",
                      scenario.file.string(), settings.dt, limit));
  }
  fluid::CanopyField canopy(plan.wind.spec, canopy_box(plan));
  std::vector<double> leaf_area(std::size_t(plan.forest.instance_count()));  // m^2, one-sided, per tree
  const trees::ForestCanopy trees_canopy(plan.forest);
  for (int k = 0; k < plan.forest.instance_count(); ++k)
    leaf_area[std::size_t(k)] = trees_canopy.add(canopy, k).leaf_area;
  plan.canopy_cells = canopy.occupied_cells();
  if (plan.purpose == PlanFor::run) plan.canopy_density = canopy.frontal_area_density();
  plan.canopy_dropped_area = canopy.dropped_frontal_area();
  for (std::size_t k = 0; k < plan.stands.size(); ++k) {
    StandPlan& stand = plan.stands[k];
    trees::StandDensity& density = stand.density;
    density.leaf_area = 0.0;
    for (int tree = stand.first_instance; tree < stand.first_instance + density.trees; ++tree)
      density.leaf_area += leaf_area[std::size_t(tree)];
    const fluid::CanopyColumns columns =
        canopy.columns_in({stand.min.x(), stand.min.y()}, {stand.max.x(), stand.max.y()});
    density.columns = columns.columns;
    density.column_ground_area = columns.ground_area;
    density.column_frontal_area = columns.frontal_area;
    if (!density.forest_like()) plan.warnings.push_back(stand_warning(scenario, k, stand));
  }
  if (scenario.forest.two_way_coupling) {
    plan.two_way_coupling = true;
    if (plan.purpose == PlanFor::run) coupling.drag_density = canopy.drag_density();
    plan.memory.add("canopy drag", CanopySink::estimate_device_bytes(plan.wind.spec));
  }
  if (coupling.unresolved.enabled)
    plan.memory.add("unresolved turbulence",
                    ForestStages::estimate_unresolved_bytes(coupling.unresolved, plan.forest));
}

}  // namespace fw::host
