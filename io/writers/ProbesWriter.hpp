// probes.csv: the wind at named points and the tip displacement of the first trees, one row per frame
// (io/ProbesCsv.hpp has the columns).
//
//   fw::io::ProbesWriter probes("out/storm", spec, {{"mast", {40, 120, 10}}}, forest, /*tip_trees=*/4);
#pragma once

#include <array>
#include <filesystem>
#include <optional>
#include <string>
#include <vector>

#include "fluid/GridSpec.hpp"
#include "io/ProbesCsv.hpp"
#include "io/writers/FrameWriter.hpp"
#include "trees/Forest.hpp"

namespace fw::io {

struct ProbePoint {
  std::string name;
  std::array<double, 3> position{};  ///< m, world frame
};

/// The highest node of a skeleton: the tree's tip.
int tip_node(const trees::Skeleton& skeleton);

class ProbesWriter : public FrameWriter {
 public:
  /// tip_trees: how many of the first instances get tip columns (fewer when the forest is smaller).
  ProbesWriter(std::filesystem::path directory, fluid::GridSpec spec, std::vector<ProbePoint> probes,
               const trees::Forest& forest, int tip_trees);

  std::string name() const override { return "probes"; }
  FrameNeeds needs() const override {
    return {.velocity = !probes_.empty(), .displacement = !tip_nodes_.empty()};
  }
  void begin() override;
  void write(const OutputFrame& frame) override;

 private:
  std::filesystem::path directory_;
  fluid::GridSpec spec_;
  std::vector<ProbePoint> probes_;
  std::vector<int> tip_trees_;
  std::vector<std::size_t> tip_nodes_;  ///< flat forest node index of each tip
  std::optional<ProbesCsv> csv_;
};

}  // namespace fw::io
