// The one interface of every run output (docs/design.md, "Outputs"): the run loop hands each frame to every
// writer, and a new output is a new class, not an edit of the loop.
//
//   std::vector<std::unique_ptr<fw::io::FrameWriter>> writers;
//   writers.push_back(std::make_unique<fw::io::WindVtkWriter>(directory, settings, grid));
//   fw::io::OutputPipeline output(std::move(writers));   // writes on a background thread
//   output.begin();                                      // folders and headers, before the first step
//   output.push(std::move(frame));                       // every output frame
//   output.finish(outcome);                              // waits for the queue, then each writer's finish
//
// A writer's begin() and finish() run on the run loop's thread, write() on the output thread, one frame at
// a time in frame order; an output with an every-N (set_every) gets only the frames it takes. Every file is
// written under a temporary name and renamed (io/AtomicFile), and a collection (.pvd) lists a frame only once
// its file is complete.
#pragma once

#include <array>
#include <cstdint>
#include <map>
#include <optional>
#include <stdexcept>
#include <string>
#include <vector>

#include "fluid/MacVelocity.hpp"
#include "trees/LeafState.hpp"
#include "trees/TreeDamage.hpp"

namespace fw::io {

/// One probe sample (docs/design.md, "probes.csv"): taken at the probes' own interval, not only on frames.
struct ProbeSample {
  double time = 0.0;                        ///< simulated time, s
  std::vector<std::array<float, 3>> wind;   ///< per probe point, m/s
  std::vector<std::array<double, 3>> tips;  ///< tip displacement per tracked tree, m, world frame
  trees::LeafCounts leaf_counts;            ///< at the sample's time; written only in runs with leaves
  trees::DamageCounts damage_counts;        ///< at the sample's time; written only in runs with damage
};

/// The leaves of a frame (docs/leaves.md): the written leaves (attached ones thinned or left out as the
/// output settings ask; exited ones never), one entry each in every array, and the counts over all leaves.
struct LeafFrame {
  std::vector<std::array<float, 3>> position;  ///< blade centre, m, world frame
  std::vector<std::array<float, 3>> normal;    ///< blade normal, unit
  std::vector<std::uint8_t> state;             ///< trees::LeafState: 0 attached, 1 flying, 2 landed
  std::vector<std::int32_t> tree_id;           ///< instance index of the tree the leaf grew on
  std::vector<std::int32_t>
      leaf;  ///< its index among that tree's leaves (orders the leaves gathered over ranks)
  std::vector<float>
      side;  ///< blade side l = sqrt(area), m (the files' array "size", Houdini's pscale l / 2)
  trees::LeafCounts counts;  ///< over every leaf of the run, written or not
  std::size_t size_written() const { return position.size(); }
};

/// What a frame carries: the state copied back from the device. What never changes (grid, solids, canopy,
/// the trees' rest geometry) the writers keep from their construction.
struct OutputFrame {
  int index = 0;                ///< 0, 1, 2, ...: the frame number in file names
  double time = 0.0;            ///< simulated time, s
  long step = 0;                ///< solver steps taken
  fluid::MacVelocity velocity;  ///< face velocities, m/s
  std::vector<float> pressure;  ///< kinematic pressure p/rho per cell, m^2/s^2; empty unless needed
  std::vector<float>
      displacement;  ///< 3 per forest node (instance order, world frame), m; empty unless needed
  LeafFrame leaves;  ///< empty unless a writer needs the leaves
  /// Storm damage (docs/damage.md), empty unless needed: every tree's record in whole-forest order (over
  /// ranks on rank 0 only), and the stress utilisation of each of this rank's trees' nodes (as
  /// `displacement`, one float a node: a stem node's section's, 0 elsewhere) with each of its trees' state
  /// (trees::TreeState as an int).
  std::vector<trees::TreeDamageRecord> damage;
  std::vector<float> utilisation;
  std::vector<std::int32_t> tree_state;
  /// Over MPI ranks a rank's frame holds its block's velocity (with the halo) and its leaves. For the files
  /// that hold the whole domain (VDB), rank 0's frame also holds every rank's part, gathered: the domain's
  /// faces and every leaf in one process's order. Empty in one process, and on the other ranks.
  struct Gathered {
    fluid::MacVelocity velocity;
    LeafFrame leaves;
  };
  std::optional<Gathered> gathered;
  /// The probe samples taken since the previous frame, this frame's time included, in time order.
  std::vector<ProbeSample> probe_samples;
  /// A last batch of probe samples after the last frame: only writers that need probe samples get it, and
  /// it is not a frame (no files, not counted).
  bool probe_samples_only = false;
};

/// Which optional parts of a frame a writer reads, so that the run copies back only those.
struct FrameNeeds {
  bool velocity = false;
  bool pressure = false;
  bool displacement = false;
  bool probe_samples = false;
  bool leaves = false;
  bool leaf_counts = false;  ///< the counts over every leaf only (LeafFrame::counts); implied by leaves
  bool damage = false;       ///< every tree's damage record (OutputFrame::damage)
  bool utilisation = false;  ///< the nodes' stress utilisation and trees' states (OutputFrame::utilisation)
  FrameNeeds& operator|=(const FrameNeeds& other) {
    velocity = velocity || other.velocity;
    pressure = pressure || other.pressure;
    displacement = displacement || other.displacement;
    probe_samples = probe_samples || other.probe_samples;
    leaves = leaves || other.leaves;
    leaf_counts = leaf_counts || other.leaf_counts;
    damage = damage || other.damage;
    utilisation = utilisation || other.utilisation;
    return *this;
  }
};

/// One stretch of a run between a start (or a resume) and its stop (docs/design.md "Long runs"): run.json
/// lists them, so that a run resumed from checkpoints accounts for every wall second.
struct RunSegment {
  double start_time = 0.0, end_time = 0.0;  ///< simulated, s
  long start_step = 0, end_step = 0;        ///< solver steps taken at its start and end
  double wall_seconds = 0.0;
  std::string status;  ///< how it ended: "completed", "interrupted", "failed" or "stopped" (a later segment
                       ///< resumed from a checkpoint before its end)
};

/// Where a resumed run's output goes on (docs/design.md "Long runs"): the checkpoint's time, the frames and
/// probe samples written before it, in a folder that may hold the stopped run's files (or be a new one).
struct OutputResume {
  double time = 0.0;       ///< s: collections keep their frames up to it, later ones are dropped
  int frames = 0;          ///< frames handed out before the checkpoint: the next frame's index
  long probe_samples = 0;  ///< probes.csv rows before the checkpoint
};

/// How a run ended, for the writers' finish().
struct RunOutcome {
  std::string status = "completed";  ///< "completed", "interrupted" or "failed"
  std::string message;               ///< the error, for "failed"
  long steps = 0;
  double simulated_time = 0.0;  ///< s
  int frames = 0;               ///< frames written
  double wall_seconds = 0.0;
  std::map<std::string, double> stage_ms;  ///< totals over the run, ms
  /// The wind's spin-up before t = 0 (time.spin_up): its simulated seconds and steps (not in `steps`) and
  /// its wall seconds (in wall_seconds). This run's: 0 steps for a run resumed from a checkpoint.
  double spin_up_seconds = 0.0;
  long spin_up_steps = 0;
  double spin_up_wall_seconds = 0.0;
  /// The run's segments in order, this one last: one for a run that was never resumed. Empty only for a
  /// caller that does not keep them (run.json then lists none).
  std::vector<RunSegment> segments;
  /// Every tree's damage record at the end (whole-forest order; rank 0), empty without damage or when a
  /// failure left it out of reach.
  std::vector<trees::TreeDamageRecord> damage;
};

/// Whether an output written every `every`-th frame takes frame `index`: the multiples of `every`, so that
/// every output's files keep the frame's number and line up in time.
inline bool takes_frame(int index, int every) {
  return index % every == 0;
}

class FrameWriter {
 public:
  virtual ~FrameWriter() = default;
  /// What the writer produces, for messages ("wind VTK").
  virtual std::string name() const = 0;
  virtual FrameNeeds needs() const { return {}; }
  /// Creates folders and headers. Throws std::runtime_error naming the path on failure.
  virtual void begin() {}
  /// begin() for a run resumed from a checkpoint: a writer of a collection or of a growing file takes over
  /// what the folder holds up to `resume` and drops what came after it (a resumed run writes it again).
  /// Writers of one file per frame need nothing more than begin(), the default.
  virtual void resume(const OutputResume& /*resume*/) { begin(); }
  /// Throws std::invalid_argument when resume() would refuse the folder (a growing file of other columns),
  /// before any writer touches it; nothing by default.
  virtual void check_resume(const OutputResume& /*resume*/) const {}
  /// Writes one frame. Throws std::runtime_error naming the path on failure.
  virtual void write(const OutputFrame& frame) = 0;
  /// After the last frame was written (also after a failure or an interruption).
  virtual void finish(const RunOutcome& /*outcome*/) {}

  /// The output's every-N (output.vtk.wind_every, ...): it gets the frames whose index is a multiple of
  /// `every` only. Throws std::invalid_argument for every < 1.
  void set_every(int every) {
    if (every < 1) throw std::invalid_argument(name() + ": every " + std::to_string(every) + " is not >= 1");
    every_ = every;
  }
  int every() const { return every_; }
  /// Whether write() gets frame `index`.
  bool takes(int index) const { return takes_frame(index, every_); }

 private:
  int every_ = 1;
};

}  // namespace fw::io
