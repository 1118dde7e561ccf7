// The forest's part of the plan: the tree instances (the stands first, in file order, then the single
// trees), each standing on the ground under it (the terrain's height, else the domain floor) unless the file
// gives z, turned counter-clockwise about +z by its yaw; the trees and leaves per species; and the device
// memory of the trees' and the leaves' stages.
#include <fmt/format.h>

#include <algorithm>
#include <stdexcept>

#include "host/app/plan/PlanBuilders.hpp"
#include "host/stages/ForestStages.hpp"
#include "host/stages/LeafStages.hpp"
#include "trees/ForestLayout.hpp"

namespace fw::host {

namespace {

double ground_z(const io::Scenario& scenario, double x, double y) {
  double z = scenario.domain.origin[2];
  if (scenario.terrain && scenario.terrain->map) z += scenario.terrain->map->height_at(x, y);
  return z;
}

std::vector<trees::TreeInstance> place_instances(const io::Scenario& scenario) {
  std::vector<trees::TreeInstance> instances;
  for (const io::Stand& stand : scenario.forest.stands) {
    for (const trees::PlacedTree& placed : trees::place_stand(stand.layout)) {
      const double x = placed.position.x(), y = placed.position.y();
      instances.push_back({placed.species, {x, y, ground_z(scenario, x, y)}, placed.yaw_rad, placed.scale});
    }
  }
  for (const io::PlacedTreeSettings& placed : scenario.forest.trees) {
    const auto& p = placed.position;
    const double z = placed.height_given ? p[2] : ground_z(scenario, p[0], p[1]);
    instances.push_back({placed.species_index, {p[0], p[1], z}, placed.yaw_rad, placed.scale});
  }
  return instances;
}

}  // namespace

void plan_forest(const io::Scenario& scenario, std::vector<trees::SpeciesBasis> bases, SimulationPlan& plan) {
  std::vector<trees::TreeInstance> instances = place_instances(scenario);
  for (const auto& tree : instances) {
    ++plan.species[std::size_t(tree.species)].trees;
    plan.leaf_count += plan.coupling.leaves[std::size_t(tree.species)].count();
  }
  plan.forest = trees::Forest(std::move(bases), std::move(instances));
  if (plan.forest.instance_count() == 0) return;
  plan.memory.add("trees", ForestStages::estimate_device_bytes(plan.forest));
  if (plan.leaf_count == 0) return;
  if (plan.leaf_count > LeafStages::kMaxLeaves)
    throw std::invalid_argument(fmt::format(
        "{}: forest: {} leaves on all trees, more than the {} the leaf stage holds; lower a species' "
        "leaves.fraction or canopy.leaf_area_index",
        scenario.file.string(), plan.leaf_count, LeafStages::kMaxLeaves));
  plan.memory.add("leaves", LeafStages::estimate_device_bytes(plan.forest, plan.coupling.leaves));
}

}  // namespace fw::host
