// Probe samples at their own interval (docs/design.md, "probes.csv"): the wind at the scenario's probe points
// and the tip displacement of the first trees, taken from the device without copying the grid or the forest
// back. Spectra need many more samples than output frames give.
//
//   fw::host::ProbeRecorder probes(cc, plan.wind.spec, {{40, 120, 10}}, plan.forest, /*tip_trees=*/4,
//                                /*strong_wind_correction=*/true);
//   fw::io::ProbeSample s = probes.sample(coupled);   // s.wind[p] m/s, s.tips[t] m, at coupled.time()
//
// A tip is the highest node of the tree's skeleton; its displacement is the one the trees' VTK frames show
// (trees::Forest::instance_displacements, with or without the strong-wind correction), from the
// tree's modal coordinates read back (2 m floats a tree).
//
// Over MPI ranks (docs/parallel.md) the rank whose block holds a probe samples it
// (host/stages/PointWindAcrossRanks) and the rank that holds a tracked tree computes its tip; both go to rank
// 0, whose sample is the one written. sample() is then collective.
#pragma once

#include <array>
#include <optional>
#include <vector>

#include "fluid/GridSpec.hpp"
#include "host/app/CoupledStep.hpp"
#include "host/stages/PointWindAcrossRanks.hpp"
#include "io/writers/FrameWriter.hpp"
#include "trees/BranchElements.hpp"
#include "trees/Forest.hpp"

namespace fw::host {

/// The highest node of a skeleton: the tree's tip.
int tip_node(const trees::Skeleton& skeleton);

class ProbeRecorder {
 public:
  /// points: probe positions, m, world frame; tip_trees: how many of the first instances (Forest::id 0, 1,
  /// ...) of the whole forest of `all_trees` trees are tracked (fewer when it is smaller). `coupled` is the
  /// step it samples, over its ranks when it has blocks (its own_forest() must outlive the sampler).
  ProbeRecorder(ComputeContext& cc, CoupledStep& coupled, const std::vector<std::array<double, 3>>& points,
                int all_trees, int tip_trees, bool strong_wind_correction);

  /// The instance ids whose tips are tracked, in column order.
  const std::vector<int>& tip_trees() const { return tip_trees_; }
  bool empty() const { return point_count_ == 0 && tip_trees_.empty(); }
  /// One sample of the coupled state now (blocks for a few floats).
  io::ProbeSample sample(CoupledStep& coupled);

 private:
  /// The tips of the tracked trees this rank holds: (id, x, y, z) each, m.
  std::vector<double> own_tips(CoupledStep& coupled) const;

  ComputeContext& cc_;
  const Communicator* world_;
  int point_count_ = 0;
  PointWindAcrossRanks points_;  // rank 0 asks for every probe
  const trees::Forest& forest_;  // this rank's trees
  bool strong_wind_correction_ = true;
  std::vector<int> tip_trees_;             // ids, in column order
  std::vector<int> own_tips_, tip_nodes_;  // of this rank's tracked trees: the index in forest_, the tip node
  // Of the same trees moved by an element model, their element table (trees/BranchPose's input); else empty.
  std::vector<std::optional<trees::BranchElements>> tip_elements_;
};

}  // namespace fw::host
