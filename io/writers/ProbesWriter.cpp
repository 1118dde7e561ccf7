#include "io/writers/ProbesWriter.hpp"

#include <utility>

namespace fw::io {

ProbesWriter::ProbesWriter(std::filesystem::path directory, std::vector<std::string> probe_names,
                           std::vector<int> tip_trees, CountColumns counts)
    : directory_(std::move(directory)),
      probe_names_(std::move(probe_names)),
      tip_trees_(std::move(tip_trees)),
      counts_(counts) {}

void ProbesWriter::begin() {
  csv_.emplace(directory_ / "probes.csv", probe_names_, tip_trees_, ProbesCsv::kDefaultRewriteLimit, counts_);
}

void ProbesWriter::resume(const OutputResume& resume) {
  csv_.emplace(ProbesCsv::continued(directory_ / "probes.csv", probe_names_, tip_trees_,
                                    std::size_t(resume.probe_samples), ProbesCsv::kDefaultRewriteLimit,
                                    counts_));
}

void ProbesWriter::check_resume(const OutputResume& resume) const {
  ProbesCsv::check_continuable(directory_ / "probes.csv", probe_names_, tip_trees_,
                               std::size_t(resume.probe_samples), counts_);
}

void ProbesWriter::write(const OutputFrame& frame) {
  std::vector<ProbesCsv::Row> rows;
  rows.reserve(frame.probe_samples.size());
  for (const ProbeSample& sample : frame.probe_samples)
    rows.push_back({sample.time, &sample.wind, &sample.tips, &sample.leaf_counts, &sample.damage_counts});
  csv_->append_rows(rows);
}

}  // namespace fw::io
