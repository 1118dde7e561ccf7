#include "host/app/Simulation.hpp"

#include <fmt/format.h>

#include <array>
#include <chrono>
#include <cmath>
#include <exception>
#include <iostream>
#include <utility>

#include "host/app/OutputWriters.hpp"
#include "host/app/ProbeSampler.hpp"
#include "io/writers/OutputPipeline.hpp"

namespace fw::host {

namespace {

using Clock = std::chrono::steady_clock;

double ms_since(Clock::time_point start) {
  return std::chrono::duration<double, std::milli>(Clock::now() - start).count();
}

// Simulated times closer than this fraction of the frame interval are the same time (sums of float dt).
constexpr double kTimeTolerance = 1e-9;

std::string format_duration(double seconds) {
  if (!std::isfinite(seconds) || seconds < 0) return "?";
  const long s = std::lround(seconds);
  if (s >= 3600) return fmt::format("{}h{:02d}m", s / 3600, (s / 60) % 60);
  if (s >= 60) return fmt::format("{}m{:02d}s", s / 60, s % 60);
  return fmt::format("{}s", s);
}

// The leaves the writers get: flying and landed ones always, every attached_stride-th attached one (none for
// 0), exited ones never (they are outside the domain).
io::LeafFrame leaf_frame(const LeafSnapshot& snap, const trees::LeafCounts& counts, int attached_stride) {
  io::LeafFrame out;
  out.counts = counts;
  long attached_seen = 0;
  for (std::size_t j = 0; j < snap.state.size(); ++j) {
    const auto state = static_cast<trees::LeafState>(snap.state[j]);
    if (state == trees::LeafState::exited) continue;
    if (state == trees::LeafState::attached &&
        (attached_stride <= 0 || attached_seen++ % attached_stride != 0))
      continue;
    out.position.push_back({snap.position[3 * j], snap.position[3 * j + 1], snap.position[3 * j + 2]});
    out.normal.push_back({snap.normal[3 * j], snap.normal[3 * j + 1], snap.normal[3 * j + 2]});
    out.state.push_back(snap.state[j]);
    out.tree_id.push_back(snap.tree_id[j]);
    out.size.push_back(snap.side[j]);
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
  return frame;
}

}  // namespace

Simulation::Simulation(ComputeContext& cc, SimulationPlan plan, std::filesystem::path output_directory)
    : cc_(cc), plan_(std::move(plan)), directory_(std::move(output_directory)) {
  coupled_ = std::make_unique<CoupledStep>(cc_, plan_.wind, plan_.forest, plan_.coupling);
}

Simulation::~Simulation() = default;

RunSummary Simulation::run(const RunOptions& options) {
  CoupledStep& coupled = *coupled_;
  const double end = options.end_time > 0.0 ? options.end_time : plan_.end_time;
  const double interval = plan_.output.interval;

  RunSummary summary;
  const auto wall_start = Clock::now();
  std::vector<std::array<double, 3>> probe_points;
  for (const auto& probe : plan_.output.probes) probe_points.push_back(probe.position);
  ProbeSampler probes(cc_, plan_.wind.spec, probe_points, plan_.forest, options.tip_trees,
                      plan_.coupling.strong_wind_correction);
  io::OutputPipeline output(make_writers(plan_, directory_, cc_.device(), probes.tip_trees()));
  const io::FrameNeeds needs = output.needs();
  double output_ms = 0.0, probe_ms = 0.0;
  int frames = 0;
  // Probe samples since the last frame; they travel with the next frame (or a last batch of their own).
  std::vector<io::ProbeSample> pending_samples;
  auto take_probe_sample = [&] {
    if (probes.empty()) return;
    const auto start = Clock::now();
    pending_samples.push_back(probes.sample(coupled));
    probe_ms += ms_since(start);
  };
  auto hand_over_frame = [&] {
    const auto start = Clock::now();
    io::OutputFrame frame = capture_frame(coupled, needs, plan_.output.leaves_attached_stride, frames++);
    frame.probe_samples = std::move(pending_samples);
    pending_samples.clear();
    output.push(std::move(frame));
    output_ms += ms_since(start);
  };

  // Every frame captured so far is written before run.json: a writer's error found while waiting for them
  // fails the run (unless it failed already) and is rethrown once run.json records it.
  auto finish = [&](const std::string& status, const std::string& message) {
    cc_.finish();
    io::RunOutcome outcome;
    outcome.status = status;
    outcome.message = message;
    std::exception_ptr write_error;
    const auto drain_start = Clock::now();
    try {
      if (!pending_samples.empty()) {
        io::OutputFrame last;
        last.probe_samples_only = true;
        last.probe_samples = std::move(pending_samples);
        pending_samples.clear();
        output.push(std::move(last));
      }
      output.drain();
    } catch (const std::exception& e) {
      write_error = std::current_exception();
      if (outcome.status != "failed") {
        outcome.status = "failed";
        outcome.message = e.what();
      }
    }
    output_ms += ms_since(drain_start);
    outcome.steps = summary.steps = coupled.steps();
    outcome.simulated_time = summary.simulated_time = coupled.time();
    summary.stage_ms = coupled.stage_ms();
    summary.stage_ms["output"] = output_ms;
    summary.stage_ms["probes"] = probe_ms;
    summary.stage_ms["output_write"] = output.write_ms();
    outcome.frames = summary.frames = output.frames_written();
    outcome.wall_seconds = summary.wall_seconds = ms_since(wall_start) * 1e-3;
    outcome.stage_ms = summary.stage_ms;
    output.finish(outcome);
    if (write_error) std::rethrow_exception(write_error);
  };

  try {
    std::filesystem::create_directories(directory_);
    output.begin();
    coupled.set_stage_timing(true);
    if (plan_.turbulence_sigma) coupled.wind().set_turbulence_sigma(plan_.turbulence_sigma(0.0));
    coupled.start(plan_.ambient_wind(0.0));
    take_probe_sample();
    hand_over_frame();
    double next_frame = interval;
    // 0: every step. Like frames, a sample is due once the simulated time reaches its time.
    const double probe_interval = plan_.probe_interval;
    double next_probe = probe_interval;
    auto last_progress = Clock::now();
    while (coupled.time() < end - kTimeTolerance * interval) {
      if (options.stop && options.stop->load()) {
        summary.interrupted = true;
        break;
      }
      output.check();
      coupled.set_ambient(plan_.ambient_wind(coupled.time()));
      if (plan_.turbulence_sigma) coupled.wind().set_turbulence_sigma(plan_.turbulence_sigma(coupled.time()));
      if (plan_.unresolved_intensity)
        coupled.set_unresolved_intensity(plan_.unresolved_intensity(coupled.time()));
      const CoupledStepReport report = coupled.step(end - coupled.time());
      if (!(probe_interval > 0.0) || report.wind.time >= next_probe - kTimeTolerance * probe_interval) {
        take_probe_sample();
        while (probe_interval > 0.0 && next_probe <= report.wind.time + kTimeTolerance * probe_interval)
          next_probe += probe_interval;
      }
      if (report.wind.time >= next_frame - kTimeTolerance * interval) {
        hand_over_frame();
        while (next_frame <= report.wind.time + kTimeTolerance * interval) next_frame += interval;
      }
      if (options.progress && ms_since(last_progress) > 250.0) {
        last_progress = Clock::now();
        const double wall = ms_since(wall_start) * 1e-3;
        const double rate = report.wind.time / std::max(wall, 1e-9);  // simulated seconds per wall second
        std::cerr << fmt::format("\rstep {:>7}  t {:8.2f} / {:.2f} s  {:7.1f} ms/step  ETA {:>8}   ",
                                 report.wind.step, report.wind.time, end,
                                 wall * 1e3 / double(report.wind.step),
                                 format_duration((end - report.wind.time) / rate))
                  << std::flush;
      }
    }
  } catch (const std::exception& e) {
    if (options.progress) std::cerr << "\n";
    // The frames captured before the failure are still written; a second error while finishing is
    // secondary to the first, which is the one reported.
    try {
      finish("failed", e.what());
    } catch (const std::exception&) {
    }
    throw;
  }
  if (options.progress) std::cerr << "\n";
  finish(summary.interrupted ? "interrupted" : "completed", "");
  return summary;
}

}  // namespace fw::host
