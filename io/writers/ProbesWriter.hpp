// probes.csv: the wind at named points and the tip displacement of the first trees, one row per probe
// sample (io/ProbesCsv.hpp has the columns). The samples are taken by the run loop at the probes' own
// interval (host/app/ProbeRecorder) and reach this writer in batches, with each frame. In runs with leaves
// each sample's leaf counts (ProbeSample::leaf_counts) follow as four more columns, in runs with storm damage
// its tree counts (ProbeSample::damage_counts) as three more.
//
//   fw::io::ProbesWriter probes("out/storm", {"mast", "edge"}, /*tip_trees=*/{0, 1, 2, 3});
//   fw::io::ProbesWriter probes("out/storm", {"mast"}, {0}, {.leaves = true});
#pragma once

#include <filesystem>
#include <optional>
#include <string>
#include <vector>

#include "io/ProbesCsv.hpp"
#include "io/writers/FrameWriter.hpp"

namespace fw::io {

class ProbesWriter : public FrameWriter {
 public:
  /// probe_names: the columns' probe names; tip_trees: the instance ids whose tip columns follow;
  /// counts: the count columns to add (a run with leaves, with damage).
  ProbesWriter(std::filesystem::path directory, std::vector<std::string> probe_names,
               std::vector<int> tip_trees, CountColumns counts = {});

  std::string name() const override { return "probes"; }
  FrameNeeds needs() const override { return {.probe_samples = true}; }
  void begin() override;
  /// probes.csv keeps its header and the rows sampled up to the checkpoint (a new file in a new folder).
  void resume(const OutputResume& resume) override;
  void check_resume(const OutputResume& resume) const override;
  /// Appends frame.probe_samples (throws std::invalid_argument when a sample has the wrong counts).
  void write(const OutputFrame& frame) override;

 private:
  std::filesystem::path directory_;
  std::vector<std::string> probe_names_;
  std::vector<int> tip_trees_;
  CountColumns counts_;
  std::optional<ProbesCsv> csv_;
};

}  // namespace fw::io
