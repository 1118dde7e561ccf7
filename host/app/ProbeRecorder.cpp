#include "host/app/ProbeRecorder.hpp"

#include "trees/BranchPose.hpp"

#include "host/runtime/Communicator.hpp"

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

namespace {

// Rank 0 asks for every probe's wind, the other ranks for none.
std::vector<float> asked_points(const std::vector<std::array<double, 3>>& points, const Communicator& world) {
  return world.rank() == 0 ? PointWindReadback::flat_positions(points) : std::vector<float>{};
}

const Communicator& world_of(const WindBlocks* blocks) {
  return blocks != nullptr ? *blocks->world : Communicator::alone();
}

}  // namespace

ProbeRecorder::ProbeRecorder(ComputeContext& cc, CoupledStep& coupled,
                             const std::vector<std::array<double, 3>>& points, int all_trees, int tip_trees,
                             bool strong_wind_correction)
    : cc_(cc),
      world_(&world_of(coupled.blocks())),
      point_count_(int(points.size())),
      points_(cc, coupled.wind().local_spec(), coupled.blocks(), asked_points(points, *world_)),
      forest_(coupled.own_forest()),
      strong_wind_correction_(strong_wind_correction) {
  for (int id = 0; id < std::min(tip_trees, all_trees); ++id) tip_trees_.push_back(id);
  for (int k = 0; k < forest_.instance_count(); ++k) {
    if (forest_.id(k) >= int(tip_trees_.size())) continue;
    own_tips_.push_back(k);
    tip_nodes_.push_back(tip_node(forest_.species_of(k).skeleton()));
    const BranchStages* branches = coupled.trees().branches();
    const trees::SpeciesBasis& basis = forest_.species_of(k);
    tip_elements_.push_back(branches != nullptr && branches->entry_offset(k) >= 0
                                ? std::optional(trees::BranchElements::of(
                                      basis.skeleton(), basis.settings().material, basis.settings().wind))
                                : std::nullopt);
  }
}

std::vector<double> ProbeRecorder::own_tips(CoupledStep& coupled) const {
  std::vector<double> tips;
  for (std::size_t t = 0; t < own_tips_.size(); ++t) {
    const int k = own_tips_[t];
    if (tip_elements_[t]) {
      // An element model's tree: its pose from its joints (trees/BranchPose, as the device's frames).
      const trees::BranchElements& elements = *tip_elements_[t];
      const double scale = forest_.instances()[std::size_t(k)].scale;
      const Eigen::Vector3d world =
          forest_.rotation(k) *
          trees::branch_displacements(elements, scale,
                                      coupled.trees().branches()->download_angles(k, elements.size()))
              .row(tip_nodes_[t])
              .transpose();
      tips.insert(tips.end(), {double(forest_.id(k)), world.x(), world.y(), world.z()});
      continue;
    }
    const int modes = forest_.species_of(k).modes().mode_count();
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
    tips.insert(tips.end(), {double(forest_.id(k)), world.x(), world.y(), world.z()});
  }
  return tips;
}

io::ProbeSample ProbeRecorder::sample(CoupledStep& coupled) {
  io::ProbeSample out;
  out.time = coupled.time();
  const std::vector<float> wind = points_.exchange(coupled.wind().velocity());
  for (std::size_t p = 0; p + 2 < wind.size(); p += 3)
    out.wind.push_back({wind[p], wind[p + 1], wind[p + 2]});
  // Every rank's tracked tips go to rank 0, which puts them in column (id) order.
  const std::vector<double> tips = joined(world_->gather(own_tips(coupled)));
  out.tips.resize(world_->rank() == 0 ? tip_trees_.size() : 0);
  for (std::size_t at = 0; at + 3 < tips.size(); at += 4)
    out.tips[std::size_t(tips[at])] = {tips[at + 1], tips[at + 2], tips[at + 3]};
  if (coupled.has_leaves()) out.leaf_counts = coupled.leaves().counts();
  out.damage_counts = coupled.damage_counts();
  return out;
}

}  // namespace fw::host
