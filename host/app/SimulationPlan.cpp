#include "host/app/SimulationPlan.hpp"

#include <fmt/format.h>

#include <chrono>
#include <cmath>
#include <memory>
#include <stdexcept>

#include "fluid/CanopyField.hpp"
#include "fluid/SolidMap.hpp"
#include "trees/CanopyDrag.hpp"
#include "trees/QsmImport.hpp"
#include "trees/TreeFile.hpp"
#include "trees/TreeGenerator.hpp"

namespace fw::host {

namespace {

using Clock = std::chrono::steady_clock;

double seconds_since(Clock::time_point start) {
  return std::chrono::duration<double>(Clock::now() - start).count();
}

// The height of the ground under (x, y): the terrain's surface, else the domain floor.
double ground_z(const io::Scenario& scenario, double x, double y) {
  double z = scenario.domain.origin[2];
  if (scenario.terrain && scenario.terrain->map) z += scenario.terrain->map->height_at(x, y);
  return z;
}

std::size_t forest_device_bytes(const trees::Forest& forest) {
  std::size_t floats = 0;
  for (const auto& s : forest.species()) {
    const std::size_t n = std::size_t(s.skeleton().size()), m = std::size_t(s.modes().mode_count()),
                      samples = std::size_t(s.wind().sample_count());
    floats += 3 * n * m + 3 * samples * m + 3 * samples + 2 * m;
  }
  // Per instance-mode: q, qdot, force, owner; per node: displacement and owner; per sample: the wind.
  floats += 4 * std::size_t(forest.total_modes()) + 4 * std::size_t(forest.total_nodes()) +
            3 * std::size_t(forest.total_samples());
  return floats * 4 + std::size_t(forest.instance_count()) * sizeof(FwTreeInstance);
}

}  // namespace

trees::Skeleton species_skeleton(const io::Species& species) {
  using Kind = io::SkeletonSource::Kind;
  try {
    switch (species.skeleton.kind) {
      case Kind::generate:
        return trees::generate_tree(species.skeleton.generate);
      case Kind::file:
        return trees::read_tree_file(species.skeleton.path.string());
      case Kind::qsm:
        return trees::read_qsm_cylinders(species.skeleton.path.string());
    }
  } catch (const std::invalid_argument&) {
    throw;
  } catch (const std::runtime_error& e) {
    // The readers report "FILE:LINE: KEY: ..." as runtime errors; for a run they are input errors.
    throw std::invalid_argument(e.what());
  }
  throw std::logic_error("species_skeleton: unknown skeleton source");
}

fluid::TurbulenceBoxSpec inflow_turbulence_spec(const io::TurbulenceSettings& turbulence, double h,
                                                const std::array<double, 3>& wind_at_start) {
  fluid::TurbulenceBoxSpec spec;
  // Points every h/2: every face of an inflow plane (at whole cells along its normal, half cells across)
  // then sits on a box point, so that the plane carries the box's values without interpolation.
  for (int a = 0; a < 3; ++a) spec.cells[a] = kTurbulencePointsPerCell * turbulence.box_cells[a];
  spec.spacing = h / kTurbulencePointsPerCell;
  spec.spectrum = {1.0, turbulence.length_scale};  // unit sigma_u: the run scales it by sigma_u(t)
  spec.seed = turbulence.seed;
  // sigma = [along, across, vertical]: the box's x and y take the along- and across-wind values by the
  // horizontal axis closer to the wind at t = 0 (equal values, the intensity form, need no such choice).
  const auto sigma = turbulence.standard_deviations(1.0);
  const bool along_x = std::abs(wind_at_start[0]) >= std::abs(wind_at_start[1]);
  if (sigma[0] > 0.0) {
    spec.component_scale = {(along_x ? sigma[0] : sigma[1]) / sigma[0],
                            (along_x ? sigma[1] : sigma[0]) / sigma[0], sigma[2] / sigma[0]};
  }
  return spec;
}

fluid::TurbulenceBox inflow_turbulence_box(const io::TurbulenceSettings& turbulence, double h,
                                           const std::array<double, 3>& wind_at_start) {
  return fluid::TurbulenceBox(inflow_turbulence_spec(turbulence, h, wind_at_start));
}

FwGust to_device_gust(const io::GustEvent& event, const std::array<double, 3>& wind_at_start) {
  FwGust gust{};
  gust.start = float(event.start);
  gust.duration = float(event.duration);
  gust.peak_speed = float(event.peak_speed);
  gust.radius = float(event.radius);
  const double speed = std::hypot(wind_at_start[0], wind_at_start[1], wind_at_start[2]);
  for (int a = 0; a < 3; ++a) {
    gust.center[a] = float(event.center[a]);
    gust.travel[a] = float(event.travel[a]);
    // Along the ambient wind; with no wind at the start, along +x (east), so the gust is still well defined.
    gust.direction[a] = float(speed > 0.0 ? wind_at_start[a] / speed : (a == 0 ? 1.0 : 0.0));
  }
  return gust;
}

SimulationPlan plan_simulation(const io::Scenario& scenario, const trees::BasisCache* cache,
                               std::ostream* log) {
  SimulationPlan plan;
  plan.scenario = {scenario.name, scenario.file.filename().string(), scenario.text, scenario.seed};
  plan.end_time = scenario.time.end;
  plan.ambient_wind = [source = scenario.wind](double t) { return io::wind_vector(source, t); };
  plan.output = scenario.output;
  plan.probe_interval = scenario.resolved_probe_interval().value_or(0.0);

  // --- the wind grid ---------------------------------------------------------------------------------------
  WindGridSetup& wind = plan.wind;
  wind.spec = scenario.grid_spec(0.0);
  wind.settings = scenario.wind_settings();
  wind.profile = scenario.wind.profile;
  wind.ambient = scenario.wind_vector(0.0);
  fluid::SolidMap solids(wind.spec);
  for (const auto& obstacle : scenario.obstacles) {
    std::visit([&](const auto& shape) { solids.add(shape); }, obstacle);
  }
  if (scenario.terrain && scenario.terrain->map) solids.add_terrain(*scenario.terrain->map);
  wind.solid = solids.cells();
  for (const auto& event : scenario.events) {
    wind.gusts.push_back(to_device_gust(event, scenario.wind_vector(event.start)));
  }
  if (scenario.wind.forcing) wind.forcing.relaxation_time = scenario.wind.forcing->relaxation_time;
  if (scenario.wind.turbulence) {
    wind.turbulence = std::make_shared<const fluid::TurbulenceBox>(
        inflow_turbulence_box(*scenario.wind.turbulence, wind.spec.h, wind.ambient));
    plan.turbulence_sigma = [turbulence = *scenario.wind.turbulence, source = scenario.wind](double t) {
      const auto v = io::wind_vector(source, t);
      return turbulence.standard_deviations(std::hypot(v[0], v[1], v[2]))[0];
    };
  }

  // --- species ---------------------------------------------------------------------------------------------
  std::vector<trees::SpeciesBasis> bases;
  for (std::size_t index = 0; index < scenario.forest.species.size(); ++index) {
    const io::Species& species = scenario.forest.species[index];
    const auto start = Clock::now();
    trees::SpeciesSettings settings;
    settings.material = species.material;
    settings.modal.mode_count = species.modes.count;
    settings.modal.damping = trees::Damping::modal_ratio(species.modes.damping_ratio);
    settings.wind.samples = species.modes.wind_samples;
    // One drag convention on both sides of the coupling (trees/CanopyDrag.hpp): 1/2 rho C_D A |u| u.
    settings.wind.branch_drag_coefficient = species.drag_coefficient;
    settings.wind.leaf_area_index = species.canopy.leaf_area_index;
    settings.wind.leaf_drag_coefficient = species.canopy.drag_coefficient;
    trees::Skeleton skeleton = species_skeleton(species);
    io::check_species_skeleton(scenario, int(index), skeleton.size());
    io::SpeciesSummary summary;
    summary.name = species.name;
    if (cache) {
      trees::CacheOutcome outcome{};
      std::string store_error;
      bases.push_back(cache->load_or_compute(skeleton, settings, &outcome, &store_error));
      summary.cache = trees::to_string(outcome);
      if (!store_error.empty() && log) *log << "warning: " << store_error << "\n";
    } else {
      bases.push_back(trees::SpeciesBasis::compute(skeleton, settings));
    }
    summary.seconds = seconds_since(start);
    summary.nodes = bases.back().skeleton().size();
    summary.modes = bases.back().modes().mode_count();
    summary.samples = bases.back().wind().sample_count();
    summary.first_hz = bases.back().modes().frequencies_hz()(0);
    // The leaves on the basis' own skeleton and foliage, so that their elements are the forest's.
    const trees::Skeleton& basis_skeleton = bases.back().skeleton();
    plan.leaves.push_back(species.leaves.has_leaves()
                              ? trees::SpeciesLeaves::generate(
                                    basis_skeleton,
                                    trees::Foliage::of(basis_skeleton, species.canopy.leaf_area_index),
                                    species.leaves)
                              : trees::SpeciesLeaves());
    const int leaves = plan.leaves.back().count();
    if (log) {
      *log << fmt::format("species {}: {} nodes, {} modes from {:.3f} Hz, {} wind samples{} ({}, {:.2f} s)\n",
                          summary.name, summary.nodes, summary.modes, summary.first_hz, summary.samples,
                          species.leaves.has_leaves() ? fmt::format(", {} leaves", leaves) : "",
                          summary.cache, summary.seconds);
    }
    plan.species.push_back(summary);
  }

  // --- instances: stands first, in file order, then the single trees ---------------------------------------
  std::vector<trees::TreeInstance> instances;
  for (const io::Stand& stand : scenario.forest.stands) {
    for (const trees::PlacedTree& placed : trees::place_stand(stand.layout)) {
      trees::TreeInstance tree;
      tree.species = placed.species;
      tree.position = {placed.position.x(), placed.position.y(),
                       ground_z(scenario, placed.position.x(), placed.position.y())};
      tree.yaw_rad = placed.yaw_rad;
      tree.scale = placed.scale;
      instances.push_back(tree);
    }
  }
  for (const io::PlacedTreeSettings& placed : scenario.forest.trees) {
    trees::TreeInstance tree;
    tree.species = placed.species_index;
    tree.position = {placed.position[0], placed.position[1],
                     placed.height_given ? placed.position[2]
                                         : ground_z(scenario, placed.position[0], placed.position[1])};
    tree.yaw_rad = placed.yaw_rad;
    tree.scale = placed.scale;
    instances.push_back(tree);
  }
  for (const auto& tree : instances) ++plan.species[std::size_t(tree.species)].trees;
  for (const auto& tree : instances) plan.leaf_count += plan.leaves[std::size_t(tree.species)].count();
  std::size_t species_leaf_count = 0;
  for (const auto& leaves : plan.leaves) species_leaf_count += std::size_t(leaves.count());

  plan.forest = trees::Forest(std::move(bases), std::move(instances));
  plan.coupling.integrator = scenario.forest.integrator;
  plan.coupling.leaves = plan.leaves;
  plan.coupling.strong_wind_correction = scenario.forest.strong_wind_correction;
  if (scenario.wind.turbulence && scenario.wind.turbulence->unresolved) {
    const io::TurbulenceSettings& turbulence = *scenario.wind.turbulence;
    trees::UnresolvedTurbulenceSettings& unresolved = plan.coupling.unresolved;
    unresolved.enabled = true;
    unresolved.cutoff_cells = turbulence.cutoff_cells;
    unresolved.cell_size = wind.spec.h;
    unresolved.integral_length = turbulence.length_scale;
    unresolved.seed = turbulence.seed;
    // sigma_u / U: the intensity as given, or sigma_u over the wind speed of the moment.
    plan.unresolved_intensity = [turbulence, source = scenario.wind](double t) {
      if (turbulence.intensity) return *turbulence.intensity;
      const auto v = io::wind_vector(source, t);
      const double speed = std::hypot(v[0], v[1], v[2]);
      return speed > 0.0 ? turbulence.standard_deviations(speed)[0] / speed : 0.0;
    };
    unresolved.intensity = plan.unresolved_intensity(0.0);
  }

  // --- canopy: every tree's frontal area on the grid, with the drag the trees receive ---------------------
  if (plan.forest.instance_count() > 0) {
    fluid::CanopyField canopy(wind.spec);
    for (int k = 0; k < plan.forest.instance_count(); ++k) trees::add_to_canopy(canopy, plan.forest, k);
    plan.canopy_density = canopy.frontal_area_density();
    plan.canopy_dropped_area = canopy.dropped_frontal_area();
    if (scenario.forest.two_way_coupling) plan.coupling.drag_density = canopy.drag_density();
  }

  plan.estimated_device_bytes =
      WindGrid::estimate_device_bytes(wind.spec, wind.settings, 1) + forest_device_bytes(plan.forest) +
      (plan.coupling.drag_density.size() * sizeof(float)) +
      (wind.turbulence ? wind.turbulence->values().size() * sizeof(float) : 0) +
      std::size_t(plan.leaf_count) * kDeviceBytesPerLeaf + species_leaf_count * kDeviceBytesPerSpeciesLeaf;
  return plan;
}

}  // namespace fw::host
