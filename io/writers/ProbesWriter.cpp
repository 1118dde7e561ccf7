#include "io/writers/ProbesWriter.hpp"

#include <algorithm>
#include <utility>

#include "io/WindFrame.hpp"

namespace fw::io {

int tip_node(const trees::Skeleton& skeleton) {
  int tip = 0;
  for (int n = 1; n < skeleton.size(); ++n) {
    if (skeleton.node(n).position.z() > skeleton.node(tip).position.z()) tip = n;
  }
  return tip;
}

ProbesWriter::ProbesWriter(std::filesystem::path directory, fluid::GridSpec spec,
                           std::vector<ProbePoint> probes, const trees::Forest& forest, int tip_trees)
    : directory_(std::move(directory)), spec_(std::move(spec)), probes_(std::move(probes)) {
  for (int k = 0; k < std::min(tip_trees, forest.instance_count()); ++k) {
    tip_trees_.push_back(k);
    tip_nodes_.push_back(std::size_t(forest.node_offset(k)) +
                         std::size_t(tip_node(forest.species_of(k).skeleton())));
  }
}

void ProbesWriter::begin() {
  std::vector<std::string> names;
  for (const auto& probe : probes_) names.push_back(probe.name);
  csv_.emplace(directory_ / "probes.csv", names, tip_trees_);
}

void ProbesWriter::write(const OutputFrame& frame) {
  std::vector<std::array<float, 3>> velocity;
  for (const auto& probe : probes_)
    velocity.push_back(sample_velocity(spec_, frame.velocity, probe.position));
  std::vector<std::array<double, 3>> tips;
  for (std::size_t node : tip_nodes_) {
    tips.push_back({frame.displacement.at(3 * node), frame.displacement.at(3 * node + 1),
                    frame.displacement.at(3 * node + 2)});
  }
  csv_->append(frame.time, velocity, tips);
}

}  // namespace fw::io
