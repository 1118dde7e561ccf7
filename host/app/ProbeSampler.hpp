// Probe samples at their own interval (docs/design.md, "probes.csv"): the wind at the scenario's probe points
// and the tip displacement of the first trees, taken from the device without copying the grid or the forest
// back. Spectra need many more samples than output frames give.
//
//   fw::host::ProbeSampler probes(cc, plan.wind.spec, {{40, 120, 10}}, plan.forest, /*tip_trees=*/4,
//                                /*strong_wind_correction=*/true);
//   fw::io::ProbeSample s = probes.sample(coupled);   // s.wind[p] m/s, s.tips[t] m, at coupled.time()
//
// A tip is the highest node of the tree's skeleton; its displacement is the one the trees' VTK frames show
// (trees::Forest::instance_displacements, with or without the strong-wind correction), from the
// tree's modal coordinates read back (2 m floats a tree).
#pragma once

#include <array>
#include <vector>

#include "fluid/GridSpec.hpp"
#include "host/app/CoupledStep.hpp"
#include "host/stages/PointSampler.hpp"
#include "io/writers/FrameWriter.hpp"
#include "trees/Forest.hpp"

namespace fw::host {

/// The highest node of a skeleton: the tree's tip.
int tip_node(const trees::Skeleton& skeleton);

class ProbeSampler {
 public:
  /// points: probe positions, m, world frame; tip_trees: how many of the first instances are tracked (fewer
  /// when the forest is smaller). Keeps a reference to `forest`, which must outlive the sampler.
  ProbeSampler(ComputeContext& cc, const fluid::GridSpec& spec,
               const std::vector<std::array<double, 3>>& points, const trees::Forest& forest, int tip_trees,
               bool strong_wind_correction);

  /// The instance ids whose tips are tracked, in column order.
  const std::vector<int>& tip_trees() const { return tip_trees_; }
  bool empty() const { return points_.point_count() == 0 && tip_trees_.empty(); }
  /// One sample of the coupled state now (blocks for a few floats).
  io::ProbeSample sample(CoupledStep& coupled);

 private:
  ComputeContext& cc_;
  PointSampler points_;
  const trees::Forest& forest_;
  bool strong_wind_correction_ = true;
  std::vector<int> tip_trees_, tip_nodes_;
};

}  // namespace fw::host
