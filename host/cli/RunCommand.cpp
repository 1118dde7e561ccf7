// `forestwind run` and `forestwind check` (docs/design.md, "Command line").
#include <fmt/format.h>
#include <unistd.h>

#include <atomic>
#include <cmath>
#include <csignal>
#include <filesystem>
#include <iostream>

#include "host/app/Simulation.hpp"
#include "host/app/SimulationPlan.hpp"
#include "host/cli/Commands.hpp"
#include "host/runtime/ComputeContext.hpp"
#include "host/runtime/Device.hpp"
#include "io/Scenario.hpp"
#include "trees/BasisCache.hpp"
#include "trees/Foliage.hpp"
#include "trees/ForestLayout.hpp"
#include "trees/SpeciesLeaves.hpp"

namespace fw::cli {

namespace {

std::atomic<bool> g_interrupted{false};

extern "C" void on_interrupt(int) {
  g_interrupted.store(true);
}

// Restores the previous SIGINT handler when the run ends, however it ends.
class InterruptGuard {
 public:
  InterruptGuard() { previous_ = std::signal(SIGINT, on_interrupt); }
  ~InterruptGuard() { std::signal(SIGINT, previous_); }

 private:
  void (*previous_)(int) = SIG_DFL;
};

std::string megabytes(std::size_t bytes) {
  return fmt::format("{:.1f} MB", double(bytes) / 1e6);
}

// The largest ambient speed over the run (sampled every second and at the end) plus the strongest gust: what
// an automatic time step will be limited by.
double peak_wind_speed(const io::Scenario& scenario) {
  double peak = 0.0;
  for (double t = 0.0;; t = std::min(t + 1.0, scenario.time.end)) {
    const auto v = scenario.wind_vector(t);
    peak = std::max(peak, std::hypot(v[0], v[1], v[2]));
    if (t >= scenario.time.end) break;
  }
  double gust = 0.0;
  for (const auto& event : scenario.events) gust = std::max(gust, event.peak_speed);
  return peak + gust;
}

}  // namespace

int run_check(const std::string& scenario_path) {
  const io::Scenario scenario = io::load_scenario(scenario_path);
  const fluid::GridSpec spec = scenario.grid_spec(0.0);
  std::cout << fmt::format("{}: scenario '{}' is valid\n", scenario_path, scenario.name);
  std::cout << fmt::format("grid: {} x {} x {} = {} cells of {} m, domain {} x {} x {} m\n", spec.nx, spec.ny,
                           spec.nz, spec.cell_count(), spec.h, scenario.domain.size[0],
                           scenario.domain.size[1], scenario.domain.size[2]);
  static const char* faces[6] = {"west", "east", "south", "north", "ground", "top"};
  std::string boundaries;
  for (int f = 0; f < 6; ++f) {
    // A rough ground is a slip wall for the grid plus the log-law stress; say what the file says.
    const bool rough =
        f == FW_FACE_GROUND && scenario.boundaries[std::size_t(f)] == io::BoundaryChoice::rough;
    boundaries += fmt::format("{}{} {}", f ? ", " : "", faces[f],
                              rough ? fmt::format("rough (z0 {} m)", scenario.ground_roughness_length)
                                    : fluid::to_string(spec.boundary[std::size_t(f)]));
  }
  std::cout << "boundaries at t = 0: " << boundaries << "\n";
  if (const auto& turbulence = scenario.wind.turbulence) {
    const auto& n = turbulence->box_cells;
    std::cout << fmt::format(
        "turbulence: von Karman, L_u {} m, box {} x {} x {} cells ({} x {} x {} m, points every h/2), "
        "{}\n",
        turbulence->length_scale, n[0], n[1], n[2], turbulence->box_size[0], turbulence->box_size[1],
        turbulence->box_size[2],
        turbulence->unresolved ? "unresolved eddies force the trees" : "no unresolved forcing");
  }

  std::vector<int> trees_per_species(scenario.forest.species.size(), 0);
  for (const auto& stand : scenario.forest.stands) {
    trees_per_species[std::size_t(stand.layout.species)] += int(trees::place_stand(stand.layout).size());
  }
  for (const auto& tree : scenario.forest.trees) ++trees_per_species[std::size_t(tree.species_index)];
  std::size_t forest_floats = 0, leaf_bytes = 0;
  long leaf_total = 0;
  int tree_count = 0;
  for (std::size_t i = 0; i < scenario.forest.species.size(); ++i) {
    const io::Species& species = scenario.forest.species[i];
    const trees::Skeleton skeleton = host::species_skeleton(species);
    const int nodes = skeleton.size();
    io::check_species_skeleton(scenario, int(i), nodes);
    const int modes = species.modes.count;
    std::string leaves;
    if (species.leaves.has_leaves()) {
      const int per_tree =
          trees::SpeciesLeaves::generate(
              skeleton, trees::Foliage::of(skeleton, species.canopy.leaf_area_index), species.leaves)
              .count();
      leaves = fmt::format(", {} leaves a tree ({})", per_tree, trees::to_string(species.leaves.model));
      leaf_bytes += std::size_t(per_tree) * (std::size_t(trees_per_species[i]) * host::kDeviceBytesPerLeaf +
                                             host::kDeviceBytesPerSpeciesLeaf);
      leaf_total += long(per_tree) * trees_per_species[i];
    }
    std::cout << fmt::format("species {}: {} nodes, {} modes, {} wind samples, {} trees{}\n", species.name,
                             nodes, modes, species.modes.wind_samples, trees_per_species[i], leaves);
    forest_floats += std::size_t(3) * std::size_t(nodes) * std::size_t(modes) +
                     std::size_t(trees_per_species[i]) * (4 * std::size_t(modes) + 4 * std::size_t(nodes));
    tree_count += trees_per_species[i];
  }
  std::cout << fmt::format(
      "trees: {}, leaves: {}, obstacles: {}, gusts: {}, terrain: {}, two-way coupling: {}\n", tree_count,
      leaf_total, scenario.obstacles.size(), scenario.events.size(), scenario.terrain ? "yes" : "no",
      scenario.forest.two_way_coupling ? "on" : "off");
  const std::size_t bytes = host::WindGrid::estimate_device_bytes(spec, scenario.wind_settings(), 1) +
                            forest_floats * sizeof(float) + (tree_count > 0 ? spec.cell_count() * 4 : 0) +
                            leaf_bytes;
  std::cout << "estimated device memory: " << megabytes(bytes) << "\n";
  if (scenario.time.dt) {
    std::cout << fmt::format("steps: {} (dt {} s to t = {} s)\n",
                             long(std::ceil(scenario.time.end / *scenario.time.dt)), *scenario.time.dt,
                             scenario.time.end);
  } else {
    const double peak = peak_wind_speed(scenario);
    const double dt = peak > 0.0 ? scenario.time.cfl * spec.h / peak : 1.0;
    std::cout << fmt::format(
        "steps: about {} or more (dt auto, CFL {}: {:.3f} s at the peak ambient wind plus gusts, {:.1f} m/s, "
        "to t = "
        "{} s)\n",
        long(std::ceil(scenario.time.end / dt)), scenario.time.cfl, dt, peak, scenario.time.end);
  }
  std::cout << fmt::format("output: {} every {} s\n", scenario.output.directory.string(),
                           scenario.output.interval);
  return 0;
}

int run_scenario(const RunOptions& options, const GlobalOptions& global) {
  // Everything that can be wrong with the input is found before the device or the output folder is touched.
  const io::Scenario scenario = io::load_scenario(options.scenario);
  const std::filesystem::path directory =
      options.output_dir.empty() ? scenario.output.directory : std::filesystem::absolute(options.output_dir);
  const bool terminal = ::isatty(STDERR_FILENO) == 1 && !options.quiet;
  std::ostream* log = options.quiet ? nullptr : &std::cerr;
  trees::BasisCache cache(trees::BasisCache::default_directory());
  host::SimulationPlan plan = host::plan_simulation(scenario, &cache, log);
  const bool leaves = plan.leaf_count > 0;

  host::ComputeContext cc(host::select_device(host::device_filter_from_env(global.device_filter)),
                          global.profile);
  if (log) {
    *log << fmt::format("{}: {} x {} x {} cells, {} trees, device {} ({})\n", scenario.name,
                        plan.wind.spec.nx, plan.wind.spec.ny, plan.wind.spec.nz, plan.forest.instance_count(),
                        cc.device().device_name, cc.device().platform_name);
  }
  host::Simulation simulation(cc, std::move(plan), directory);
  host::RunOptions run;
  run.end_time = options.end_time;
  run.progress = terminal;
  run.stop = &g_interrupted;
  g_interrupted.store(false);
  InterruptGuard guard;
  const host::RunSummary summary = simulation.run(run);

  if (!options.quiet) {
    std::cout << fmt::format("{} steps to t = {:.2f} s in {:.1f} s ({:.1f} ms/step), {} frames{}\n",
                             summary.steps, summary.simulated_time, summary.wall_seconds,
                             summary.steps ? summary.wall_seconds * 1e3 / double(summary.steps) : 0.0,
                             summary.frames, summary.interrupted ? " (interrupted)" : "");
    std::cout << fmt::format("outputs in {}\n", directory.string());
    std::cout << fmt::format(
        "  ParaView: paraview --script={}/view.py   (a speed slice, the trees as tubes{})\n",
        directory.string(), leaves ? ", the leaves as points" : "");
    std::cout << fmt::format(
        "  pictures: forestwind render {0} -o {0}/frame.png   forestwind plot {0} -o {0}/probes.png\n",
        directory.string());
    if (scenario.output.vdb_enabled) {
      std::string grids;
      for (const auto& grid : scenario.output.vdb_grids)
        if (grid != "leaves" || leaves) grids += (grids.empty() ? "" : ", ") + grid;
      std::cout << fmt::format("  Houdini / Blender: {}/vdb/wind.####.vdb (grids {})\n", directory.string(),
                               grids);
    }
    std::cout << fmt::format("  probes: {0}/probes.csv   timings: {0}/run.json\n", directory.string());
  }
  if (cc.profiling()) cc.profiler()->print(std::cout);
  return summary.interrupted ? 130 : 0;
}

}  // namespace fw::cli
