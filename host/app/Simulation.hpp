// The run loop: the coupled step over [0, end], with output frames handed to every writer on a background
// thread (docs/design.md, "Data flow").
//
//   fw::host::SimulationPlan plan = fw::host::plan_simulation(scenario, &cache, &std::cerr);
//   fw::host::Simulation sim(cc, std::move(plan), "out/storm");
//   fw::host::RunOptions options;
//   options.stop = &stop_signal;                  // std::atomic<int>, set by a signal handler
//   fw::host::RunSummary summary = sim.run(options);
//
//   fw::host::CheckpointParts from = fw::host::read_checkpoint(fw::host::find_checkpoint("out/storm"), world,
//                                                              plan.decomposition.describe());
//   options.resume = &from;                       // goes on from a checkpoint (host/app/RunCheckpoint.hpp)
//
// Each step is host/app/CoupledStep. Frames are captured at t = 0 and at the first step that reaches each
// multiple of the output interval: the velocity, the pressure and the trees' displacements (only what a
// writer needs) are copied from the device on the loop's thread, then written by io/OutputPipeline while
// the next steps run. The last step ends exactly on the end time.
//
// Output folder (host/app/OutputWriters.hpp lists the writers; every file is written under a temporary
// name and renamed, so any frame on disk is complete):
//   wind.pvd, wind/wind_NNNNNN.vti     cell data velocity, pressure, speed, vorticity, solid, canopy_density
//   trees.pvd, trees/trees_NNNNNN.vtp  polylines at deformed positions: radius, displacement, tree_id, ...
//   vdb/wind.NNNN.vdb                  grids vel (Vec3s) and speed, metadata time_s (when enabled)
//   probes.csv                         time_s, each probe's u, v, w, the tip displacement of the first trees
//   run.json                           version, device, scenario hash, counts, timings per stage, status
//   <scenario file name>               a copy of the scenario
//
//   checkpoints/step_NNNNNNNNNN/       the whole state (host/app/RunCheckpoint.hpp), every
//                                      output.checkpoint.interval, at the end, and when a signal stops it
//
// A blow-up (CoupledStep's SimulationError), a device error or a writer's error stops the run: the frames
// already captured are still written, run.json records the failure, and the error is rethrown. A stop
// request (a signal) ends the run after a checkpoint, with status "interrupted".
//
// Checkpoints and resuming (docs/design.md "Long runs"): before a checkpoint the loop waits until every
// frame and probe sample so far is on disk, so that a checkpoint never describes output that a crash could
// still lose. A resumed run restores every stage (CoupledStep::restore_state) and the loop's schedules, and
// the writers take over the folder's collections and probes.csv up to the checkpoint (FrameWriter::resume):
// the run goes on bit for bit as if it had never stopped. Its earlier segments go to run.json.
#pragma once

#include <atomic>
#include <filesystem>
#include <map>
#include <memory>
#include <ostream>
#include <string>

#include "host/app/CoupledStep.hpp"
#include "host/app/RunCheckpoint.hpp"
#include "host/app/Schedule.hpp"
#include "host/app/SimulationPlan.hpp"
#include "host/runtime/ComputeContext.hpp"

namespace fw::host {

struct RunOptions {
  double end_time = 0.0;  ///< s; > 0 overrides the plan's end time
  bool progress = false;  ///< one self-overwriting progress line on stderr
  /// Checked before every step: a signal number (> 0) stops the run cleanly, after a checkpoint.
  const std::atomic<int>* stop = nullptr;
  int tip_trees = 4;  ///< trees whose tip displacement goes to probes.csv
  /// Gets one line when the spin-up (time.spin_up) ends: its steps, simulated and wall seconds. May be null.
  std::ostream* log = nullptr;
  /// A checkpoint of this plan's run (read_checkpoint) to go on from, instead of t = 0; its scenario's
  /// state keys are the caller's to check (io::require_same_state). Parts of other ranks or blocks are
  /// redistributed over this run's (host/app/CheckpointRedistribution).
  const CheckpointParts* resume = nullptr;
};

struct RunSummary {
  long steps = 0;               ///< solver steps taken, a resumed run's earlier segments included
  long start_step = 0;          ///< steps taken before this run started (the checkpoint's, when resumed)
  double simulated_time = 0.0;  ///< s
  int frames = 0;
  bool interrupted = false;
  int stop_signal = 0;               ///< the signal that stopped the run (interrupted), else 0
  std::filesystem::path checkpoint;  ///< the last checkpoint written; empty when none was
  double wall_seconds = 0.0;
  /// The wind's spin-up before t = 0 (time.spin_up), when this run started at t = 0: its steps (not in
  /// `steps`), simulated seconds and wall seconds (in wall_seconds, not in stage_ms). 0 when resumed.
  long spin_up_steps = 0;
  double spin_up_seconds = 0.0;
  double spin_up_wall_seconds = 0.0;
  /// Totals over the run, ms: the coupled step's stages, "output" (the loop's own time for output: copies
  /// from the device and waits for room in the queue) and "output_write" (the output thread, overlapped).
  std::map<std::string, double> stage_ms;
};

class Simulation {
 public:
  /// Uploads the plan to the device; the output folder is created by run(). Throws std::invalid_argument when
  /// the grid does not fit the device. world: the run's ranks (null: one process); over several, every rank
  /// constructs one and runs it (docs/parallel.md), writing its pieces of the output into the same folder.
  Simulation(ComputeContext& cc, SimulationPlan plan, std::filesystem::path output_directory,
             const Communicator* world = nullptr);
  ~Simulation();
  Simulation(const Simulation&) = delete;
  Simulation& operator=(const Simulation&) = delete;

  RunSummary run(const RunOptions& options);

  const SimulationPlan& plan() const { return plan_; }

 private:
  ComputeContext& cc_;
  SimulationPlan plan_;
  std::filesystem::path directory_;
  const Communicator* world_;
  std::unique_ptr<CoupledStep> coupled_;
};

}  // namespace fw::host
