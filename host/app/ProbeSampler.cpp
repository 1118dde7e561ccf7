#include "host/app/ProbeSampler.hpp"

#include <algorithm>
#include <cmath>

namespace fw::host {

int tip_node(const trees::Skeleton& skeleton) {
  int tip = 0;
  for (int n = 1; n < skeleton.size(); ++n) {
    if (skeleton.node(n).position.z() > skeleton.node(tip).position.z()) tip = n;
  }
  return tip;
}

ProbeSampler::ProbeSampler(ComputeContext& cc, const fluid::GridSpec& spec,
                           const std::vector<std::array<double, 3>>& points, const trees::Forest& forest,
                           int tip_trees, bool strong_wind_correction)
    : cc_(cc), points_(cc, spec, points), forest_(forest), strong_wind_correction_(strong_wind_correction) {
  for (int k = 0; k < std::min(tip_trees, forest.instance_count()); ++k) {
    tip_trees_.push_back(k);
    tip_nodes_.push_back(tip_node(forest.species_of(k).skeleton()));
  }
}

io::ProbeSample ProbeSampler::sample(CoupledStep& coupled) {
  io::ProbeSample out;
  out.time = coupled.time();
  out.wind = points_.sample(coupled.wind().velocity());
  for (std::size_t t = 0; t < tip_trees_.size(); ++t) {
    const int k = tip_trees_[t];
    const trees::SpeciesBasis& species = forest_.species_of(k);
    const int modes = species.modes().mode_count();
    // The state holds (q, qdot) per flat mode.
    std::vector<float> state(2 * std::size_t(modes));
    cc_.queue().enqueueReadBuffer(coupled.trees().state(), CL_TRUE,
                                  2 * std::size_t(forest_.mode_offset(k)) * sizeof(float),
                                  state.size() * sizeof(float), state.data());
    Eigen::VectorXd q(modes);
    for (int i = 0; i < modes; ++i) q(i) = state[2 * std::size_t(i)];
    // The whole tree: the strong-wind correction's length pass walks it from the root.
    const Eigen::Vector3d world =
        forest_.instance_displacements(k, q, strong_wind_correction_).row(tip_nodes_[t]).transpose();
    out.tips.push_back({world.x(), world.y(), world.z()});
  }
  if (coupled.has_leaves()) out.leaf_counts = coupled.leaves().counts();
  return out;
}

}  // namespace fw::host
