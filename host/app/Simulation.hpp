// The coupled run: the wind grid and every tree's modes advance together on one OpenCL device, and output
// frames are written as the run goes (DESIGN.md, "Data flow").
//
//   fw::host::SimulationPlan plan = fw::host::plan_simulation(scenario, &cache, &std::cerr);
//   fw::host::Simulation sim(cc, std::move(plan), "out/storm");
//   fw::host::RunOptions options;
//   options.stop = &interrupted;                  // std::atomic<bool>, set by a SIGINT handler
//   fw::host::RunSummary summary = sim.run(options);
//
// Per step, all on the device: ambient wind and gusts at time t -> wind grid step (advect, forces, canopy
// drag, projection) -> sample the wind at every tree -> modal forces -> modal step. Nothing comes back to the
// host except on output frames (velocity, pressure, the trees' displacements) and the solver's scalars.
//
// Output folder (every file written under a temporary name and renamed, so any frame on disk is complete):
//   wind.pvd, wind/wind_NNNNNN.vti     cell data velocity, pressure, speed, vorticity, solid, canopy_density
//   trees.pvd, trees/trees_NNNNNN.vtp  polylines at deformed positions: radius, displacement, tree_id,
//   species vdb/wind.NNNN.vdb                  grids vel (Vec3s) and speed, metadata time_s (when enabled)
//   probes.csv                         time_s, each probe's u, v, w, the tip displacement of the first trees
//   run.json                           version, device, scenario hash, counts, timings per stage, status
//   <scenario file name>               a copy of the scenario
// Frames are written at t = 0 and at the first step that reaches each multiple of the output interval.
//
// A NaN velocity, or a fixed time step whose CFL number exceeds 5 (far past stable advection), stops the run
// with a SimulationError naming the step and the field; the frames written so far stay valid, and run.json
// records the failure.
#pragma once

#include <atomic>
#include <filesystem>
#include <map>
#include <stdexcept>
#include <string>

#include "host/runtime/ComputeContext.hpp"
#include "host/app/SimulationPlan.hpp"

namespace fw::host {

struct RunOptions {
  double end_time = 0.0;                    ///< s; > 0 overrides the scenario's time.end
  bool progress = false;                    ///< one self-overwriting progress line on stderr
  const std::atomic<bool>* stop = nullptr;  ///< checked after every step: true stops the run cleanly
  int tip_trees = 4;                        ///< trees whose tip displacement goes to probes.csv
};

struct RunSummary {
  long steps = 0;
  double simulated_time = 0.0;  ///< s
  int frames = 0;
  bool interrupted = false;
  double wall_seconds = 0.0;
  std::map<std::string, double> stage_ms;  ///< totals over the run
};

/// A numerical blow-up: what() names the step and the field.
class SimulationError : public std::runtime_error {
 public:
  using std::runtime_error::runtime_error;
};

class Simulation {
 public:
  /// Uploads the plan to the device; the output folder is created by run(). Throws std::invalid_argument when
  /// the grid does not fit the device.
  Simulation(ComputeContext& cc, SimulationPlan plan, std::filesystem::path output_directory);
  ~Simulation();
  Simulation(const Simulation&) = delete;
  Simulation& operator=(const Simulation&) = delete;

  RunSummary run(const RunOptions& options);

  const SimulationPlan& plan() const;

 private:
  struct State;
  std::unique_ptr<State> state_;
};

/// 64-bit FNV-1a of a text, as 16 hex digits (the scenario hash in run.json).
std::string text_hash(const std::string& text);

}  // namespace fw::host
