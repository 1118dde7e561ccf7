// The builders of a SimulationPlan, one per part, in the order plan_simulation calls them. Each fills its
// part of the plan from the scenario, validates it as the stage that will receive it does, and adds the
// device memory that stage will allocate (plan.memory). Later builders read what earlier ones resolved.
//
//   SimulationPlan plan;
//   plan_wind(scenario, ranks, plan);   // grid, solids, profile, gusts, mean forcing, ambient wind over
//                                       // time, the blocks over the ranks
//   plan_turbulence(scenario.wind, plan);   // the inflow box and its sigma_u(t); Stam's unresolved forcing
//   auto bases = plan_species(scenario, cache, log, plan);   // bases (cache), leaves, summaries
//   plan_forest(scenario, std::move(bases), plan);          // the placed instances, the stands
//   plan_damage(scenario, plan);        // the species' critical moments; the damage stage
//   plan_coupling(scenario, plan);      // the canopy and its drag, the stands' density, integrator, ...
//   plan_outputs(scenario, plan);       // writers, probes, the scenario record
#pragma once

#include <ostream>
#include <string>
#include <vector>

#include "host/app/SimulationPlan.hpp"
#include "trees/BasisCache.hpp"
#include "trees/SpeciesBasis.hpp"
#include "trees/SpeciesLeaves.hpp"

namespace fw::io {
// Each builder takes the part of the scenario it reads, and its file includes only that part's header.
struct Scenario;      // io/Scenario.hpp
struct WindScenario;  // io/WindScenario.hpp
struct WindSource;    // io/settings/WindSource.hpp
}  // namespace fw::io

namespace fw::host {

/// host/app/plan/WindPlan.cpp
void plan_wind(const io::WindScenario& scenario, int ranks, SimulationPlan& plan);
/// host/app/plan/TurbulencePlan.cpp (after plan_wind): the turbulence of the scenario's wind
void plan_turbulence(const io::WindSource& wind, SimulationPlan& plan);
/// host/app/plan/SpeciesPlan.cpp: every species' basis, in file order (to be handed to plan_forest), its
/// leaves (plan.coupling.leaves) and its summary (plan.species). `cache` and `log` may be null.
std::vector<trees::SpeciesBasis> plan_species(const io::Scenario& scenario, const trees::BasisCache* cache,
                                              std::ostream* log, SimulationPlan& plan);
/// The key of the file that sets a basis' leaf area (the species' canopy.leaf_area_index, or a stand's own
/// leaf_area_index), its line and its value, for the error of a leaf count past the leaf stage.
struct LeafAreaKey {
  std::string key;  ///< dotted, with the item's index
  int line = 0;
  double value = 0.0;
};
/// host/app/plan/SpeciesPlan.cpp: forest.species[index]'s basis of `skeleton`, through the cache when there
/// is one (summary.cache says how; plan.warnings gets a cache that failed). Throws io::ScenarioError at the
/// species when its modes cannot be solved.
trees::SpeciesBasis cached_species_basis(const io::Scenario& scenario, std::size_t index,
                                         const trees::Skeleton& skeleton,
                                         const trees::SpeciesSettings& settings,
                                         const trees::BasisCache* cache, io::SpeciesSummary& summary,
                                         SimulationPlan& plan);

/// host/app/plan/SpeciesPlan.cpp: the key of forest.species[index]'s canopy.leaf_area_index.
LeafAreaKey species_leaf_area_key(const io::Scenario& scenario, std::size_t index);

/// host/app/plan/SpeciesPlan.cpp: the leaves `settings` ask for on a basis' own skeleton and foliage (its
/// settings().wind.leaf_area_index), so that their elements are the forest's; none without leaves; generated
/// for a run's plan, counted for `check`'s (PlanFor). Throws io::ScenarioError at `source` when one tree
/// would carry more leaves than the leaf stage holds.
trees::SpeciesLeaves species_leaves(const io::Scenario& scenario, const trees::SpeciesBasis& basis,
                                    const trees::LeafSettings& settings, const LeafAreaKey& source,
                                    PlanFor purpose);
/// host/app/plan/ForestPlan.cpp (after plan_species): the placed instances, a basis of its own for every
/// stand that gives its leaf area index and for every girth class of the inventory's trees (through `cache`,
/// which may be null), with their summaries (plan.stands, plan.species, plan.coupling.leaves, plan.inventory,
/// plan.tree_ids)
void plan_forest(const io::Scenario& scenario, std::vector<trees::SpeciesBasis> bases,
                 const trees::BasisCache* cache, SimulationPlan& plan);
/// host/app/plan/DamagePlan.cpp (after plan_forest): every species' critical moments and winds
/// (plan.strengths), and the damage stage's settings and memory when forest.damage is enabled
void plan_damage(const io::Scenario& scenario, SimulationPlan& plan);
/// host/app/plan/CouplingPlan.cpp (after plan_forest and plan_turbulence)
void plan_coupling(const io::Scenario& scenario, SimulationPlan& plan);
/// host/app/plan/OutputPlan.cpp
void plan_outputs(const io::Scenario& scenario, SimulationPlan& plan);

}  // namespace fw::host
