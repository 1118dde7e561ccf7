// `forestwind run` and `forestwind check` (docs/design.md, "Command line").
#include <fmt/format.h>
#include <unistd.h>

#include <atomic>
#include <cmath>
#include <csignal>
#include <filesystem>
#include <iostream>
#include <iterator>
#include <memory>
#include <optional>

#include "base/FileLock.hpp"
#include "host/app/DeviceMemory.hpp"
#include "host/app/OutputFolder.hpp"
#include "host/app/OutputSpace.hpp"
#include "host/app/Simulation.hpp"
#include "host/app/SimulationPlan.hpp"
#include "host/cli/Commands.hpp"
#include "host/runtime/ComputeContext.hpp"
#include "host/runtime/Device.hpp"
#include "io/Scenario.hpp"
#include "io/ScenarioStateKeys.hpp"
#include "trees/BasisCache.hpp"

namespace fw::cli {

namespace {

// The signals that stop a run after a checkpoint (docs/design.md "Long runs"): Ctrl-C, a batch system's stop,
// and the notice some clusters send before a job's time limit.
constexpr int kStopSignals[] = {SIGINT, SIGTERM, SIGUSR1};
// A run stopped by signal S exits with 128 + S, as a shell reports a process a signal ended.
constexpr int kSignalExitBase = 128;

std::atomic<int> g_stop_signal{0};

extern "C" void on_stop_signal(int signal) {
  g_stop_signal.store(signal);
}

// Restores the previous handlers when the run ends, however it ends.
class StopSignalGuard {
 public:
  StopSignalGuard() {
    for (std::size_t s = 0; s < std::size(kStopSignals); ++s)
      previous_[s] = std::signal(kStopSignals[s], on_stop_signal);
  }
  ~StopSignalGuard() {
    for (std::size_t s = 0; s < std::size(kStopSignals); ++s) std::signal(kStopSignals[s], previous_[s]);
  }

 private:
  void (*previous_[std::size(kStopSignals)])(int) = {};
};

// The checkpoint `given` names, read for this rank of the run `plan` describes, after checking that the
// scenario keeps what its state depends on: everything but time.end, output and the decomposition (exit 2
// naming the key otherwise).
host::CheckpointParts checkpoint_to_resume(const std::string& given, const io::Scenario& scenario,
                                           const host::SimulationPlan& plan,
                                           const host::Communicator& world) {
  host::CheckpointParts read =
      host::read_checkpoint(host::find_checkpoint(given), world, plan.decomposition.describe());
  io::require_same_state(read.any().state_keys, io::state_keys(scenario.text), scenario.file.string());
  return read;
}

// What `check` and `run` say of a resume: the checkpoint, its time and step, and the ranks it came from.
std::string resume_summary(const host::CheckpointParts& from) {
  const host::RunSnapshot& any = from.any();
  return fmt::format(
      "from {} at t = {:.6g} s (step {}, {} frames and {} probe rows written{})", from.folder.string(),
      any.time, any.step, any.progress.frames, any.progress.probe_samples,
      from.own ? "" : fmt::format("; written by {} ranks ({}), redistributed", any.ranks, any.decomposition));
}

// What a resume from `at` to `end` runs. The checkpoint a run writes at its end holds its last whole step
// (host::RunProgress::reached_end), so the end's cut step is taken again, or a longer one in its place.
std::string what_is_left(const host::RunSnapshot& at, double end) {
  const std::optional<double> reached = at.progress.reached_end;
  if (reached && end <= *reached)
    return fmt::format(
        "nothing new to run: the run reached its end, {} s, and goes on from its last whole "
        "step to take the step cut to land on it again (raise time.end to extend)",
        *reached);
  if (reached)
    return fmt::format(
        "{:.6g} s more than the run reached, from its last whole step before {} s, bit for "
        "bit as a run to the new end",
        end - *reached, *reached);
  const double more = end - at.time;
  return more > 0.0 ? fmt::format("{:.6g} s more", more) : "nothing more to run (raise time.end to extend)";
}

}  // namespace

int run_check(const std::string& scenario_path, const std::string& resume, const host::Communicator& world) {
  const io::Scenario scenario = io::load_scenario(scenario_path);
  // The plan `run` builds, with the same cache (species bases are computed or loaded here once), but for
  // check: what only the run needs of the turbulence box and the leaves is estimated, not built
  // (host::PlanFor). Valid means that nothing short of the device itself can fail. Under mpirun every rank
  // plans; rank 0 reports.
  trees::BasisCache cache(trees::BasisCache::default_directory());
  const host::SimulationPlan plan =
      host::plan_simulation(scenario, &cache, nullptr, world.size(), host::PlanFor::check);
  std::optional<host::CheckpointParts> from;
  if (!resume.empty()) from = checkpoint_to_resume(resume, scenario, plan, world);
  if (world.rank() != 0) return 0;
  std::cout << fmt::format("{}: scenario '{}' is valid\n", scenario_path, scenario.name);
  host::print_plan(plan, std::cout);
  if (from) {
    const host::RunSnapshot& at = from->any();
    std::cout << fmt::format("resume: {}, to time.end {} s: {}{}\n", resume_summary(*from), plan.end_time,
                             what_is_left(at, plan.end_time), plan.spin_up > 0.0 ? ", no spin-up" : "");
  }
  for (const std::string& warning : plan.warnings) std::cerr << "warning: " << warning << "\n";
  return 0;
}

int run_scenario(const RunCommandOptions& options, const GlobalOptions& global,
                 const host::Communicator& world) {
  // Everything that can be wrong with the input is found before the device or the output folder is touched.
  const io::Scenario scenario = io::load_scenario(options.scenario);
  const std::filesystem::path directory =
      options.output_dir.empty() ? scenario.output.directory : std::filesystem::absolute(options.output_dir);
  // Over ranks, rank 0 speaks for all: they plan alike.
  const bool speaks = world.rank() == 0 && !options.quiet;
  const bool terminal = ::isatty(STDERR_FILENO) == 1 && speaks;
  std::ostream* log = speaks ? &std::cerr : nullptr;
  trees::BasisCache cache(trees::BasisCache::default_directory());
  host::SimulationPlan plan = host::plan_simulation(scenario, &cache, log, world.size());
  std::optional<host::CheckpointParts> from;
  if (!options.resume.empty()) from = checkpoint_to_resume(options.resume, scenario, plan, world);
  if (log)
    for (const std::string& warning : plan.warnings) *log << "warning: " << warning << "\n";
  const bool leaves = plan.leaf_count > 0;
  const double end = options.run.end_time > 0.0 ? options.run.end_time : plan.end_time;
  // The folder's own faults, before the device: it cannot be written, or its disk lacks room (--force runs
  // anyway on a disk that seems full, not on a read-only one).
  host::require_writable_output(directory, world);
  if (!options.force)
    host::require_output_space(plan, directory, end, world, options.free_bytes,
                               from ? from->any().time : 0.0);

  host::ComputeContext cc(
      host::select_device(host::device_filter_from_env(global.device_filter), world.node_rank()),
      global.profile);
  // A run the device cannot hold is refused before the folder exists (over ranks, each rank's block is
  // checked where the grid is allocated, also before the folder exists).
  if (!plan.decomposition.splits()) host::require_fits(plan.memory, cc.device(), scenario.file.string());
  // One run at a time in a folder: held until this function returns, however it returns.
  const std::unique_ptr<base::FileLock> lock = host::lock_output_folder(directory, world);
  if (log) {
    *log << fmt::format("{}: {} x {} x {} cells, {} trees, device {} ({})\n", scenario.name,
                        plan.wind.spec.nx, plan.wind.spec.ny, plan.wind.spec.nz, plan.forest.instance_count(),
                        cc.device().device_name, cc.device().platform_name);
    if (plan.decomposition.splits())
      *log << fmt::format("{} ranks: {}, a device each\n", plan.decomposition.ranks(),
                          plan.decomposition.describe());
    if (from) *log << fmt::format("resuming {}\n", resume_summary(*from));
  }
  host::Simulation simulation(cc, std::move(plan), directory, &world);
  host::RunOptions run = options.run;
  run.progress = terminal;
  run.log = log;
  run.stop = &g_stop_signal;
  run.resume = from ? &*from : nullptr;
  g_stop_signal.store(0);
  StopSignalGuard guard;
  const host::RunSummary summary = simulation.run(run);

  if (speaks) {
    const long steps = summary.steps - summary.start_step;  // this run's, a resumed run's from its checkpoint
    // The spin-up before t = 0 has its own line: its steps and wall time are not this line's.
    const double steps_wall = summary.wall_seconds - summary.spin_up_wall_seconds;
    std::cout << fmt::format("{} steps{} to t = {:.2f} s in {:.1f} s ({:.1f} ms/step), {} frames{}\n", steps,
                             summary.start_step > 0 ? fmt::format(" from step {}", summary.start_step) : "",
                             summary.simulated_time, summary.wall_seconds,
                             steps > 0 ? steps_wall * 1e3 / double(steps) : 0.0, summary.frames,
                             summary.interrupted ? " (interrupted)" : "");
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
    if (scenario.output.statistics)
      std::cout << fmt::format(
          "  statistics: {0}/stats.nc (xarray; docs/statistics.md)   forestwind plot {0} "
          "--profiles -o {0}/profiles.png\n",
          directory.string());
    if (!summary.checkpoint.empty())
      std::cout << fmt::format("  checkpoint: {}   go on: forestwind run {} -o {} --resume {}\n",
                               summary.checkpoint.string(), options.scenario, directory.string(),
                               directory.string());
  }
  if (cc.profiling()) cc.profiler()->print(std::cout);
  return summary.interrupted ? kSignalExitBase + summary.stop_signal : 0;
}

}  // namespace fw::cli
