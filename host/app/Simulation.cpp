#include "host/app/Simulation.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <exception>
#include <iostream>
#include <optional>
#include <utility>
#include <vector>

#include "base/AtomicFile.hpp"
#include "base/WallClock.hpp"
#include "host/app/CheckpointRedistribution.hpp"
#include "host/app/FrameGather.hpp"
#include "host/app/OutputWriters.hpp"
#include "host/app/ProbeRecorder.hpp"
#include "host/app/StatisticsRecorder.hpp"
#include "host/runtime/Communicator.hpp"
#include "io/PvdCollection.hpp"
#include "io/writers/LeavesVtkWriter.hpp"
#include "io/writers/OutputPipeline.hpp"
#include "io/writers/TreesVtkWriter.hpp"
#include "io/writers/WindVtkWriter.hpp"

namespace fw::host {

namespace {

using Clock = base::WallClock;
using base::ms_since;

std::string format_duration(double seconds) {
  if (!std::isfinite(seconds) || seconds < 0) return "?";
  const long s = std::lround(seconds);
  if (s >= 3600) return fmt::format("{}h{:02d}m", s / 3600, (s / 60) % 60);
  if (s >= 60) return fmt::format("{}m{:02d}s", s / 60, s % 60);
  return fmt::format("{}s", s);
}

// The leaves the writers get: flying and landed ones always, of the attached ones those whose index among
// their tree's leaves is a multiple of attached_stride (none for 0), so that a frame shows the same attached
// leaves however many have been shed and however the forest is split over ranks; exited ones never (they
// are outside the domain).
io::LeafFrame leaf_frame(const LeafSnapshot& snap, const trees::LeafCounts& counts, int attached_stride) {
  io::LeafFrame out;
  out.counts = counts;
  for (std::size_t j = 0; j < snap.state.size(); ++j) {
    const auto state = static_cast<trees::LeafState>(snap.state[j]);
    if (state == trees::LeafState::exited) continue;
    if (state == trees::LeafState::attached && (attached_stride <= 0 || snap.leaf[j] % attached_stride != 0))
      continue;
    out.position.push_back({snap.position[3 * j], snap.position[3 * j + 1], snap.position[3 * j + 2]});
    out.normal.push_back({snap.normal[3 * j], snap.normal[3 * j + 1], snap.normal[3 * j + 2]});
    out.state.push_back(snap.state[j]);
    out.tree_id.push_back(snap.tree_id[j]);
    out.leaf.push_back(snap.leaf[j]);
    out.side.push_back(snap.side[j]);
  }
  return out;
}

// What the writers need of the device's state, copied back now (blocking reads on the loop's thread).
io::OutputFrame capture_frame(CoupledStep& coupled, const io::FrameNeeds& needs, int attached_stride,
                              int index) {
  io::OutputFrame frame;
  frame.index = index;
  frame.time = coupled.time();
  frame.step = coupled.steps();
  if (needs.velocity) frame.velocity = coupled.wind().download_velocity();
  if (needs.pressure) frame.pressure = coupled.wind().download_pressure();
  const bool leaves = needs.leaves && coupled.has_leaves();
  if ((needs.displacement || leaves) && coupled.has_trees()) coupled.enqueue_frame_deformation();
  if (needs.displacement && coupled.has_trees())
    frame.displacement = coupled.trees().download_displacements();
  if (leaves)
    frame.leaves = leaf_frame(coupled.leaves().download(), coupled.leaves().counts(), attached_stride);
  else if (needs.leaf_counts && coupled.has_leaves())
    frame.leaves.counts = coupled.leaves().counts();
  if (needs.damage) frame.damage = coupled.gather_damage();
  if (needs.utilisation && coupled.has_damage()) {
    frame.utilisation = coupled.node_utilisation();
    frame.tree_state = coupled.tree_states();
  }
  return frame;
}

// One self-overwriting line on stderr: the step, the simulated time, the wall time per step and the ETA.
void print_progress(const WindStepReport& step, double end, double wall_seconds) {
  const double rate = step.time / std::max(wall_seconds, 1e-9);  // simulated seconds per wall second
  std::cerr << fmt::format("\rstep {:>7}  t {:8.2f} / {:.2f} s  {:7.1f} ms/step  ETA {:>8}   ", step.step,
                           step.time, end, wall_seconds * 1e3 / double(step.step),
                           format_duration((end - step.time) / rate))
            << std::flush;
}

// One run of the loop: the coupled step, its probe samples and frames handed to the output pipeline, and
// the summary with its timings. Probe samples since the last frame travel with the next frame (or, at the
// end, in a last batch of their own).
class RunLoop {
 public:
  RunLoop(ComputeContext& cc, const SimulationPlan& plan, const std::filesystem::path& directory,
          CoupledStep& coupled, const RunOptions& options, const Communicator& world)
      : cc_(cc),
        plan_(plan),
        directory_(directory),
        options_(options),
        coupled_(coupled),
        world_(world),
        share_(output_share(plan, coupled, world)),
        probes_(cc, coupled, probe_points(plan), plan.forest.instance_count(), options.tip_trees,
                plan.coupling.strong_wind_correction),
        output_(make_writers(plan, directory, cc.device(), probes_.tip_trees(), share_ ? &*share_ : nullptr)),
        statistics_(cc, plan, coupled, world, directory / kStatisticsFile),
        checkpoints_(directory / "checkpoints", world),
        state_keys_(io::state_keys(plan.scenario.text)),
        frames_due_(plan.output.interval),
        samples_due_(plan.probe_interval),
        checkpoints_due_(plan.output.checkpoint_interval) {
    if (share_ && world.rank() == 0) {
      if (plan.output.vtk_wind) wind_pvd_.emplace(directory / "wind.pvd");
      if (plan.output.vtk_trees && plan.forest.instance_count() > 0)
        trees_pvd_.emplace(directory / "trees.pvd");
      if (plan.output.vtk_leaves && plan.leaf_count > 0) leaves_pvd_.emplace(directory / "leaves.pvd");
    }
  }

  /// Steps from t = 0, or from the checkpoint of options.resume, to `end` (or a stop request), then finishes
  /// the output; see Simulation::run.
  RunSummary run(double end) {
    // A checkpoint that does not fit this run is refused before the output folder is touched.
    const RunSnapshot* from = nullptr;
    if (options_.resume) {
      const CheckpointParts& read = *options_.resume;
      if (read.own) {
        from = &read.parts.front();
      } else {
        redistributed_ = redistribute_checkpoint(read.parts, coupled_, plan_);
        from = &*redistributed_;
      }
      coupled_.restore_state(from->stages);
      output_.check_resume(resume_point(*from));  // a probes.csv of other columns: refused, nothing touched
      statistics_.resume(from->time, from->progress.statistics);  // reads stats.nc; refuses another run's
    }
    try {
      std::filesystem::create_directories(directory_);
      coupled_.set_stage_timing(true);
      if (from) {
        resume(*from);
      } else {
        output_.begin();
        // A stats.nc of an earlier run in this folder is not this run's.
        if (world_.rank() == 0) std::filesystem::remove(directory_ / kStatisticsFile);
        start_with_spin_up();
        sample_probes();
        hand_over_frame();
      }
      start_time_ = coupled_.time();
      start_step_ = coupled_.steps();
      step_until(end);
      if (checkpoints_on() && !summary_.interrupted && !end_checkpointed_) write_checkpoint();
    } catch (const std::exception& e) {
      if (options_.progress) std::cerr << "\n";
      // The frames captured before the failure are still written; a second error while finishing is
      // secondary to the first, which is the one reported. Over ranks, only a blow-up is found by every rank
      // alike (the checks take global maxima); any other error is this rank's alone, and its caller stops
      // every rank, so it finishes without waiting for the others.
      const bool every_rank = dynamic_cast<const SimulationError*>(&e) != nullptr;
      try {
        finish("failed", e.what(), every_rank);
      } catch (const std::exception&) {
      }
      throw;
    }
    if (options_.progress) std::cerr << "\n";
    finish(summary_.interrupted ? "interrupted" : "completed", "");
    return summary_;
  }

 private:
  static std::optional<OutputShare> output_share(const SimulationPlan& plan, CoupledStep& coupled,
                                                 const Communicator& world) {
    if (!plan.decomposition.splits()) return std::nullopt;
    return OutputShare{world.rank(),           plan.decomposition.ranks(), coupled.wind().local_spec(),
                       coupled.wind().block(), plan.decomposition,         &coupled.own_forest()};
  }

  // Over ranks every rank copies back what any rank's writers need on a frame: the copies of the leaves and
  // the frame's gathering are collective. Collective.
  static io::FrameNeeds agreed_needs(io::FrameNeeds needs, const Communicator& world) {
    for (bool* flag : {&needs.velocity, &needs.pressure, &needs.displacement, &needs.probe_samples,
                       &needs.leaves, &needs.leaf_counts, &needs.damage, &needs.utilisation})
      *flag = world.max(*flag ? 1.0 : 0.0) > 0.0;
    return needs;
  }

  // Over ranks, rank 0 lists in the .pvd collections the frames that every rank has written (a collective
  // call): a frame some rank has not finished is never listed, so every listed frame opens.
  void list_complete_frames() {
    if (!share_) return;
    const long long complete = first_frame_ + world_.min(output_.frames_written());
    for (; listed_ < complete; ++listed_) {
      const double time = frame_times_[std::size_t(listed_ - first_frame_)];
      const int k = int(listed_);
      const io::OutputSettings& out = plan_.output;  // each collection lists its own frames
      if (wind_pvd_ && io::takes_frame(k, out.vtk_wind_every))
        wind_pvd_->add(time, io::WindVtkWriter::frame_file(k, true));
      if (trees_pvd_ && io::takes_frame(k, out.vtk_trees_every))
        trees_pvd_->add(time, io::TreesVtkWriter::frame_file(k, true));
      if (leaves_pvd_ && io::takes_frame(k, out.leaves_every))
        leaves_pvd_->add(time, io::LeavesVtkWriter::frame_file(k, true));
    }
  }

  // A stop request (a signal on any rank) stops every rank at the same step: the signal's number, else 0.
  int stop_requested() const {
    const int local = options_.stop ? options_.stop->load() : 0;
    return int(world_.max(double(local)));
  }

  bool checkpoints_on() const { return plan_.output.checkpoint_interval > 0.0; }

  // Goes on from a checkpoint whose stages are restored already: the schedules, the frame and sample
  // counts, the segments so far, and the output folder up to the checkpoint.
  static io::OutputResume resume_point(const RunSnapshot& from) {
    return {from.time, from.progress.frames, from.progress.probe_samples};
  }

  void resume(const RunSnapshot& from) {
    output_.resume(resume_point(from));
    checkpoints_.remove_after(from.step);  // collective: every rank has stopped writing past it
    if (world_.rank() == 0) base::remove_stale_temporaries(directory_);
    const RunProgress& progress = from.progress;
    frames_ = first_frame_ = listed_ = progress.frames;
    samples_taken_ = progress.probe_samples;
    frames_due_.resume(progress.next_frame);
    samples_due_.resume(progress.next_sample);
    checkpoints_due_.resume(progress.next_checkpoint);
    earlier_segments_ = progress.segments;
    last_checkpoint_step_ = from.step;
    for (auto* pvd : {&wind_pvd_, &trees_pvd_, &leaves_pvd_})
      if (*pvd) (*pvd)->continue_existing(from.time);
  }

  // The coupled step's start at t = 0, after the plan's spin-up (nothing is written during it). Its stage
  // timings are dropped, so that run.json's stages_ms are the recorded steps'; its wall time is reported.
  void start_with_spin_up() {
    const auto start = Clock::now();
    const SpinUpReport spun = coupled_.start(plan_.spin_up);
    if (spun.steps == 0) return;
    cc_.finish();
    summary_.spin_up_steps = spun.steps;
    summary_.spin_up_seconds = spun.seconds;
    summary_.spin_up_wall_seconds = ms_since(start) * 1e-3;
    coupled_.reset_stage_ms();
    if (options_.log)
      *options_.log << fmt::format("spin-up: {} steps, {} s of wind before t = 0, in {:.1f} s\n", spun.steps,
                                   spun.seconds, summary_.spin_up_wall_seconds);
  }

  // This run's segment up to now, with how it ended.
  io::RunSegment segment(const std::string& status) const {
    return {start_time_, coupled_.time(), start_step_, coupled_.steps(), ms_since(wall_start_) * 1e-3,
            status};
  }

  // Everything handed out so far is written first, so that the checkpoint never describes output a crash
  // could still lose; then every rank writes its part. reached_end: see RunProgress (the one at this step
  // without it is written again with it). Collective.
  void write_checkpoint(std::optional<double> reached_end = std::nullopt) {
    if (coupled_.steps() == last_checkpoint_step_ && !reached_end) return;
    const auto start = Clock::now();
    push_pending_samples();
    output_.drain();
    list_complete_frames();
    statistics_.write();
    RunSnapshot snapshot;
    snapshot.time = coupled_.time();
    snapshot.step = coupled_.steps();
    snapshot.stages = coupled_.save_state();
    snapshot.progress = {
        frames_,           samples_taken_, frames_due_.next(), samples_due_.next(), checkpoints_due_.next(),
        earlier_segments_, reached_end,    statistics_.saved()};
    snapshot.progress.segments.push_back(segment(kStoppedSegment));
    snapshot.state_keys = state_keys_;
    snapshot.ranks = plan_.decomposition.ranks();
    snapshot.decomposition = plan_.decomposition.describe();
    snapshot.block = coupled_.wind().block();
    const trees::Forest& own = coupled_.own_forest();
    for (int k = 0; k < own.instance_count(); ++k) snapshot.tree_ids.push_back(own.id(k));
    summary_.checkpoint = checkpoints_.write(snapshot, plan_.output.checkpoints_kept);
    last_checkpoint_step_ = coupled_.steps();
    checkpoint_ms_ += ms_since(start);
  }

  // The probe samples not yet handed to the writers, as a batch of their own.
  void push_pending_samples() {
    if (pending_samples_.empty()) return;
    io::OutputFrame last;
    last.probe_samples_only = true;
    last.probe_samples = std::move(pending_samples_);
    pending_samples_.clear();
    output_.push(std::move(last));
  }

  static std::vector<std::array<double, 3>> probe_points(const SimulationPlan& plan) {
    std::vector<std::array<double, 3>> points;
    for (const auto& probe : plan.output.probes) points.push_back(probe.position);
    return points;
  }

  void step_until(double end) {
    const double interval = plan_.output.interval;
    auto last_progress = Clock::now();
    while (coupled_.time() < end - kScheduleTolerance * interval) {
      if (const int signal = stop_requested()) {
        summary_.interrupted = true;
        summary_.stop_signal = signal;
        write_checkpoint();
        return;
      }
      output_.check();
      const NextStep next = coupled_.next_step(end - coupled_.time());
      // The end cuts the last step short, which a longer run would not: the end's checkpoint keeps the
      // state before it, so that an extension goes on from a step the longer run took too.
      if (checkpoints_on() && next.cut()) {
        write_checkpoint(end);
        end_checkpointed_ = true;
      }
      const CoupledStepReport report = coupled_.step(next);
      statistics_.after_step(report);
      if (samples_due_.due(report.wind.time)) sample_probes();
      if (frames_due_.due(report.wind.time)) hand_over_frame();
      // After the cut step none: the end's is the one before it.
      if (checkpoints_on() && !end_checkpointed_ && checkpoints_due_.due(report.wind.time))
        write_checkpoint();
      if (options_.progress && ms_since(last_progress) > kProgressMs) {
        last_progress = Clock::now();
        print_progress(report.wind, end, ms_since(wall_start_) * 1e-3);
      }
    }
  }

  void sample_probes() {
    if (probes_.empty()) return;
    const auto start = Clock::now();
    pending_samples_.push_back(probes_.sample(coupled_));
    ++samples_taken_;
    probe_ms_ += ms_since(start);
  }

  void hand_over_frame() {
    const auto start = Clock::now();
    // Only what this frame's writers take is copied back (each output's every-N).
    const io::FrameNeeds needs = agreed_needs(output_.needs(frames_), world_);
    io::OutputFrame frame = capture_frame(coupled_, needs, plan_.output.leaves_attached_stride, frames_++);
    // The VDB frames hold the whole domain: rank 0 writes them from every rank's part.
    if (share_ && plan_.output.vdb_enabled && io::takes_frame(frame.index, plan_.output.vdb_every))
      frame.gathered = gather_frame(frame, plan_.wind.spec, *coupled_.blocks(), coupled_.wind().block(),
                                    vdb_holds_leaves(plan_));
    frame.probe_samples = std::move(pending_samples_);
    pending_samples_.clear();
    frame_times_.push_back(frame.time);
    output_.push(std::move(frame));
    list_complete_frames();
    output_ms_ += ms_since(start);
  }

  // Every frame captured so far is written before run.json: a writer's error found while waiting for them
  // fails the run (unless it failed already) and is rethrown once run.json records it.
  void finish(const std::string& status, const std::string& message, bool every_rank = true) {
    cc_.finish();
    io::RunOutcome outcome;
    outcome.status = status;
    outcome.message = message;
    std::exception_ptr write_error;
    const auto drain_start = Clock::now();
    try {
      push_pending_samples();
      output_.drain();
      statistics_.write();
    } catch (const std::exception& e) {
      write_error = std::current_exception();
      if (outcome.status != "failed") {
        outcome.status = "failed";
        outcome.message = e.what();
      }
    }
    if (every_rank && !write_error) list_complete_frames();
    output_ms_ += ms_since(drain_start);
    outcome.steps = summary_.steps = coupled_.steps();
    summary_.start_step = start_step_;
    outcome.simulated_time = summary_.simulated_time = coupled_.time();
    summary_.stage_ms = coupled_.stage_ms();
    summary_.stage_ms["output"] = output_ms_;
    summary_.stage_ms["probes"] = probe_ms_;
    if (statistics_.on()) summary_.stage_ms["statistics"] = statistics_.ms();
    summary_.stage_ms["output_write"] = output_.write_ms();
    if (checkpoint_ms_ > 0.0) summary_.stage_ms["checkpoint"] = checkpoint_ms_;
    outcome.frames = summary_.frames = first_frame_ + output_.frames_written();
    summary_.wall_seconds = ms_since(wall_start_) * 1e-3;
    outcome.segments = earlier_segments_;
    outcome.segments.push_back(segment(outcome.status));
    for (const io::RunSegment& s : outcome.segments) outcome.wall_seconds += s.wall_seconds;
    outcome.stage_ms = summary_.stage_ms;
    outcome.spin_up_seconds = summary_.spin_up_seconds;
    outcome.spin_up_steps = summary_.spin_up_steps;
    outcome.spin_up_wall_seconds = summary_.spin_up_wall_seconds;
    if (every_rank) outcome.damage = coupled_.gather_damage();  // collective
    output_.finish(outcome);
    if (write_error) std::rethrow_exception(write_error);
  }

  static constexpr double kProgressMs = 250.0;  // between progress lines

  ComputeContext& cc_;
  const SimulationPlan& plan_;
  const std::filesystem::path& directory_;
  const RunOptions& options_;
  CoupledStep& coupled_;
  const Communicator& world_;
  const std::optional<OutputShare> share_;  // over ranks
  const Clock::time_point wall_start_ = Clock::now();
  ProbeRecorder probes_;
  io::OutputPipeline output_;
  StatisticsRecorder statistics_;
  RunSummary summary_;
  double output_ms_ = 0.0, probe_ms_ = 0.0;
  int frames_ = 0;
  std::vector<io::ProbeSample> pending_samples_;
  // Over ranks, rank 0's collections, the frames' times and how many frames they list.
  std::optional<io::PvdCollection> wind_pvd_, trees_pvd_, leaves_pvd_;
  std::vector<double> frame_times_;  // of the frames from first_frame_ on
  long long listed_ = 0;
  // Checkpoints, and where a resumed run started: its first frame's index, time and step.
  RunCheckpoints checkpoints_;
  const std::vector<io::StateKey> state_keys_;
  Schedule frames_due_, samples_due_, checkpoints_due_;
  int first_frame_ = 0;
  long samples_taken_ = 0;
  double start_time_ = 0.0;
  long start_step_ = 0;
  long last_checkpoint_step_ = -1;
  bool end_checkpointed_ = false;  // the end's checkpoint, before a last step cut short, is written
  double checkpoint_ms_ = 0.0;
  std::vector<io::RunSegment> earlier_segments_;
  std::optional<RunSnapshot> redistributed_;  // a checkpoint of other ranks or blocks, made this rank's
};

}  // namespace

Simulation::Simulation(ComputeContext& cc, SimulationPlan plan, std::filesystem::path output_directory,
                       const Communicator* world)
    : cc_(cc),
      plan_(std::move(plan)),
      directory_(std::move(output_directory)),
      world_(world != nullptr ? world : &Communicator::alone()) {
  coupled_ = std::make_unique<CoupledStep>(cc_, plan_, world_);
}

Simulation::~Simulation() = default;

RunSummary Simulation::run(const RunOptions& options) {
  const double end = options.end_time > 0.0 ? options.end_time : plan_.end_time;
  RunLoop loop(cc_, plan_, directory_, *coupled_, options, *world_);
  return loop.run(end);
}

}  // namespace fw::host
