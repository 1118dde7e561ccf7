#include "host/app/Simulation.hpp"

#include <fmt/format.h>
#include <unistd.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <fstream>
#include <iostream>
#include <limits>
#include <optional>

#include "host/stages/ForestStages.hpp"
#include "host/stages/WindGrid.hpp"
#include "io/AtomicFile.hpp"
#include "io/JsonWriter.hpp"
#include "io/ProbesCsv.hpp"
#include "io/PvdCollection.hpp"
#include "io/TreesVtk.hpp"
#include "io/VdbWriter.hpp"
#include "io/WindFrame.hpp"
#include "io/WindVtk.hpp"
#include "trees/ForestReference.hpp"

namespace fw::host {

namespace {

using Clock = std::chrono::steady_clock;

double ms_since(Clock::time_point start) {
  return std::chrono::duration<double, std::milli>(Clock::now() - start).count();
}

// A fixed time step this far past the advection CFL limit is a blow-up in the making, not a slow run.
constexpr double kRunawayCfl = 5.0;

// Semi-implicit Euler of q'' + gamma q' + omega^2 q = f is stable while dt^2 omega^2 + 2 gamma dt < 4 (Jury's
// test on its amplification matrix, trace 2 - dt^2 omega^2 - gamma dt and determinant 1 - gamma dt): the
// largest stable dt over every instance's modes, s; infinity without trees.
double semi_implicit_dt_limit(const trees::Forest& forest) {
  const trees::ForestReference reference(forest);
  const Eigen::VectorXd omega = reference.omega(), gamma = reference.gamma();
  double limit = std::numeric_limits<double>::infinity();
  for (Eigen::Index i = 0; i < omega.size(); ++i) {
    const double w2 = omega[i] * omega[i];
    limit = std::min(limit, (std::sqrt(gamma[i] * gamma[i] + 4.0 * w2) - gamma[i]) / w2);
  }
  return limit;
}

std::string format_duration(double seconds) {
  if (!std::isfinite(seconds) || seconds < 0) return "?";
  const long s = std::lround(seconds);
  if (s >= 3600) return fmt::format("{}h{:02d}m", s / 3600, (s / 60) % 60);
  if (s >= 60) return fmt::format("{}m{:02d}s", s / 60, s % 60);
  return fmt::format("{}s", s);
}

bool contains(const std::vector<std::string>& list, const std::string& name) {
  return std::find(list.begin(), list.end(), name) != list.end();
}

// Rest geometry of every instance in the world frame, for the trees' output frames.
std::vector<io::TreesFrame::Tree> rest_trees(const trees::Forest& forest) {
  std::vector<io::TreesFrame::Tree> rest;
  for (int k = 0; k < forest.instance_count(); ++k) {
    const trees::TreeInstance& instance = forest.instances()[std::size_t(k)];
    const trees::Skeleton& skeleton = forest.species_of(k).skeleton();
    const Eigen::Matrix3d rotation = forest.rotation(k);
    io::TreesFrame::Tree tree;
    tree.tree_id = k;
    tree.species = instance.species;
    tree.rest.resize(skeleton.size(), 3);
    for (int n = 0; n < skeleton.size(); ++n) {
      const trees::SkeletonNode& node = skeleton.node(n);
      tree.rest.row(n) = (instance.position + instance.scale * rotation * node.position).transpose();
      tree.radius.push_back(instance.scale * node.radius);
      tree.parent.push_back(node.parent);
    }
    rest.push_back(std::move(tree));
  }
  return rest;
}

// The highest node of a species' skeleton: the tree's tip for probes.csv.
int tip_node(const trees::Skeleton& skeleton) {
  int tip = 0;
  for (int n = 1; n < skeleton.size(); ++n) {
    if (skeleton.node(n).position.z() > skeleton.node(tip).position.z()) tip = n;
  }
  return tip;
}

}  // namespace

std::string text_hash(const std::string& text) {
  std::uint64_t hash = 0xcbf29ce484222325ULL;
  for (unsigned char c : text) {
    hash ^= c;
    hash *= 0x100000001b3ULL;
  }
  return fmt::format("{:016x}", hash);
}

struct Simulation::State {
  State(ComputeContext& context, SimulationPlan p, std::filesystem::path dir)
      : cc(context),
        plan(std::move(p)),
        directory(std::move(dir)),
        wind(cc, plan.wind),
        trees(cc, plan.wind.spec, plan.forest),
        wind_pvd(directory / "wind.pvd"),
        trees_pvd(directory / "trees.pvd") {
    if (!plan.drag_density.empty()) wind.set_canopy(plan.drag_density);
    trees.set_integrator(plan.scenario.forest.integrator);
    rest = rest_trees(plan.forest);
  }

  ComputeContext& cc;
  SimulationPlan plan;
  std::filesystem::path directory;
  WindGrid wind;
  ForestStages trees;
  io::PvdCollection wind_pvd, trees_pvd;
  std::optional<io::ProbesCsv> probes;
  std::vector<io::TreesFrame::Tree> rest;
  std::vector<int> tip_instances;  // instances whose tip goes to probes.csv
  std::map<std::string, double> stage_ms;
  int frames = 0;

  void prepare_output(const RunOptions& options);
  void write_frame(double time, long step);
  void write_manifest(const RunSummary& summary, const std::string& status, const std::string& message);
};

void Simulation::State::prepare_output(const RunOptions& options) {
  const io::OutputSettings& out = plan.scenario.output;
  std::filesystem::create_directories(directory);
  if (out.vtk_wind) std::filesystem::create_directories(directory / "wind");
  if (out.vtk_trees && plan.forest.instance_count() > 0)
    std::filesystem::create_directories(directory / "trees");
  if (out.vdb_enabled) std::filesystem::create_directories(directory / "vdb");

  // A copy of the scenario, so the folder says how it was made.
  const auto copy = directory / plan.scenario.file.filename();
  io::AtomicFile file(copy);
  {
    std::ofstream stream(file.temporary_path(), std::ios::binary);
    stream << plan.scenario.text;
    if (!stream) throw std::runtime_error(fmt::format("cannot write {}", copy.string()));
  }
  file.commit();

  std::vector<std::string> names;
  for (const auto& probe : out.probes) names.push_back(probe.name);
  for (int k = 0; k < std::min(options.tip_trees, plan.forest.instance_count()); ++k)
    tip_instances.push_back(k);
  if (!names.empty() || !tip_instances.empty())
    probes.emplace(directory / "probes.csv", names, tip_instances);
}

void Simulation::State::write_frame(double time, long step) {
  const auto start = Clock::now();
  const io::OutputSettings& out = plan.scenario.output;
  const fluid::GridSpec& spec = wind.spec();
  const fluid::MacVelocity velocity = wind.download_velocity();
  const bool trees_present = plan.forest.instance_count() > 0;

  if (out.vtk_wind || out.vdb_enabled) {
    std::vector<float> pressure;
    if (contains(out.vtk_fields, "pressure")) pressure = wind.download_pressure();
    const io::WindFrame frame = io::make_wind_frame(spec, velocity, std::move(pressure), plan.wind.solid,
                                                    plan.canopy_density, time, step);
    if (out.vtk_wind) {
      const std::string name = fmt::format("wind/wind_{:06d}.vti", frames);
      io::write_wind_vti(directory / name, frame, out.vtk_fields);
      wind_pvd.add(time, name);
    }
    if (out.vdb_enabled) {
      io::write_wind_vdb(directory / fmt::format("vdb/wind.{:04d}.vdb", frames), frame,
                         contains(out.vdb_grids, "vel"), contains(out.vdb_grids, "speed"));
    }
  }

  std::vector<float> displacement;
  if (trees_present && (out.vtk_trees || !tip_instances.empty())) {
    trees.enqueue_deform();
    displacement = trees.download_displacements();
  }
  if (trees_present && out.vtk_trees) {
    io::TreesFrame frame;
    frame.time = time;
    frame.trees = rest;
    for (int k = 0; k < plan.forest.instance_count(); ++k) {
      io::TreesFrame::Tree& tree = frame.trees[std::size_t(k)];
      const std::size_t first = std::size_t(plan.forest.node_offset(k));
      tree.displacement.resize(tree.rest.rows(), 3);
      for (Eigen::Index n = 0; n < tree.rest.rows(); ++n) {
        for (int a = 0; a < 3; ++a)
          tree.displacement(n, a) = displacement[3 * (first + std::size_t(n)) + std::size_t(a)];
      }
    }
    const std::string name = fmt::format("trees/trees_{:06d}.vtp", frames);
    io::write_trees_vtp(directory / name, frame);
    trees_pvd.add(time, name);
  }

  if (probes) {
    std::vector<std::array<float, 3>> probe_velocity;
    for (const auto& probe : out.probes)
      probe_velocity.push_back(io::sample_velocity(spec, velocity, probe.position));
    std::vector<std::array<double, 3>> tips;
    for (int k : tip_instances) {
      const std::size_t node = std::size_t(plan.forest.node_offset(k)) +
                               std::size_t(tip_node(plan.forest.species_of(k).skeleton()));
      tips.push_back({displacement[3 * node], displacement[3 * node + 1], displacement[3 * node + 2]});
    }
    probes->append(time, probe_velocity, tips);
  }
  ++frames;
  stage_ms["output"] += ms_since(start);
}

void Simulation::State::write_manifest(const RunSummary& summary, const std::string& status,
                                       const std::string& message) {
  io::JsonWriter json;
  json.begin_object();
  json.key("version").value(std::string(FORESTWIND_VERSION));
  json.key("scenario").value(plan.scenario.name);
  json.key("scenario_file").value(plan.scenario.file.filename().string());
  json.key("scenario_hash").value(text_hash(plan.scenario.text));
  json.key("seed").value(std::uint64_t(plan.scenario.seed));
  json.key("device").value(cc.device().device_name);
  json.key("platform").value(cc.device().platform_name);
  json.key("status").value(status);
  if (!message.empty()) json.key("message").value(message);
  const auto& spec = plan.wind.spec;
  json.key("grid").begin_array().value(spec.nx).value(spec.ny).value(spec.nz).end_array();
  json.key("cell_size_m").value(spec.h);
  json.key("trees").value(plan.forest.instance_count());
  json.key("species").begin_array();
  for (const auto& s : plan.species) {
    json.begin_object();
    json.key("name").value(s.name);
    json.key("nodes").value(s.nodes);
    json.key("modes").value(s.modes);
    json.key("wind_samples").value(s.samples);
    json.key("trees").value(s.trees);
    json.key("first_hz").value(s.first_hz);
    json.key("cache").value(s.cache);
    json.end_object();
  }
  json.end_array();
  json.key("two_way_coupling").value(!plan.drag_density.empty());
  json.key("steps").value(std::int64_t(summary.steps));
  json.key("simulated_time_s").value(summary.simulated_time);
  json.key("frames").value(summary.frames);
  json.key("interrupted").value(summary.interrupted);
  json.key("wall_seconds").value(summary.wall_seconds);
  json.key("ms_per_step").value(summary.steps > 0 ? summary.wall_seconds * 1e3 / double(summary.steps) : 0.0);
  json.key("stages_ms").begin_object();
  for (const auto& [stage, ms] : summary.stage_ms) json.key(stage).value(ms);
  json.end_object();
  json.end_object();

  const auto path = directory / "run.json";
  io::AtomicFile file(path);
  {
    std::ofstream stream(file.temporary_path(), std::ios::binary);
    stream << json.str() << "\n";
    if (!stream) throw std::runtime_error(fmt::format("cannot write {}", path.string()));
  }
  file.commit();
}

Simulation::Simulation(ComputeContext& cc, SimulationPlan plan, std::filesystem::path output_directory)
    : state_(std::make_unique<State>(cc, std::move(plan), std::move(output_directory))) {}

Simulation::~Simulation() = default;

const SimulationPlan& Simulation::plan() const {
  return state_->plan;
}

RunSummary Simulation::run(const RunOptions& options) {
  State& s = *state_;
  const io::Scenario& scenario = s.plan.scenario;
  const double end = options.end_time > 0.0 ? options.end_time : scenario.time.end;
  const double interval = scenario.output.interval;
  const bool fixed_dt = scenario.time.dt.has_value();

  RunSummary summary;
  const auto wall_start = Clock::now();
  s.prepare_output(options);
  s.wind.set_stage_timing(true);
  s.wind.set_ambient(scenario.wind_vector(0.0));
  s.wind.initialise_ambient();
  s.write_frame(0.0, 0);
  double next_frame = interval;
  auto last_progress = Clock::now();

  auto finish = [&](const std::string& status, const std::string& message) {
    s.cc.finish();
    summary.frames = s.frames;
    summary.simulated_time = s.wind.time();
    summary.wall_seconds = ms_since(wall_start) * 1e-3;
    summary.stage_ms = s.stage_ms;
    for (const auto& [stage, ms] : s.wind.stage_ms()) summary.stage_ms[stage] += ms;
    s.write_manifest(summary, status, message);
  };

  try {
    const double semi_implicit_limit = scenario.forest.integrator == trees::ModalIntegrator::semi_implicit
                                           ? semi_implicit_dt_limit(s.plan.forest)
                                           : std::numeric_limits<double>::infinity();
    // The last step may overshoot `end` by less than one dt: frames are only written up to `end`.
    while (s.wind.time() < end - 1e-9) {
      if (options.stop && options.stop->load()) {
        summary.interrupted = true;
        break;
      }
      s.wind.set_ambient(scenario.wind_vector(s.wind.time()));
      const WindStepReport report = s.wind.step();
      if (report.dt >= semi_implicit_limit) {
        throw SimulationError(fmt::format(
            "step {} (t = {:.3f} s): field tree modes: semi-implicit Euler is unstable at dt = {:.4g} s "
            "for the fastest tree mode (stable below {:.4g} s); lower time.dt or set forest.integrator: "
            "exact",
            report.step, report.time, report.dt, semi_implicit_limit));
      }
      const auto trees_start = Clock::now();
      if (s.plan.forest.instance_count() > 0) {
        s.trees.enqueue_wind_load(s.wind.velocity());
        s.trees.enqueue_modal_step(float(report.dt));
        s.cc.finish();
      }
      s.stage_ms["trees"] += ms_since(trees_start);
      summary.steps = report.step;

      if (fixed_dt && report.step % 10 == 0) {
        const double vmax = s.wind.max_speed_component();
        const double cfl = vmax * report.dt / s.wind.spec().h;
        if (!std::isfinite(vmax)) {
          throw SimulationError(
              fmt::format("step {} (t = {:.3f} s): field velocity is not finite", report.step, report.time));
        }
        if (cfl > kRunawayCfl) {
          throw SimulationError(
              fmt::format("step {} (t = {:.3f} s): field velocity reaches {:.1f} m/s, CFL number {:.1f} > {} "
                          "with the fixed "
                          "dt {} s; lower time.dt or use dt: auto",
                          report.step, report.time, vmax, cfl, kRunawayCfl, report.dt));
        }
      }
      if (report.time >= next_frame - 1e-9 * interval) {
        s.write_frame(report.time, report.step);
        while (next_frame <= report.time + 1e-9 * interval) next_frame += interval;
      }
      if (options.progress && ms_since(last_progress) > 250.0) {
        last_progress = Clock::now();
        const double wall = ms_since(wall_start) * 1e-3;
        const double rate = report.time / std::max(wall, 1e-9);  // simulated seconds per wall second
        std::cerr << fmt::format("\rstep {:>7}  t {:8.2f} / {:.2f} s  {:7.1f} ms/step  ETA {:>8}   ",
                                 report.step, report.time, end, wall * 1e3 / double(report.step),
                                 format_duration((end - report.time) / rate))
                  << std::flush;
      }
    }
  } catch (const std::exception& e) {
    if (options.progress) std::cerr << "\n";
    // Name the step for failures that come from the grid itself (e.g. "velocity is not finite before step
    // N").
    finish("failed", e.what());
    throw;
  }
  if (options.progress) std::cerr << "\n";
  finish(summary.interrupted ? "interrupted" : "completed", "");
  return summary;
}

}  // namespace fw::host
