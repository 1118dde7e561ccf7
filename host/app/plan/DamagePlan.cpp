// The plan's storm damage (docs/damage.md): every forest species' critical moments at scale 1, the model's
// own static critical wind and Hale's, for `check` and run.json; and, with forest.damage enabled, the damage
// stage's settings (one strength per forest species: the loader requires one of every species then) and its
// device memory.
#include <fmt/format.h>

#include <cmath>
#include <stdexcept>

#include "host/app/plan/PlanBuilders.hpp"
#include "host/stages/DamageStages.hpp"
#include "io/Scenario.hpp"

namespace fw::host {

namespace {

// ForestGALES's deflection loading factor (Hale et al. 2015): the share of a bent tree's peak moment its
// own weight adds, which Hale's regression of the wind alone leaves out.
constexpr double kDeflectionLoadingFactor = 1.14;

}  // namespace

void plan_damage(const io::Scenario& scenario, SimulationPlan& plan) {
  const std::vector<trees::SpeciesBasis>& species = plan.forest.species();
  for (std::size_t sp = 0; sp < plan.strengths.size(); ++sp) {
    std::optional<SpeciesStrength>& entry = plan.strengths[sp];
    if (!entry) continue;
    const trees::StemLoads& stem = species.at(sp).stem_loads();
    entry->critical = trees::critical_moments(stem, entry->strength);
    entry->static_wind = trees::static_critical_wind(species[sp], entry->critical);
    const std::vector<trees::StemSection> sections = stem.sections();
    if (entry->static_wind.breaks)
      entry->static_break_height = sections[std::size_t(entry->static_wind.section)].height;
    entry->height = species[sp].skeleton().height();
    entry->dbh = stem.breast_height_diameter();
    // Hale's relation is of the root's moment: the base section's and the roots' critical moments.
    const double base = std::min(entry->critical.breaking.front(), entry->critical.overturning);
    entry->hale_wind = trees::hale_critical_wind(base / kDeflectionLoadingFactor, entry->dbh, entry->height);
  }
  trees::DamageSettings& damage = plan.coupling.damage;
  damage.enabled = scenario.forest.damage.enabled;
  damage.consequences = scenario.forest.damage.consequences;
  if (!damage.enabled || plan.forest.instance_count() == 0) return;
  for (std::size_t sp = 0; sp < plan.strengths.size(); ++sp) {
    if (!plan.strengths[sp])  // the loader requires a strength of every species with damage: a bug here
      throw std::logic_error(fmt::format("plan_damage: forest species {} has no strength", sp));
    damage.strengths.push_back(plan.strengths[sp]->strength);
  }
  plan.memory.add("damage", DamageStages::estimate_device_bytes(plan.forest, damage, plan.coupling.dynamics));
}

}  // namespace fw::host
