// The forest's part of the plan: the tree instances (the stands first, in file order, then the single
// trees), each standing on the ground under it (the terrain's height, else the domain floor) unless the file
// gives z, turned counter-clockwise about +z by its yaw; the stands (plan.stands); the trees and leaves per
// species; and the device memory of the trees' and the leaves' stages.
//
// A stand that gives its own leaf area index gets a basis of its own (SpeciesBasis::with_leaf_area_index,
// appended after the scenario's species, with its leaves, its model and its summary): its species' with the
// crown leaf area index at which the stand's trees, as placed, carry that leaf area index over its region
// (trees/StandDensity.hpp). The species' own index stays for its other stands and its single trees.
//
// An inventory's trees come last, in file order (docs/gis.md): each is its species' template fitted to its
// height and dbh (trees/SizeFit.hpp), an instance of scale H / H_T of a girth class. A class other than the
// species' own girth gets a basis of its own (through the cache), appended after the stands', with the
// species' leaves, model and strength; `check` sums the classes up per species. An inventory gives no yaw:
// each tree turns by a yaw drawn uniformly from the scenario's seed, in file order, so that the trees of one
// template do not all face one way.
#include <fmt/format.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <map>
#include <numbers>
#include <random>
#include <stdexcept>
#include <utility>

#include "base/SourceError.hpp"
#include "host/app/plan/PlanBuilders.hpp"
#include "host/stages/ForestStages.hpp"
#include "host/stages/LeafStages.hpp"
#include "io/Scenario.hpp"
#include "io/ScenarioSchema.hpp"
#include "io/schema/Bounds.hpp"
#include "trees/Foliage.hpp"
#include "trees/ForestLayout.hpp"
#include "trees/SizeFit.hpp"
#include "trees/StandDensity.hpp"

namespace fw::host {

namespace {

double ground_z(const io::Scenario& scenario, double x, double y) {
  double z = scenario.domain.origin[2];
  if (scenario.terrain && scenario.terrain->map) z += scenario.terrain->map->height_at(x, y);
  return z;
}

// The stand's own basis (header comment), appended to `bases` with its leaves, model and summary; its index.
int stand_basis(const io::Scenario& scenario, std::size_t index, const std::vector<trees::PlacedTree>& placed,
                StandPlan& stand, std::vector<trees::SpeciesBasis>& bases, SimulationPlan& plan) {
  const auto start = std::chrono::steady_clock::now();
  const trees::SpeciesBasis& species = bases[std::size_t(stand.species_index)];
  const double crown_area = trees::Foliage::of(species.skeleton(), 1.0).crown_projected_area;
  const io::Stand& given = scenario.forest.stands[index];
  try {
    stand.crown_leaf_area_index =
        trees::crown_leaf_area_index(*stand.leaf_area_index, given.layout.ground_area(), crown_area, placed);
  } catch (const std::invalid_argument& error) {  // a species whose crown cannot carry leaves
    throw io::ScenarioError(
        scenario.file.string(), given.leaf_area_index_line,
        io::schema::item_path(
            io::schema::key(io::schema::kForestKeys, "forest.stands[].leaf_area_index").path, index),
        fmt::format("a stand of a species with a crown to carry the leaves expected ({}), got '{}'",
                    error.what(), *stand.leaf_area_index));
  }
  bases.push_back(species.with_leaf_area_index(stand.crown_leaf_area_index));
  const io::Species& given_species = scenario.forest.species[std::size_t(stand.species_index)];
  const LeafAreaKey leaf_area{
      io::schema::item_path(io::schema::key(io::schema::kForestKeys, "forest.stands[].leaf_area_index").path,
                            index),
      given.leaf_area_index_line, *stand.leaf_area_index};
  plan.coupling.leaves.push_back(
      species_leaves(scenario, bases.back(), given_species.leaves, leaf_area, plan.purpose));
  plan.coupling.dynamics.push_back(given_species.dynamics);
  plan.strengths.push_back(plan.strengths[std::size_t(stand.species_index)]);
  io::SpeciesSummary summary = plan.species[std::size_t(stand.species_index)];
  summary.name = fmt::format("{} (stand {})", stand.species, index);
  summary.trees = 0;
  summary.seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  plan.species.push_back(summary);
  return int(bases.size()) - 1;
}

// A tree of the species' skeleton (height h) scaled by `scale` stands between the smallest and the tallest
// tree's height; else the scale's key is to blame. A skeleton without height (a horizontal test beam) has
// only its upper bound, which holds at any scale.
void check_scaled_height(const io::Scenario& scenario, double h, double scale, int line,
                         const std::string& key) {
  namespace bounds = io::schema::bounds;
  const double height = h * scale;
  if (h <= 0.0 || (height >= bounds::kMinTreeHeight && height <= bounds::kMaxTreeHeight)) return;
  throw io::ScenarioError(
      scenario.file.string(), line, key,
      fmt::format("a scale that makes a tree of this species ({:.6g} m tall) {} to {} m tall "
                  "expected: {:.6g} to {:.6g}, got '{}' ({:.6g} m)",
                  h, bounds::kMinTreeHeight, bounds::kMaxTreeHeight, bounds::kMinTreeHeight / h,
                  bounds::kMaxTreeHeight / h, scale, height));
}

// Places every tree, the stands' first; fills plan.stands and adds the stands' own bases to `bases`.
std::vector<trees::TreeInstance> place_instances(const io::Scenario& scenario,
                                                 std::vector<trees::SpeciesBasis>& bases,
                                                 SimulationPlan& plan) {
  std::vector<trees::TreeInstance> instances;
  namespace schema = io::schema;
  for (std::size_t k = 0; k < scenario.forest.stands.size(); ++k) {
    const io::Stand& given = scenario.forest.stands[k];
    const double h = bases[std::size_t(given.layout.species)].skeleton().height();
    check_scaled_height(
        scenario, h, given.layout.scale_min, given.scale_min_line,
        schema::item_path(schema::key(schema::kForestKeys, "forest.stands[].scale.min").path, k));
    check_scaled_height(
        scenario, h, given.layout.scale_max, given.scale_max_line,
        schema::item_path(schema::key(schema::kForestKeys, "forest.stands[].scale.max").path, k));
    const std::vector<trees::PlacedTree> placed = trees::place_stand(given.layout);
    StandPlan stand;
    stand.species = given.species;
    stand.species_index = stand.forest_species = given.layout.species;
    stand.first_instance = int(instances.size());
    stand.min = given.layout.min;
    stand.max = given.layout.max;
    stand.leaf_area_index = given.leaf_area_index;
    stand.crown_leaf_area_index = bases[std::size_t(stand.species_index)].settings().wind.leaf_area_index;
    if (stand.leaf_area_index) stand.forest_species = stand_basis(scenario, k, placed, stand, bases, plan);
    stand.density.trees = int(placed.size());
    stand.density.ground_area = given.layout.ground_area();
    for (const trees::PlacedTree& tree : placed) {
      const double x = tree.position.x(), y = tree.position.y();
      instances.push_back({stand.forest_species, {x, y, ground_z(scenario, x, y)}, tree.yaw_rad, tree.scale});
    }
    plan.stands.push_back(std::move(stand));
  }
  for (std::size_t k = 0; k < scenario.forest.trees.size(); ++k) {
    const io::PlacedTreeSettings& placed = scenario.forest.trees[k];
    check_scaled_height(scenario, bases[std::size_t(placed.species_index)].skeleton().height(), placed.scale,
                        placed.scale_line,
                        schema::item_path(schema::key(schema::kForestKeys, "forest.trees[].scale").path, k));
    const auto& p = placed.position;
    const double z = placed.height_given ? p[2] : ground_z(scenario, p[0], p[1]);
    instances.push_back({placed.species_index, {p[0], p[1], z}, placed.yaw_rad, placed.scale});
  }
  return instances;
}

// The basis of the girth class k of forest.species[sp] (header comment), appended to `bases` with its
// leaves, model, strength and summary; its index.
int girth_class_basis(const io::Scenario& scenario, std::size_t sp, int k, const trees::BasisCache* cache,
                      std::vector<trees::SpeciesBasis>& bases, SimulationPlan& plan) {
  const auto start = std::chrono::steady_clock::now();
  const double girth = trees::SizeFitter::girth_of_class(k);
  const trees::SpeciesBasis& species = bases[sp];
  io::SpeciesSummary summary = plan.species[sp];
  summary.name = fmt::format("{} (girth {:.4f})", summary.species, girth);
  summary.trees = 0;
  summary.girth = girth;
  trees::SpeciesBasis basis = cached_species_basis(scenario, sp, trees::with_girth(species.skeleton(), girth),
                                                   species.settings(), cache, summary, plan);
  summary.first_hz = basis.modes().frequencies_hz()(0);
  bases.push_back(std::move(basis));
  const io::Species& given = scenario.forest.species[sp];
  plan.coupling.leaves.push_back(species_leaves(scenario, bases.back(), given.leaves,
                                                species_leaf_area_key(scenario, sp), plan.purpose));
  plan.coupling.dynamics.push_back(given.dynamics);
  plan.strengths.push_back(plan.strengths[sp]);
  summary.seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  plan.species.push_back(summary);
  return int(bases.size()) - 1;
}

// Draws each inventory tree's yaw (header comment); its own stream of the scenario's seed.
constexpr std::uint64_t kInventoryYawStream = 0x1a7e'0f1e'1d5e'ed00;

// Places the inventory's trees after `instances` (header comment); fills plan.inventory and plan.tree_ids.
void place_inventory(const io::Scenario& scenario, const trees::BasisCache* cache,
                     std::vector<trees::SpeciesBasis>& bases, std::vector<trees::TreeInstance>& instances,
                     SimulationPlan& plan) {
  const io::InventorySettings& inventory = *scenario.forest.inventory;
  const std::string file = inventory.file.string();
  std::vector<trees::SizeFitter> fitters;
  for (std::size_t sp = 0; sp < scenario.forest.species.size(); ++sp)
    fitters.emplace_back(bases[sp].skeleton().height(), bases[sp].stem_loads());
  InventoryPlan& planned = plan.inventory.emplace();
  planned.file = file;
  planned.outside = inventory.outside;
  plan.tree_ids.resize(instances.size());
  std::map<std::pair<int, int>, int> classes;  // (species, girth class) -> forest species
  std::mt19937_64 yaws(scenario.seed ^ kInventoryYawStream);
  std::uniform_real_distribution<double> turn(0.0, 2.0 * std::numbers::pi);
  namespace bounds = io::schema::bounds;
  for (const io::InventoryTree& tree : inventory.trees) {
    if (!(tree.height >= bounds::kMinTreeHeight && tree.height <= bounds::kMaxTreeHeight))
      throw base::SourceError(file, tree.line, inventory.columns.height,
                              fmt::format("a height of {} to {} m (the tallest tree is 116 m)",
                                          bounds::kMinTreeHeight, bounds::kMaxTreeHeight),
                              fmt::format("'{}'", tree.height));
    const trees::SizeFitter& fitter = fitters[std::size_t(tree.species)];
    if (!fitter.fits(tree.height, tree.dbh)) {
      const auto [low, high] = fitter.dbh_range(tree.height);
      throw base::SourceError(
          file, tree.line, inventory.columns.dbh,
          fmt::format("a dbh its species' template fits at {} m: {:.3g} to {:.3g} m (radii from 1/{} to {} "
                      "times the template's, scaled to the height; is it in metres?)",
                      tree.height, low, high, trees::SizeFitter::kMaxGirth, trees::SizeFitter::kMaxGirth),
          fmt::format("'{}'", tree.dbh));
    }
    const trees::SizeFit fit = fitter.fit(tree.height, tree.dbh);
    int species = tree.species;
    if (fit.girth_class != 0) {
      const auto key = std::pair{tree.species, fit.girth_class};
      auto found = classes.find(key);
      if (found == classes.end())
        found = classes
                    .emplace(key, girth_class_basis(scenario, std::size_t(tree.species), fit.girth_class,
                                                    cache, bases, plan))
                    .first;
      species = found->second;
    }
    planned.largest_dbh_error = std::max(planned.largest_dbh_error, std::abs(fit.dbh / tree.dbh - 1.0));
    instances.push_back(
        {species, {tree.x, tree.y, ground_z(scenario, tree.x, tree.y)}, turn(yaws), fit.scale});
    plan.tree_ids.push_back(tree.id);
  }
  planned.placed = int(inventory.trees.size());
}

}  // namespace

void plan_forest(const io::Scenario& scenario, std::vector<trees::SpeciesBasis> bases,
                 const trees::BasisCache* cache, SimulationPlan& plan) {
  std::vector<trees::TreeInstance> instances = place_instances(scenario, bases, plan);
  if (scenario.forest.inventory) place_inventory(scenario, cache, bases, instances, plan);
  for (const auto& tree : instances) {
    ++plan.species[std::size_t(tree.species)].trees;
    plan.leaf_count += plan.coupling.leaves[std::size_t(tree.species)].count();
  }
  plan.forest = trees::Forest(std::move(bases), std::move(instances));
  if (plan.forest.instance_count() == 0) return;
  plan.memory.add("trees", ForestStages::estimate_device_bytes(plan.forest, plan.coupling.dynamics));
  if (plan.leaf_count == 0) return;
  if (plan.leaf_count > LeafStages::kMaxLeaves)
    throw std::invalid_argument(fmt::format(
        "{}: forest: {} leaves on all trees, more than the {} the leaf stage holds; lower a species' "
        "leaves.fraction or canopy.leaf_area_index, or a stand's leaf_area_index",
        scenario.file.string(), plan.leaf_count, LeafStages::kMaxLeaves));
  plan.memory.add("leaves", LeafStages::estimate_device_bytes(plan.forest, plan.coupling.leaves));
}

}  // namespace fw::host
