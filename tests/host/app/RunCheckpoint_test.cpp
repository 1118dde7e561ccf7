// Checkpoints and resuming (host/app/RunCheckpoint, the run loop's side in host/app/Simulation): a run
// resumed from a checkpoint in its middle writes the same bytes as the run that never stopped, for each kind
// of state a run carries; checkpoints are kept, found and refused as docs/design.md "Long runs" says.
#include "host/app/RunCheckpoint.hpp"

#include <catch2/catch.hpp>

#include <fmt/format.h>

#include <algorithm>
#include <filesystem>
#include <fstream>
#include <regex>
#include <sstream>
#include <string>
#include <vector>

#include "base/SourceError.hpp"
#include "host/app/OutputSize.hpp"
#include "host/app/Simulation.hpp"
#include "host/app/SimulationPlan.hpp"
#include "io/Checkpoint.hpp"
#include "io/Scenario.hpp"
#include "io/ScenarioStateKeys.hpp"
#include "tests/support/OutputFiles.hpp"
#include "tests/support/TempDir.hpp"
#include "tests/support/TestDevice.hpp"

namespace fs = std::filesystem;
using fw::test::TempDir;

namespace {

// A VDB file's first 57 bytes are OpenVDB's header with a random UUID of the file; the rest is the grids.
constexpr std::size_t kVdbHeaderBytes = 57;

// The parts every test scenario shares: a 48 x 24 x 16 grid of 2 m cells, probes, frames every second and
// a checkpoint every 1.5 s (all kept), so that the run of 6 s has checkpoints in its middle.
std::string scenario(const std::string& body, double end = 6.0) {
  return fmt::format(
      "scenario: resume_test\nseed: 4\ntime: {{end: {}, dt: auto, cfl: 0.8}}\n"
      "domain: {{origin: [0, 0, 0], size: [96, 48, 32], cell_size: 2.0}}\n{}"
      "output:\n  directory: out\n  interval: 1.0\n  vdb: {{enabled: true, grids: [vel, speed, leaves]}}\n"
      "  checkpoint: {{interval: 1.5, keep: 100}}\n"
      "  probes:\n    - {{name: mid, position: [48, 24, 8]}}\n    - {{name: lee, position: [80, 30, 4]}}\n",
      end, body);
}

// A small broadleaf stand, with `extra` added to the species (leaves, ...).
std::string stand(const std::string& extra = "") {
  return "forest:\n  two_way_coupling: true\n  species:\n"
         "    - name: shrub\n      skeleton: {generate: {preset: broadleaf, height: 6.0, seed: 2}}\n"
         "      modes: {count: 6, damping_ratio: 0.05, wind_samples: 2}\n"
         "      canopy: {leaf_area_index: 3.0, drag_coefficient: 0.4}\n" +
         extra +
         "  stands:\n    - {species: shrub, region: {min: [30, 12], max: [60, 36]}, layout: grid, spacing: "
         "8.0,"
         " seed: 2}\n";
}

// A turbulent inflow under `advection` with Smagorinsky, over the stand under Stam's forcing, shedding
// leaves: every kind of state a run carries.
std::string turbulent_stand_with_leaves(const std::string& advection) {
  return "wind: {speed: 14.0, direction: 270.0, reference_height: 10.0, profile: {type: power, alpha: 0.2},\n"
         "       turbulence: {intensity: 0.2, length_scale: 12.0, unresolved: true}}\n"
         "solver: {advection: " +
         advection + ", smagorinsky_constant: 0.17}\n" +
         stand(
             "      leaves: {model: stochastic, area: 0.004, fraction: 0.05, petiole_strength: 0.1,"
             " strength_spread: 0.6}\n");
}

struct Run {
  fw::io::Scenario scenario;
  fw::host::SimulationPlan plan;
};

Run plan_run(const TempDir& dir, const std::string& yaml, fw::trees::BasisCache& cache) {
  const std::string file = dir.write("resume_test.yaml", yaml);
  Run run{fw::io::load_scenario(file), {}};
  run.plan = fw::host::plan_simulation(run.scenario, &cache, nullptr);
  return run;
}

fw::host::RunSummary run_to_end(fw::host::ComputeContext& cc, const Run& run, const fs::path& out,
                                const fw::host::CheckpointParts* resume = nullptr) {
  fw::host::Simulation sim(cc, run.plan, out);
  fw::host::RunOptions options;
  options.resume = resume;
  return sim.run(options);
}

// Every file under `folder` but the checkpoints and run.json (whose segments and wall times differ), by
// its path relative to `folder`.
std::vector<std::string> output_files(const fs::path& folder) {
  std::vector<std::string> files;
  for (const auto& entry : fs::recursive_directory_iterator(folder)) {
    const std::string relative = fs::relative(entry.path(), folder).generic_string();
    if (entry.is_regular_file() && !relative.starts_with("checkpoints/") && relative != "run.json")
      files.push_back(relative);
  }
  std::sort(files.begin(), files.end());
  return files;
}

// A run.json value, as its text: a number, or an object of numbers.
std::string json_value(const fs::path& run_json, const std::string& key, bool object = false) {
  const std::string text = fw::test::file_text(run_json);
  std::smatch m;
  REQUIRE(std::regex_search(text, m, std::regex("\"" + key + (object ? "\":(\\{[^}]*\\})" : "\":([^,}]*)"))));
  return m[1].str();
}

// An output file's bytes, but for a VDB file's header (its random UUID).
std::string output_bytes(const fs::path& folder, const std::string& file) {
  std::string bytes = fw::test::file_text(folder / file);
  if (file.ends_with(".vdb")) {
    REQUIRE(bytes.size() > kVdbHeaderBytes);
    bytes.erase(0, kVdbHeaderBytes);
  }
  return bytes;
}

// Folder `b` holds the output files of `a`, each byte for byte, and run.json the same counts (steps,
// simulated time, frames, leaves): returns the files.
std::vector<std::string> check_same_output(const fs::path& a, const fs::path& b) {
  const std::vector<std::string> files = output_files(a);
  CHECK(output_files(b) == files);
  for (const std::string& file : files) {
    INFO(file);
    const bool same = output_bytes(a, file) == output_bytes(b, file);
    CHECK(same);
  }
  for (const std::string key : {"steps", "simulated_time_s", "frames"}) {
    INFO(key);
    CHECK(json_value(a / "run.json", key) == json_value(b / "run.json", key));
  }
  if (fw::test::file_text(a / "run.json").find("\"leaves\":{") != std::string::npos)
    CHECK(json_value(a / "run.json", "leaves", true) == json_value(b / "run.json", "leaves", true));
  return files;
}

// What a resume test saw: the checkpoint it resumed from, and the uninterrupted run's probes.csv.
struct Resumed {
  double time = 0.0;  // s
  std::string probes;
};

// Runs `yaml` to its end in A; copies A to B and resumes B from the checkpoint nearest the middle of the
// run; every output file of B must equal A's byte for byte, and run.json's counts too. Returns the
// checkpoint's time and A's probes.
Resumed check_resumes_bit_for_bit(const std::string& yaml) {
  auto* cc = fw::test::device_or_skip();
  if (!cc) return {};
  TempDir dir("fw_resume");
  fw::trees::BasisCache cache(fs::path(dir.path()) / "cache");
  const Run run = plan_run(dir, yaml, cache);
  const fs::path a = fs::path(dir.path()) / "A", b = fs::path(dir.path()) / "B";
  const fw::host::RunSummary whole = run_to_end(*cc, run, a);
  REQUIRE(whole.steps > 10);
  fs::copy(a, b, fs::copy_options::recursive);

  const auto checkpoints = fw::host::RunCheckpoints::list(b / "checkpoints");
  REQUIRE(checkpoints.size() >= 3);  // 6 s at 1.5 s, and the end
  // check's size prediction of a checkpoint (host/app/OutputSize) holds within the 15%.
  const fw::host::OutputSize size = fw::host::predict_output_size(run.plan, run.plan.end_time);
  const auto row = std::find_if(size.rows.begin(), size.rows.end(),
                                [](const fw::host::OutputSizeRow& r) { return r.path == "checkpoints"; });
  REQUIRE(row != size.rows.end());
  CHECK(row->files == int(checkpoints.size()));
  for (const auto& [step, folder] : checkpoints)
    CHECK(double(fs::file_size(folder / "rank_0000.fwcheck")) ==
          Approx(double(row->per_frame)).epsilon(0.15));
  const auto middle = std::next(checkpoints.begin(), long((checkpoints.size() - 1) / 2));
  fw::host::CheckpointParts read = fw::host::read_checkpoint(middle->second, fw::host::Communicator::alone(),
                                                             run.plan.decomposition.describe());
  REQUIRE(read.own);  // the same process and block: its own part
  const fw::host::RunSnapshot& from = read.any();
  REQUIRE(from.step == middle->first);
  REQUIRE(from.time > 0.0);
  const fw::host::RunSummary resumed = run_to_end(*cc, run, b, &read);
  CHECK(resumed.steps == whole.steps);
  // The same checkpoint taken apart and put together again (host/app/CheckpointRedistribution, as a run
  // over other ranks does) into a new folder: the frames after the checkpoint, byte for byte.
  const fs::path c = fs::path(dir.path()) / "C";
  read.own = false;
  run_to_end(*cc, run, c, &read);

  const std::vector<std::string> files = check_same_output(a, b);
  for (const std::string& file : files) {
    INFO(file);
    if (fs::exists(c / file) && !file.ends_with(".pvd") && file != "probes.csv") {
      const bool same_redistributed = output_bytes(c, file) == output_bytes(b, file);
      CHECK(same_redistributed);
    }
  }
  // The new folder's probes.csv holds the rows after the checkpoint: the last rows of the whole run's.
  const std::string whole_probes = fw::test::file_text(a / "probes.csv"),
                    redistributed_probes = fw::test::file_text(c / "probes.csv");
  const std::size_t header = redistributed_probes.find('\n') + 1;
  REQUIRE(redistributed_probes.size() > header);
  CHECK(whole_probes.ends_with(redistributed_probes.substr(header)));
  // run.json lists the two segments: up to the checkpoint, and from it to the end.
  const std::string segments = fw::test::file_text(b / "run.json");
  CHECK(segments.find("\"status\":\"stopped\"") != std::string::npos);
  CHECK(segments.find(fmt::format("\"end_step\":{}", from.step)) != std::string::npos);
  return {from.time, fw::test::file_text(a / "probes.csv")};
}

// The leaves flying at time t (s) in a probes.csv with leaf counts: its last row at or before t.
long flying_at(const std::string& probes, double t) {
  std::istringstream in(probes);
  std::string line, header;
  std::getline(in, header);
  const auto columns = [](const std::string& row) {
    std::vector<std::string> cells;
    std::stringstream cells_in(row);
    for (std::string cell; std::getline(cells_in, cell, ',');) cells.push_back(cell);
    return cells;
  };
  const std::vector<std::string> names = columns(header);
  const auto flying = std::find(names.begin(), names.end(), "leaves_flying");
  REQUIRE(flying != names.end());
  long count = -1;
  while (std::getline(in, line)) {
    const std::vector<std::string> cells = columns(line);
    if (std::stod(cells[0]) > t) break;
    count = std::stol(cells[std::size_t(flying - names.begin())]);
  }
  return count;
}

}  // namespace

TEST_CASE("RunCheckpoint: laminar flow past obstacles, with a gust halfway through, resumes bit for bit",
          "[simulation][checkpoint]") {
  // The gust blows from 1.5 s to 4.5 s: the checkpoint in the middle of the run falls inside it.
  const Resumed resumed = check_resumes_bit_for_bit(scenario(
      "wind: {speed: 6.0, direction: 270.0, reference_height: 10.0, profile: {type: uniform}}\n"
      "events:\n  - gust: {start: 1.5, duration: 3.0, peak_speed: 8.0, center: [30, 24, 10], radius: 12.0,"
      " travel: with_wind}\n"
      "obstacles:\n  - box: {name: barn, center: [50, 20, 6], size: [10, 8, 12], yaw: 20.0}\n"
      "  - cylinder: {name: silo, base: [70, 34, 0], radius: 3.0, height: 14.0}\n"
      "solver: {advection: semi_lagrangian}\n"));
  if (resumed.time > 0.0) CHECK((resumed.time > 1.5 && resumed.time < 4.5));
}

TEST_CASE(
    "RunCheckpoint: turbulent inflow with MacCormack or upwind5 and Smagorinsky, trees under Stam's forcing "
    "and leaves shedding and in flight, resumes bit for bit",
    "[simulation][checkpoint]") {
  const std::string advection = GENERATE(as<std::string>{}, "maccormack", "upwind5");
  INFO(advection);
  const Resumed resumed = check_resumes_bit_for_bit(scenario(turbulent_stand_with_leaves(advection)));
  // Leaves are in the air when the checkpoint is taken: their flight state goes through it.
  if (resumed.time > 0.0) CHECK(flying_at(resumed.probes, resumed.time) > 0);
}

TEST_CASE(
    "RunCheckpoint: a periodic canopy held by the mean forcing, upwind5 and the tke model, resumes bit "
    "for bit",
    "[simulation][checkpoint]") {
  check_resumes_bit_for_bit(
      "boundaries: {west: periodic, east: periodic, south: periodic, north: periodic, ground: rough, top: "
      "slip,"
      " roughness_length: 0.1}\n" +
      scenario("wind: {speed: 6.0, direction: 250.0, reference_height: 16.0,"
               " profile: {type: log, roughness_length: 0.5, displacement_height: 4.0},\n"
               "       turbulence: {intensity: 0.15, length_scale: 12.0}, forcing: {relaxation_time: 5.0}}\n"
               "solver: {pressure: cg, tolerance: 1.0e-3, advection: upwind5, subgrid: tke}\n" +
               stand()));
}

TEST_CASE("RunCheckpoint: a finished run extended to twice its end is bit for bit the run to that end",
          "[simulation][checkpoint]") {
  auto* cc = fw::test::device_or_skip();
  if (!cc) return;
  // 3 s: a multiple of the checkpoint interval, so that the interval's checkpoint falls due on the cut
  // step too, which must not be the one kept.
  constexpr double kEnd = 3.0;
  TempDir dir("fw_extend");
  fw::trees::BasisCache cache(fs::path(dir.path()) / "cache");
  const std::string body = turbulent_stand_with_leaves("upwind5");
  const Run shorter = plan_run(dir, scenario(body, kEnd), cache);
  const Run longer = plan_run(dir, scenario(body, 2 * kEnd), cache);
  const fs::path extended = fs::path(dir.path()) / "extended", whole = fs::path(dir.path()) / "whole";
  run_to_end(*cc, shorter, extended);
  // dt: auto does not land on the end: the last step was cut, and the end's checkpoint holds the state
  // before it.
  const auto checkpoints = fw::host::RunCheckpoints::list(extended / "checkpoints");
  REQUIRE(!checkpoints.empty());
  fw::host::CheckpointParts read = fw::host::read_checkpoint(
      checkpoints.rbegin()->second, fw::host::Communicator::alone(), longer.plan.decomposition.describe());
  const fw::host::RunSnapshot& end = read.any();
  REQUIRE(end.progress.reached_end.has_value());
  CHECK(*end.progress.reached_end == kEnd);
  CHECK(end.time < kEnd);
  run_to_end(*cc, longer, extended, &read);
  run_to_end(*cc, longer, whole);
  check_same_output(whole, extended);
}
