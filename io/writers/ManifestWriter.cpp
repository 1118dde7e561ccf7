#include "io/writers/ManifestWriter.hpp"

#include <fmt/format.h>

#include <utility>

#include "base/AtomicFile.hpp"
#include "base/Fnv1a.hpp"
#include "io/JsonWriter.hpp"

namespace fw::io {

ManifestWriter::ManifestWriter(std::filesystem::path directory, RunManifest manifest)
    : directory_(std::move(directory)), manifest_(std::move(manifest)) {}

void ManifestWriter::begin() {
  std::filesystem::create_directories(directory_);
  if (!manifest_.scenario_file_name.empty())
    base::write_text_atomically("ManifestWriter", directory_ / manifest_.scenario_file_name,
                                manifest_.scenario_text);
  // Until finish() replaces it, run.json says the run has not finished: what a folder killed midway keeps.
  RunOutcome running;
  running.status = kRunningStatus;
  write_run_json(running);
}

void ManifestWriter::write(const OutputFrame& frame) {
  if (!manifest_.leaves) return;
  leaf_counts_ = frame.leaves.counts;
  leaf_counts_time_ = frame.time;
}

void ManifestWriter::finish(const RunOutcome& outcome) {
  write_run_json(outcome);
}

void ManifestWriter::write_run_json(const RunOutcome& outcome) const {
  const RunManifest& m = manifest_;
  JsonWriter json;
  json.begin_object();
  json.key("version").value(m.version);
  json.key("scenario").value(m.scenario_name);
  json.key("scenario_file").value(m.scenario_file_name);
  json.key("scenario_hash").value(base::fnv1a_hex(m.scenario_text));
  json.key("seed").value(m.seed);
  json.key("device").value(m.device);
  json.key("platform").value(m.platform);
  json.key("status").value(outcome.status);
  if (!outcome.message.empty()) json.key("message").value(outcome.message);
  json.key("grid").values(m.grid);
  json.key("cell_size_m").value(m.cell_size);
  if (m.site) {
    // Local coordinates are metres from the domain's corner; origin + local is the site's CRS.
    json.key("site").begin_object();
    json.key("crs");
    if (const auto& crs = m.site->crs) {
      json.begin_object();
      json.key("name").value(crs->name);
      json.key("epsg");
      if (crs->epsg)
        json.value(*crs->epsg);
      else
        json.null();
      json.key("wkt").value(crs->wkt);
      json.end_object();
    } else {
      json.null();
    }
    json.key("origin").values(m.site->origin);
    json.key("raster").value(m.site->raster.filename().string());
    json.end_object();
  }
  json.key("trees").value(m.trees);
  json.key("species").begin_array();
  for (const SpeciesSummary& s : m.species) {
    json.begin_object();
    json.key("name").value(s.name);
    json.key("dynamics").value(s.dynamics);
    json.key("nodes").value(s.nodes);
    json.key("modes").value(s.modes);
    json.key("wind_samples").value(s.samples);
    json.key("trees").value(s.trees);
    json.key("first_hz").value(s.first_hz);
    json.key("cache").value(s.cache);
    json.end_object();
  }
  json.end_array();
  json.key("two_way_coupling").value(m.two_way_coupling);
  json.key("ranks").value(m.ranks);
  if (m.ranks > 1) json.key("decomposition").value(m.decomposition);
  json.key("steps").value(std::int64_t(outcome.steps));
  json.key("simulated_time_s").value(outcome.simulated_time);
  json.key("frames").value(outcome.frames);
  json.key("interrupted").value(outcome.status == "interrupted");
  json.key("wall_seconds").value(outcome.wall_seconds);
  // The spin-up's steps are not the run's: neither they nor their wall time count per step.
  const double steps_wall = outcome.wall_seconds - outcome.spin_up_wall_seconds;
  json.key("ms_per_step").value(outcome.steps > 0 ? steps_wall * 1e3 / double(outcome.steps) : 0.0);
  json.key("spin_up").begin_object();
  json.key("seconds").value(outcome.spin_up_seconds);
  json.key("steps").value(std::int64_t(outcome.spin_up_steps));
  json.key("wall_seconds").value(outcome.spin_up_wall_seconds);
  json.end_object();
  json.key("stages_ms").object(outcome.stage_ms);
  if (!outcome.segments.empty()) {
    json.key("segments").begin_array();
    for (const RunSegment& segment : outcome.segments) {
      json.begin_object();
      json.key("start_time_s").value(segment.start_time);
      json.key("end_time_s").value(segment.end_time);
      json.key("start_step").value(std::int64_t(segment.start_step));
      json.key("end_step").value(std::int64_t(segment.end_step));
      json.key("wall_seconds").value(segment.wall_seconds);
      json.key("status").value(segment.status);
      json.end_object();
    }
    json.end_array();
  }
  if (m.leaves) {
    json.key("leaves");
    if (leaf_counts_) {
      const trees::LeafCounts& n = *leaf_counts_;
      json.begin_object();
      json.key("shed").value(std::int64_t(n.shed));
      json.key("flying").value(std::int64_t(n.flying));
      json.key("landed").value(std::int64_t(n.landed));
      json.key("exited").value(std::int64_t(n.exited));
      json.key("attached").value(std::int64_t(n.attached));
      json.key("time_s").value(leaf_counts_time_);
      json.end_object();
    } else {
      json.null();  // no frame was written: no counts to report
    }
  }
  if (m.damage) {
    json.key("damage");
    if (!outcome.damage.empty()) {
      trees::DamageCounts n;
      for (const trees::TreeDamageRecord& r : outcome.damage) {
        n.standing += r.state == trees::TreeState::standing;
        n.broken += r.state == trees::TreeState::broken;
        n.overturned += r.state == trees::TreeState::overturned;
      }
      json.begin_object();
      json.key("standing").value(std::int64_t(n.standing));
      json.key("broken").value(std::int64_t(n.broken));
      json.key("overturned").value(std::int64_t(n.overturned));
      json.key("time_s").value(outcome.simulated_time);
      json.end_object();
    } else {
      json.null();  // still running, or a failure left the records out of reach: damage.csv has the last
    }
  }
  json.end_object();
  base::write_text_atomically("ManifestWriter", directory_ / "run.json", json.str() + "\n");
}

}  // namespace fw::io
