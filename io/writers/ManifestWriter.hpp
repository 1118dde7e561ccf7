// run.json and a copy of the scenario file: how the output folder was made and how the run went.
//
//   fw::io::ManifestWriter manifest("out/storm", info);   // begin() copies the scenario text
//   manifest.finish(outcome);                              // run.json: status, steps, timings per stage
//
// run.json keys: version, scenario, scenario_file, scenario_hash (64-bit FNV-1a of the scenario text), seed,
// device, platform, status ("running", "completed", "interrupted", "failed"), message (when failed), grid,
// cell_size_m, trees, species (name, dynamics, nodes, modes, wind_samples, trees, first_hz, cache),
// two_way_coupling, steps, simulated_time_s, frames, interrupted, wall_seconds, ms_per_step, "spin_up"
// ({seconds, steps, wall_seconds} of the wind's spin-up before t = 0, time.spin_up: not in steps, in
// wall_seconds, not in ms_per_step or stages_ms; zeros without one and in a resumed run, which does not spin
// up), stages_ms, "segments" (each with start_time_s, end_time_s, start_step, end_step, wall_seconds, status:
// one for a run never resumed; steps, frames and wall_seconds count every segment, stages_ms the last one),
// and in runs with leaves (RunManifest::leaves) "leaves": {shed, flying, landed, exited, attached, time_s},
// the counts over all leaves (docs/leaves.md, "States and counts") of the last frame written, at its time_s;
// null when no frame was written. It is written through AtomicFile when the run starts (or resumes), with
// status "running" and no steps, and again when the run ends: a folder whose run was killed (kill -9, a power
// cut) keeps status "running", which says the run did not finish.
#pragma once

#include <array>
#include <cstdint>
#include <filesystem>
#include <optional>
#include <string>
#include <vector>

#include "io/settings/SiteSettings.hpp"
#include "io/writers/FrameWriter.hpp"
#include "trees/LeafState.hpp"

namespace fw::io {

struct SpeciesSummary {
  std::string name;     ///< the forest species' name: the scenario's, or "NAME (stand K)" for a stand's basis
  std::string species;  ///< the scenario's species it is (forest.species[].name)
  std::string dynamics = "modal";  ///< the model that moves its trees (trees::dynamics_name)
  int nodes = 0;
  int modes = 0;
  int samples = 0;
  int trees = 0;                   ///< instances of this species
  double first_hz = 0.0;           ///< lowest natural frequency at scale 1
  std::string cache = "disabled";  ///< "hit", "miss", "corrupt_recomputed" or "disabled"
  double seconds = 0.0;            ///< time to obtain the basis (load or compute)
  /// The radii's factor of an inventory's girth class (trees/SizeFit.hpp); 1 for the species' own basis and
  /// a stand's.
  double girth = 1.0;
};

/// What run.json says about the run's set-up.
struct RunManifest {
  std::string version;
  std::string scenario_name;
  std::string scenario_file_name;  ///< the copy's name in the output folder
  std::string scenario_text;       ///< copied byte for byte; its hash goes to run.json
  std::uint64_t seed = 0;
  std::string device, platform;
  std::array<int, 3> grid{0, 0, 0};
  double cell_size = 0.0;  ///< m
  /// The site (docs/gis.md): the CRS and the domain's origin in it, to put the local results back.
  std::optional<SiteSettings> site;
  int trees = 0;
  std::vector<SpeciesSummary> species;
  bool two_way_coupling = false;
  bool leaves = false;        ///< the run has leaves: run.json reports their counts
  bool damage = false;        ///< the run checks its trees for damage: run.json reports the totals
  int ranks = 1;              ///< MPI ranks of the run (docs/parallel.md)
  std::string decomposition;  ///< their blocks (fluid::Decomposition::describe), over several ranks
};

/// run.json's status while the run goes on, and after a kill that gave it no time to say more.
inline constexpr const char* kRunningStatus = "running";

class ManifestWriter : public FrameWriter {
 public:
  ManifestWriter(std::filesystem::path directory, RunManifest manifest);

  std::string name() const override { return "run.json"; }
  /// The leaves' counts travel with every frame (LeafFrame::counts), the leaves themselves need not.
  FrameNeeds needs() const override { return {.leaf_counts = manifest_.leaves}; }
  /// Writes the scenario copy and run.json with status "running".
  void begin() override;
  /// Keeps the frame's leaf counts (runs with leaves).
  void write(const OutputFrame& frame) override;
  /// Writes run.json.
  void finish(const RunOutcome& outcome) override;

 private:
  void write_run_json(const RunOutcome& outcome) const;

  std::filesystem::path directory_;
  RunManifest manifest_;
  std::optional<trees::LeafCounts> leaf_counts_;  // of the last frame written
  double leaf_counts_time_ = 0.0;                 // s
};

}  // namespace fw::io
