#include "host/bench/CoupledBench.hpp"

#include <fmt/format.h>

#include <unistd.h>

#include <cmath>
#include <filesystem>
#include <numbers>
#include <random>
#include <stdexcept>
#include <system_error>

#include "base/WallClock.hpp"
#include "host/app/CoupledStep.hpp"
#include "host/app/SimulationPlan.hpp"
#include "host/bench/BenchTurbulence.hpp"
#include "host/bench/FmaPeak.hpp"
#include "host/bench/StreamTriad.hpp"
#include "host/stages/DamageStages.hpp"
#include "host/stages/PlaneStatistics.hpp"
#include "io/JsonWriter.hpp"
#include "io/Scenario.hpp"
#include "trees/Foliage.hpp"
#include "trees/ForestReference.hpp"
#include "trees/LSystem.hpp"
#include "trees/TreeGenerator.hpp"
#include "trees/TreeStrength.hpp"

namespace fw::bench {

namespace {

using Clock = base::WallClock;
using base::ms_since;

// The bench forest's foliage: a leaf area index of 3, a broadleaf stand in leaf (the branches' and the
// leaves' drag coefficients are the species defaults).
constexpr double kLeafAreaIndex = 3.0;
constexpr double kBenchWindSpeed = 10.0;  // m/s
constexpr double kBenchDt = 0.1;          // s, fixed
constexpr const char* kSpecies = "broadleaf";

// A basis cache in a folder of its own, removed afterwards: the first plan computes the species (timed as a
// miss), the later ones load it, and no user's cache is read or written.
struct ScratchCache {
  std::filesystem::path folder = std::filesystem::temp_directory_path() /
                                 fmt::format("forestwind-bench-coupled-{}", static_cast<long>(::getpid()));
  trees::BasisCache cache{folder};
  ScratchCache() = default;
  ScratchCache(const ScratchCache&) = delete;
  ScratchCache& operator=(const ScratchCache&) = delete;
  ~ScratchCache() {
    std::error_code ignored;
    std::filesystem::remove_all(folder, ignored);
  }
};

// One case of the bench: the converged laminar case, or it with turbulence, or with leaves, or with
// Oliapuram's fixed Jacobi sweeps (jacobi > 0) instead of CG to 1e-3.
struct Variant {
  int jacobi = 0;
  bool turbulent = false;
  bool leaves = false;
};

// `count` trees on a jittered lattice over the middle 80% of the ground, random yaw and scale 0.85-1.15.
std::vector<io::PlacedTreeSettings> forest_trees(int count, const std::array<int, 3>& grid, double h) {
  const double width = grid[0] * h, depth = grid[1] * h;
  const int columns = int(std::ceil(std::sqrt(count * width / depth)));
  const int rows = (count + columns - 1) / columns;
  std::mt19937_64 random(7);
  std::vector<io::PlacedTreeSettings> trees;
  for (int k = 0; k < count; ++k) {
    const double fx = (k % columns + 0.5 + 0.3 * (trees::unit_interval(random()) - 0.5)) / columns;
    const double fy = (k / columns + 0.5 + 0.3 * (trees::unit_interval(random()) - 0.5)) / rows;
    io::PlacedTreeSettings tree;
    tree.species = kSpecies;
    tree.species_index = 0;
    tree.position = {width * (0.1 + 0.8 * fx), depth * (0.1 + 0.8 * fy), 0.0};
    tree.height_given = true;
    tree.yaw_rad = 2.0 * std::numbers::pi * trees::unit_interval(random());
    tree.scale = 0.85 + 0.3 * trees::unit_interval(random());
    trees.push_back(tree);
  }
  return trees;
}

// The bench's case as a scenario, so that it runs through the planner exactly as a user's run does: a 10 m/s
// uniform wind from the west (inflow west, outflow east, slip sides and top, no-slip ground), a fixed dt of
// 0.1 s, semi-Lagrangian advection, two-way coupling; `species` the one species (its skeleton and leaves).
io::Scenario bench_scenario(const CoupledBenchOptions& options, const std::array<int, 3>& grid,
                            const Variant& variant, const io::Species& species) {
  io::Scenario scenario;
  scenario.file = "bench-coupled";
  scenario.name = "bench-coupled";
  scenario.seed = 1;
  scenario.time.end = 1.0;
  scenario.time.dt = kBenchDt;
  const double h = options.cell_size;
  for (int a = 0; a < 3; ++a) {
    scenario.domain.origin[std::size_t(a)] = 0.0;
    scenario.domain.cells[std::size_t(a)] = grid[std::size_t(a)];
    scenario.domain.size[std::size_t(a)] = grid[std::size_t(a)] * h;
  }
  scenario.domain.cell_size = h;
  using io::BoundaryChoice;
  scenario.boundaries = {BoundaryChoice::inflow, BoundaryChoice::outflow, BoundaryChoice::slip,
                         BoundaryChoice::slip,   BoundaryChoice::no_slip, BoundaryChoice::slip};
  scenario.wind.speed = io::Expression::constant(kBenchWindSpeed);
  scenario.wind.direction = io::Expression::constant(270.0);  // from the west, toward +x
  scenario.wind.profile = fluid::InflowProfile{};             // uniform
  scenario.wind.reference_height = scenario.wind.profile.reference_height;
  if (variant.turbulent) {
    // The inflow box, and Stam's forcing of every tree by the eddies below 2 cells.
    io::TurbulenceSettings turbulence;
    turbulence.intensity = kBenchTurbulenceIntensity;
    turbulence.length_scale = kBenchTurbulenceLengthCells * h;
    for (int a = 0; a < 3; ++a) {
      turbulence.box_cells[std::size_t(a)] = grid[std::size_t(a)];  // as long as the domain on each axis
      turbulence.box_size[std::size_t(a)] = grid[std::size_t(a)] * h;
    }
    turbulence.seed = 1;
    turbulence.unresolved = true;
    scenario.wind.turbulence = turbulence;
  }
  scenario.solver.advection = fluid::AdvectionScheme::semi_lagrangian;
  if (variant.jacobi > 0) {
    scenario.solver.pressure = fluid::PressureSolverType::jacobi;
    scenario.solver.jacobi_iterations = variant.jacobi;
  } else {
    scenario.solver.pressure = fluid::PressureSolverType::cg;
    scenario.solver.tolerance = 1e-3;
    scenario.solver.max_iterations = 200;
  }
  scenario.solver.vorticity_confinement = 0.0;
  scenario.solver.smagorinsky_constant = 0.0;
  scenario.forest.two_way_coupling = true;
  scenario.forest.integrator = trees::ModalIntegrator::exact;
  scenario.forest.species = {species};
  if (!variant.leaves) scenario.forest.species[0].leaves.model = trees::FlutterModel::none;
  // Every tree's loads and failure check, timed as the "damage" stage; without consequences, so that a
  // failure changes nothing else in the step (a failed tree's loads go on being computed).
  scenario.forest.damage.enabled = true;
  scenario.forest.damage.consequences = false;
  scenario.forest.species[0].strength = trees::strength_preset(trees::StrengthPreset::birch);
  scenario.forest.species[0].strength_source = "birch";
  scenario.forest.trees = forest_trees(options.trees, grid, h);
  return scenario;
}

// The bench's one species (kSpecies) and the foliage's leaves of one of its trees at scale 1.
struct BenchSpecies {
  io::Species species;
  double real_leaves_per_tree = 0.0;
};

// A broadleaf generated at about nodes_per_tree nodes, with the options' modes and wind samples, in full leaf
// (LAI kLeafAreaIndex, leaves of the default size) simulated as a sample of leaves_per_tree of them
// (LeafSettings::fraction).
BenchSpecies bench_species(const CoupledBenchOptions& options) {
  trees::GeneratorSettings generator;
  generator.preset = "broadleaf";
  generator.height = 15.0;
  generator.seed = 1;
  const trees::Skeleton skeleton =
      trees::generate_tree_with_nodes(generator, options.nodes_per_tree, &generator.max_element_length);
  BenchSpecies bench;
  io::Species& species = bench.species;
  species.name = kSpecies;
  species.skeleton.kind = io::SkeletonSource::Kind::generate;
  species.skeleton.generate = generator;
  species.modes.count = options.modes;
  species.modes.wind_samples = options.samples;
  species.canopy.leaf_area_index = kLeafAreaIndex;
  const trees::Foliage foliage = trees::Foliage::of(skeleton, kLeafAreaIndex);
  species.leaves = trees::LeafSettings{};
  bench.real_leaves_per_tree = foliage.leaf_area / species.leaves.area;
  species.leaves.fraction =
      std::min(1.0, options.leaves_per_tree / std::max(bench.real_leaves_per_tree, 1.0));
  return bench;
}

// Starts `coupled`, steps it through the warm-up, then times options.steps steps into c, every rank of
// `world` starting its clock at the same moment: ms per step, the stages, the pressure iterations and this
// rank's halo traffic.
void time_steps(host::ComputeContext& cc, host::CoupledStep& coupled, const CoupledBenchOptions& options,
                const host::Communicator& world, CoupledBenchCase& c) {
  coupled.start();
  for (int s = 0; s < options.warmup_steps; ++s) coupled.step();
  cc.finish();

  coupled.set_stage_timing(true);
  coupled.reset_stage_ms();
  const host::HaloTraffic halo_before = coupled.wind().halo_traffic();
  world.barrier();
  const auto start = Clock::now();
  for (int s = 0; s < options.steps; ++s) c.pressure_iterations += coupled.step().wind.pressure.iterations;
  c.ms_per_step = ms_since(start) / options.steps;
  c.halo = coupled.wind().halo_traffic() - halo_before;
  c.pressure_iterations /= options.steps;
  for (const auto& [stage, ms] : coupled.stage_ms()) {
    c.stages_ms[stage] = ms / options.steps;
    if (stage != "trees" && stage != "leaves" && stage != "damage") c.fluid_ms += ms / options.steps;
  }
  c.trees_ms = c.stages_ms["trees"];
  c.damage_ms = c.stages_ms["damage"];
}

// Times options.steps samples of the whole domain's profiles on the coupled step as it stands, after one
// untimed sample (the kernel's build and first launch, and the scales a run keeps from sample to sample).
void time_statistics(host::ComputeContext& cc, host::CoupledStep& coupled, const CoupledBenchOptions& options,
                     CoupledBenchCase& c) {
  host::WindGrid& wind = coupled.wind();
  host::PlaneStatistics statistics(cc, wind.spec(), wind.local_spec(), wind.block(),
                                   host::Communicator::alone());
  const host::WindStatisticsFields fields = wind.statistics_fields();
  const double speed = wind.max_speed_component();
  host::PlaneScales scales;  // kept from sample to sample, as a run keeps them
  statistics.sample(fields, speed, {}, &scales);
  const auto start = Clock::now();
  for (int s = 0; s < options.steps; ++s) statistics.sample(fields, speed, {}, &scales);
  c.statistics_ms = ms_since(start) / options.steps;
  c.statistics_gb_s =
      double(host::PlaneStatistics::bytes_read(wind.local_spec(), fields)) / (c.statistics_ms * 1e6);
}

}  // namespace

CoupledBenchResult run_coupled_bench(host::ComputeContext& cc, const CoupledBenchOptions& options) {
  CoupledBenchResult result;
  result.device = cc.device().device_name;
  result.trees = options.trees;
  result.modes = options.modes;
  result.samples = options.samples;

  // One species; its basis is computed once, by the first plan, and loaded from a cache of the bench's own
  // by the others (the point of the similarity laws: one basis for every instance).
  const BenchSpecies bench = bench_species(options);
  const io::Species& species = bench.species;
  result.real_leaves_per_tree = bench.real_leaves_per_tree;
  const ScratchCache cache;
  double damage_fmas = 0.0;  // one damage check of the first case's forest

  for (const auto& grid : options.grids) {
    // The converged case, then (when asked) the same with turbulence and with leaves, then the Jacobi
    // baseline.
    std::vector<Variant> variants{{0, false, false}};
    if (options.turbulence) variants.push_back({0, true, false});
    if (options.leaves_per_tree > 0) variants.push_back({0, false, true});
    if (options.baseline_jacobi_iterations > 0)
      variants.push_back({options.baseline_jacobi_iterations, false, false});
    for (const Variant& variant : variants) {
      const host::SimulationPlan plan =
          host::plan_simulation(bench_scenario(options, grid, variant, species), &cache.cache, nullptr);
      if (result.cases.empty()) {
        result.species_seconds = plan.species.front().seconds;
        result.nodes_per_tree = plan.species.front().nodes;
      }
      CoupledBenchCase c;
      c.grid = grid;
      c.pressure = variant.jacobi > 0 ? fmt::format("jacobi {}", variant.jacobi) : "cg 1e-3";
      c.turbulent = variant.turbulent;
      const trees::Forest& forest = plan.forest;
      host::CoupledStep coupled(cc, plan);
      if (variant.leaves) c.leaves = coupled.leaves().own_count();
      time_steps(cc, coupled, options, host::Communicator::alone(), c);
      if (variant.jacobi == 0 && !variant.turbulent && !variant.leaves)
        time_statistics(cc, coupled, options, c);
      result.cases.push_back(c);

      // Once, on the first case (neither depends on the grid): the deformation of every node, as on an
      // output frame, and the CPU reference of the trees' step and of the deformation.
      if (result.cases.size() == 1) {
        damage_fmas = host::DamageStages::modal_load_fmas(forest);
        host::ForestStages& trees = coupled.trees();
        trees.enqueue_deform();
        cc.finish();
        const auto deform_start = Clock::now();
        for (int f = 0; f < options.deform_frames; ++f) trees.enqueue_deform();
        cc.finish();
        result.deform_ms = ms_since(deform_start) / options.deform_frames;
        // The linear deformation alone, without the strong-wind correction (its cost is the difference).
        trees.set_strong_wind_correction(false);
        const auto linear_start = Clock::now();
        for (int f = 0; f < options.deform_frames; ++f) trees.enqueue_deform();
        cc.finish();
        result.deform_linear_ms = ms_since(linear_start) / options.deform_frames;
        trees.set_strong_wind_correction(true);
        result.deform_frames_per_s = 1e3 / result.deform_ms;
        result.node_modes_per_s = double(trees.total_nodes()) * options.modes * result.deform_frames_per_s;

        const trees::ForestReference reference(forest);
        const fluid::MacVelocity velocity = coupled.wind().download_velocity();
        Eigen::VectorXd q = Eigen::VectorXd::Zero(reference.total_modes()), qdot = q;
        const auto reference_start = Clock::now();
        const Eigen::VectorXd forces = reference.modal_forces(coupled.wind().spec(), velocity);
        reference.step(q, qdot, forces, kBenchDt, trees::ModalIntegrator::exact);
        result.trees_reference_ms = ms_since(reference_start);
        const auto reference_deform_start = Clock::now();
        const Eigen::MatrixX3d displacement = reference.displacements(q);
        result.deform_reference_ms = ms_since(reference_deform_start);
        if (!displacement.allFinite())
          throw std::runtime_error("bench coupled: CPU reference gave non-finite values");
      }
    }
  }
  result.fma_peak_gfma_s = measure_fma_peak(cc, 5);
  result.stream_gb_s = measure_stream_triad(cc, kRooflineElements, kRooflineRepetitions);
  // 3 FMAs (x, y, z) per node and mode in the linear sum; the corrected one has 6 (q~ v and q~^2 w).
  constexpr double kLinearFmas = 3.0, kStrongFmas = 6.0;
  const double peak = result.fma_peak_gfma_s * 1e9;
  result.deform_fraction_of_peak = kLinearFmas * result.node_modes_per_s / peak;
  result.deform_strong_fraction_of_peak = kStrongFmas * result.node_modes_per_s / peak;
  result.deform_linear_fraction_of_peak =
      kLinearFmas * result.node_modes_per_s * (result.deform_ms / result.deform_linear_ms) / peak;
  if (!result.cases.empty() && result.cases.front().damage_ms > 0.0)
    result.damage_fraction_of_peak = damage_fmas / (1e-3 * result.cases.front().damage_ms) / peak;
  return result;
}

RanksBenchResult run_coupled_bench_ranks(host::ComputeContext& cc, const CoupledBenchOptions& options,
                                         const host::Communicator& world) {
  RanksBenchResult result;
  result.bench = "coupled";
  result.device = cc.device().device_name;
  result.workload = fmt::format("{} trees of ~{} nodes x {} modes, two-way coupling, cg to 1e-3",
                                options.trees, options.nodes_per_tree, options.modes);
  result.skipped =
      "turbulence, leaves (timed in one process), the Jacobi baseline, the deformation, the CPU reference "
      "and the FMA peak";
  result.ranks = world.size();
  result.steps = options.steps;
  const BenchSpecies bench = bench_species(options);
  const ScratchCache cache;
  const Variant converged{};
  for (const auto& grid : options.grids) {
    const io::Scenario scenario = bench_scenario(options, grid, converged, bench.species);
    // The one-rank baseline: every rank steps the whole grid and forest at once, each on its own device.
    double alone_ms = 0.0;
    {
      const host::SimulationPlan alone = host::plan_simulation(scenario, &cache.cache, nullptr);
      if (alone_run_fits(world, cc.device(), alone.memory.total())) {
        CoupledBenchCase c;
        host::CoupledStep coupled(cc, alone);
        time_steps(cc, coupled, options, world, c);
        alone_ms = c.ms_per_step;
      }
    }
    const host::SimulationPlan plan = host::plan_simulation(scenario, &cache.cache, nullptr, world.size());
    CoupledBenchCase split;
    host::CoupledStep coupled(cc, plan, &world);
    time_steps(cc, coupled, options, world, split);
    result.cases.push_back(
        gather_case(world, grid, plan.decomposition,
                    {split.ms_per_step, alone_ms, split.halo, options.steps, split.pressure_iterations}));
  }
  return result;
}

void print_coupled_bench_table(const CoupledBenchResult& r, std::ostream& out) {
  out << fmt::format(
      "forestwind bench coupled on {}: {} trees x {} nodes x {} modes, {} wind samples per tree\n", r.device,
      r.trees, r.nodes_per_tree, r.modes, r.samples);
  out << fmt::format("species precomputation (host): {:.2f} s\n\n", r.species_seconds);
  out << fmt::format("{:<12} {:<15} {:>9} {:>9} {:>9} {:>9} {:>9} {:>9} {:>9}\n", "grid", "pressure",
                     "ms/step", "fluid", "advect", "canopy", "pressure", "trees", "p-iters");
  const CoupledBenchCase* converged = nullptr;  // the laminar cg case of the current grid
  for (const auto& c : r.cases) {
    auto stage = [&](const char* name) {
      auto it = c.stages_ms.find(name);
      return it == c.stages_ms.end() ? 0.0 : it->second;
    };
    out << fmt::format("{:<12} {:<15} {:>9.2f} {:>9.2f} {:>9.2f} {:>9.2f} {:>9.2f} {:>9.2f} {:>9.1f}",
                       fmt::format("{}x{}x{}", c.grid[0], c.grid[1], c.grid[2]),
                       c.pressure + (c.turbulent ? " +turb" : "") + (c.leaves > 0 ? " +leaves" : ""),
                       c.ms_per_step, c.fluid_ms, stage("advect"), stage("canopy"), stage("pressure"),
                       c.trees_ms, c.pressure_iterations);
    if (c.turbulent && converged)
      out << fmt::format("   turbulence x{:.2f} (+{:.1f} ms)", c.ms_per_step / converged->ms_per_step,
                         c.ms_per_step - converged->ms_per_step);
    if (c.leaves > 0)
      out << fmt::format("   {} leaves: {:.2f} ms = {:.1f}% of the step", c.leaves, stage("leaves"),
                         100.0 * stage("leaves") / c.ms_per_step);
    out << "\n";
    if (!c.turbulent && c.leaves == 0 && c.pressure == "cg 1e-3") converged = &c;
  }
  if (r.real_leaves_per_tree > 0)
    out << fmt::format(
        "(+leaves: the forest in full leaf, {:.0f} leaves of 40 cm^2 a tree, a sample of them "
        "simulated)\n",
        r.real_leaves_per_tree);
  out << "(+turb: the inflow turbulence box (15%, L_u 16 cells) and Stam's forcing of the trees by the "
         "eddies "
         "below 2 cells; jacobi N: Oliapuram's fixed Jacobi sweeps, the baseline; divergence is not "
         "controlled)\n";
  const CoupledBenchCase& head = r.cases.front();
  out << fmt::format(
      "trees' step on the device {:.2f} ms; CPU reference (double, 1 thread) {:.2f} ms: x{:.1f}\n",
      head.trees_ms, r.trees_reference_ms, r.trees_reference_ms / head.trees_ms);
  out << fmt::format(
      "storm damage (every tree's stem loads and failure check) {:.2f} ms = {:.1f}% of the trees' step; "
      "its maps' FMAs reach {:.0f}% of the FMA peak\n",
      head.damage_ms, 100.0 * head.damage_ms / head.trees_ms, 100.0 * r.damage_fraction_of_peak);
  for (const CoupledBenchCase& c : r.cases)
    if (c.statistics_ms > 0.0)
      out << fmt::format(
          "statistics on {}x{}x{} (stats.nc's profiles, one sample a step): {:.2f} ms = {:.1f}% of the step "
          "(limit 5%); {:.1f} GB/s = {:.0f}% of the STREAM triad ({:.1f} GB/s)\n",
          c.grid[0], c.grid[1], c.grid[2], c.statistics_ms, 100.0 * c.statistics_ms / c.ms_per_step,
          c.statistics_gb_s, 100.0 * c.statistics_gb_s / r.stream_gb_s, r.stream_gb_s);
  out << fmt::format(
      "\ndeformation of all {} nodes (output frames): {:.2f} ms = {:.1f} frames/s, {:.3g} node*modes/s\n",
      r.trees * r.nodes_per_tree, r.deform_ms, r.deform_frames_per_s, r.node_modes_per_s);
  out << fmt::format("of which the strong-wind correction {:.2f} ms (linear deformation alone {:.2f} ms)\n",
                     r.deform_ms - r.deform_linear_ms, r.deform_linear_ms);
  out << fmt::format(
      "corrected x{:.2f} the linear's time; of the FMA peak the linear reaches {:.0f}% (3 FMAs a "
      "node-mode), the corrected {:.0f}% (its 6: v and w)\n",
      r.deform_ms / r.deform_linear_ms, 100.0 * r.deform_linear_fraction_of_peak,
      100.0 * r.deform_strong_fraction_of_peak);
  out << fmt::format("CPU reference deformation (double, 1 thread): {:.1f} ms: the device is x{:.1f}\n",
                     r.deform_reference_ms, r.deform_reference_ms / r.deform_ms);
  out << fmt::format(
      "FMA peak (device, same process): {:.1f} GFMA/s; the deformation reaches {:.0f}% of it\n",
      r.fma_peak_gfma_s, 100.0 * r.deform_fraction_of_peak);
}

std::string coupled_bench_json(const CoupledBenchResult& r) {
  io::JsonWriter json;
  json.begin_object();
  json.key("device").value(r.device);
  json.key("trees").value(r.trees);
  json.key("nodes_per_tree").value(r.nodes_per_tree);
  json.key("modes").value(r.modes);
  json.key("samples").value(r.samples);
  const CoupledBenchCase& head = r.cases.front();
  json.key("grid").values(head.grid);
  json.key("ms_per_step").value(head.ms_per_step);
  json.key("stages_ms").object(head.stages_ms);
  json.key("deform_ms").value(r.deform_ms);
  json.key("deform_linear_ms").value(r.deform_linear_ms);
  json.key("deform_frames_per_s").value(r.deform_frames_per_s);
  json.key("node_modes_per_s").value(r.node_modes_per_s);
  json.key("fma_peak_gfma_s").value(r.fma_peak_gfma_s);
  json.key("deform_fraction_of_peak").value(r.deform_fraction_of_peak);
  json.key("deform_linear_fraction_of_peak").value(r.deform_linear_fraction_of_peak);
  json.key("damage_fraction_of_peak").value(r.damage_fraction_of_peak);
  json.key("deform_strong_fraction_of_peak").value(r.deform_strong_fraction_of_peak);
  json.key("species_seconds").value(r.species_seconds);
  json.key("trees_reference_ms").value(r.trees_reference_ms);
  json.key("deform_reference_ms").value(r.deform_reference_ms);
  json.key("stream_gb_s").value(r.stream_gb_s);
  json.key("cases").begin_array();
  for (const auto& c : r.cases) {
    json.begin_object();
    json.key("grid").values(c.grid);
    json.key("pressure").value(c.pressure);
    json.key("turbulent").value(c.turbulent);
    json.key("leaves").value(c.leaves);
    json.key("ms_per_step").value(c.ms_per_step);
    json.key("fluid_ms").value(c.fluid_ms);
    json.key("trees_ms").value(c.trees_ms);
    json.key("damage_ms").value(c.damage_ms);
    json.key("pressure_iterations").value(c.pressure_iterations);
    json.key("stages_ms").object(c.stages_ms);
    if (c.statistics_ms > 0.0) {
      json.key("statistics_ms").value(c.statistics_ms);
      json.key("statistics_fraction_of_step").value(c.statistics_ms / c.ms_per_step);
      json.key("statistics_gb_s").value(c.statistics_gb_s);
    }
    json.end_object();
  }
  json.end_array();
  json.end_object();
  return json.str();
}

}  // namespace fw::bench
