// The species' part of the plan: each species' skeleton (generated, or read from its .tree or TreeQSM file),
// its modal and wind basis (through the disk cache when there is one; every model builds on it), its leaves
// on the basis' own skeleton, the model that moves its trees, and the summary that run.json and `check`
// report.
#include <fmt/format.h>

#include <chrono>

#include "base/SourceError.hpp"
#include "host/app/plan/PlanBuilders.hpp"
#include "host/stages/LeafStages.hpp"
#include "io/Scenario.hpp"
#include "io/ScenarioSchema.hpp"
#include "io/schema/Bounds.hpp"
#include "trees/Foliage.hpp"
#include "trees/QsmImport.hpp"
#include "trees/TreeFile.hpp"
#include "trees/TreeGenerator.hpp"

namespace fw::host {

namespace {

using Clock = std::chrono::steady_clock;

// A file that does not parse throws base::SourceError naming its line (an input error).
trees::Skeleton read_skeleton(const io::SkeletonSource& source) {
  using Kind = io::SkeletonSource::Kind;
  switch (source.kind) {
    case Kind::generate:
      return trees::generate_tree(source.generate);
    case Kind::file:
      return trees::read_tree_file(source.path.string());
    case Kind::qsm:
      return trees::read_qsm_cylinders(source.path.string());
  }
  throw std::logic_error("species_skeleton: unknown skeleton source");
}

// The species' skeleton, no taller than a tree: what the skeleton's key gives is to blame for one that
// cannot be built or is taller (a .tree file's own errors name their line in it).
trees::Skeleton species_skeleton(const io::Scenario& scenario, const io::Species& species) {
  const io::SkeletonSource& source = species.skeleton;
  trees::Skeleton skeleton;
  try {
    skeleton = read_skeleton(source);
  } catch (const base::SourceError&) {
    throw;
  } catch (const std::invalid_argument& error) {
    throw io::ScenarioError(scenario.file.string(), source.line, source.key,
                            fmt::format("a skeleton that can be built expected ({})", error.what()));
  }
  if (!(skeleton.height() <= io::schema::bounds::kMaxTreeHeight))
    throw io::ScenarioError(
        scenario.file.string(), source.line, source.key,
        fmt::format("a skeleton at most {} m tall expected (the tallest tree is 116 m), got "
                    "one {:.6g} m tall",
                    io::schema::bounds::kMaxTreeHeight, skeleton.height()));
  return skeleton;
}

trees::SpeciesSettings species_settings(const io::Species& species) {
  trees::SpeciesSettings settings;
  settings.material = species.material;
  // modal.mode_count: io::species_mode_count, once the skeleton is known.
  settings.modal.damping = trees::Damping::modal_ratio(species.modes.damping_ratio);
  settings.wind.samples = species.modes.wind_samples;
  // One drag convention on both sides of the coupling (trees/CanopyDrag.hpp): 1/2 rho C_D A |u| u.
  settings.wind.branch_drag_coefficient = species.drag_coefficient;
  settings.wind.leaf_area_index = species.canopy.leaf_area_index;
  settings.wind.leaf_drag_coefficient = species.canopy.drag_coefficient;
  return settings;
}

}  // namespace

trees::SpeciesBasis cached_species_basis(const io::Scenario& scenario, std::size_t index,
                                         const trees::Skeleton& skeleton,
                                         const trees::SpeciesSettings& settings,
                                         const trees::BasisCache* cache, io::SpeciesSummary& summary,
                                         SimulationPlan& plan) {
  const io::Species& species = scenario.forest.species[index];
  try {
    if (!cache) return trees::SpeciesBasis::compute(skeleton, settings);
    trees::CacheOutcome outcome{};
    std::string store_error, corrupt;
    trees::SpeciesBasis basis = cache->load_or_compute(skeleton, settings, &outcome, &store_error, &corrupt);
    summary.cache = trees::to_string(outcome);
    // Neither stops the run: the basis is computed here instead (docs/trees.md, "The cache").
    if (!corrupt.empty())
      plan.warnings.push_back(
          fmt::format("basis cache: {}; the basis is computed again and the entry replaced", corrupt));
    if (!store_error.empty())
      plan.warnings.push_back(fmt::format("basis cache: {}; the run goes on without caching species '{}'",
                                          store_error, species.name));
    return basis;
  } catch (const trees::ModalError& error) {
    throw io::ScenarioError(
        scenario.file.string(), species.line, io::schema::item_path("forest.species[]", index),
        fmt::format("a species whose vibration modes can be solved expected (its skeleton, material and "
                    "modes give: {})",
                    error.what()));
  }
}

LeafAreaKey species_leaf_area_key(const io::Scenario& scenario, std::size_t index) {
  const io::Species& species = scenario.forest.species[index];
  return {
      io::schema::item_path(
          io::schema::key(io::schema::kSpeciesKeys, "forest.species[].canopy.leaf_area_index").path, index),
      species.canopy.leaf_area_index_line, species.canopy.leaf_area_index};
}

trees::SpeciesLeaves species_leaves(const io::Scenario& scenario, const trees::SpeciesBasis& basis,
                                    const trees::LeafSettings& settings, const LeafAreaKey& source,
                                    PlanFor purpose) {
  if (!settings.has_leaves()) return {};
  const trees::Foliage foliage = trees::Foliage::of(basis.skeleton(), basis.settings().wind.leaf_area_index);
  // Every tree of the species carries all its leaves, and the leaf stage indexes leaves with 32-bit
  // integers: one tree's must fit before the forest's total is checked (plan_forest), and before a count
  // past any integer is rounded. The count grows in proportion to the leaf area index.
  const double count = trees::SpeciesLeaves::planned_count(foliage, settings);
  const double limit = double(LeafStages::kMaxLeaves);
  if (!(count <= limit)) {
    throw io::ScenarioError(
        scenario.file.string(), source.line, source.key,
        fmt::format("at most {:.6g} expected (leaves of {:.6g} m^2 at leaves.fraction {:.6g} on these crowns "
                    "make {:.3g} leaves a tree here, more than the {} the leaf stage holds), got '{}'",
                    source.value * limit / count, settings.area, settings.fraction, count,
                    LeafStages::kMaxLeaves, source.value));
  }
  return purpose == PlanFor::run ? trees::SpeciesLeaves::generate(basis.skeleton(), foliage, settings)
                                 : trees::SpeciesLeaves::counted(basis.skeleton(), foliage, settings);
}

std::vector<trees::SpeciesBasis> plan_species(const io::Scenario& scenario, const trees::BasisCache* cache,
                                              std::ostream* log, SimulationPlan& plan) {
  std::vector<trees::SpeciesBasis> bases;
  for (std::size_t index = 0; index < scenario.forest.species.size(); ++index) {
    const io::Species& species = scenario.forest.species[index];
    const auto start = Clock::now();
    const trees::Skeleton skeleton = species_skeleton(scenario, species);
    io::check_species_skeleton(scenario, int(index), skeleton.size());
    trees::SpeciesSettings settings = species_settings(species);
    settings.modal.mode_count = io::species_mode_count(scenario, int(index), skeleton.size());
    io::SpeciesSummary summary;
    summary.name = summary.species = species.name;
    summary.dynamics = trees::dynamics_name(species.dynamics.model);
    bases.push_back(cached_species_basis(scenario, index, skeleton, settings, cache, summary, plan));
    const trees::SpeciesBasis& basis = bases.back();
    summary.seconds = std::chrono::duration<double>(Clock::now() - start).count();
    summary.nodes = basis.skeleton().size();
    summary.modes = basis.modes().mode_count();
    summary.samples = basis.wind().sample_count();
    summary.first_hz = basis.modes().frequencies_hz()(0);
    plan.coupling.leaves.push_back(species_leaves(scenario, basis, species.leaves,
                                                  species_leaf_area_key(scenario, index), plan.purpose));
    species.dynamics.validate();  // the loader's ranges are its own: a failure here is a bug, not the file's
    plan.coupling.dynamics.push_back(species.dynamics);
    std::optional<SpeciesStrength>& strength = plan.strengths.emplace_back();
    if (species.strength) {
      strength.emplace();
      strength->strength = *species.strength;
      strength->source = species.strength_source;
    }
    if (log) {
      const int leaves = plan.coupling.leaves.back().count();
      *log << fmt::format(
          "species {}: {}, {} nodes, {} modes from {:.3f} Hz, {} wind samples{} ({}, {:.2f} s)\n",
          summary.name, summary.dynamics, summary.nodes, summary.modes, summary.first_hz, summary.samples,
          species.leaves.has_leaves() ? fmt::format(", {} leaves", leaves) : "", summary.cache,
          summary.seconds);
    }
    plan.species.push_back(summary);
  }
  return bases;
}

}  // namespace fw::host
