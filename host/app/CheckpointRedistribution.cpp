#include "host/app/CheckpointRedistribution.hpp"

#include <fmt/format.h>

#include <stdexcept>

#include "host/runtime/Communicator.hpp"
#include "host/stages/SavedStateNames.hpp"

namespace fw::host {

namespace {

// Every part's `stage`, with the rank's block and trees: what the stage takes its share from.
std::vector<SavedShare> shares_of(const std::vector<RunSnapshot>& parts, const char* stage) {
  std::vector<SavedShare> shares;
  for (const RunSnapshot& part : parts) {
    const auto at = part.stages.find(stage);
    if (at == part.stages.end())
      throw std::invalid_argument(
          fmt::format("checkpoint: a part has no {} stage: it is another run's", stage));
    shares.push_back({&at->second, part.block, part.tree_ids});
  }
  return shares;
}

}  // namespace

RunSnapshot redistribute_checkpoint(const std::vector<RunSnapshot>& parts, CoupledStep& coupled,
                                    const SimulationPlan& plan) {
  if (parts.empty()) throw std::invalid_argument("checkpoint: no parts to redistribute");
  const RunSnapshot& first = parts.front();
  RunSnapshot mine;
  mine.time = first.time;
  mine.step = first.step;
  mine.progress = first.progress;
  mine.state_keys = first.state_keys;
  mine.ranks = plan.decomposition.ranks();
  mine.decomposition = plan.decomposition.describe();
  mine.block = coupled.wind().block();
  const trees::Forest& own = coupled.own_forest();
  for (int k = 0; k < own.instance_count(); ++k) mine.tree_ids.push_back(own.id(k));
  // Each stage takes its share of what every part saved.
  mine.stages[saved::kWindStage] = coupled.wind().share_of(shares_of(parts, saved::kWindStage));
  if (first.stages.count(saved::kTreesStage) > 0)
    mine.stages[saved::kTreesStage] = ForestStages::share_of(shares_of(parts, saved::kTreesStage),
                                                             plan.forest, plan.coupling.dynamics, own);
  if (first.stages.count(saved::kLeavesStage) > 0) {
    const auto leaves_of = [&](int id) {
      const int species = plan.forest.instances()[std::size_t(id)].species;
      return std::size_t(plan.coupling.leaves[std::size_t(species)].count());
    };
    // One rank takes the leaf counters' totals: rank 0, whose counts every rank's are summed with anyway.
    const WindBlocks* blocks = coupled.blocks();
    const bool takes_counters = blocks == nullptr || blocks->world->rank() == 0;
    mine.stages[saved::kLeavesStage] =
        LeafStages::share_of(shares_of(parts, saved::kLeavesStage), plan.wind.spec, mine.block, own,
                             plan.forest.instance_count(), leaves_of, takes_counters);
  }
  return mine;
}

}  // namespace fw::host
