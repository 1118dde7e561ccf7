#include "host/app/SimulationPlan.hpp"

#include "host/app/plan/PlanBuilders.hpp"

namespace fw::host {

SimulationPlan plan_simulation(const io::Scenario& scenario, const trees::BasisCache* cache,
                               std::ostream* log) {
  SimulationPlan plan;
  plan_wind(scenario, plan);
  plan_turbulence(scenario, plan);
  plan_forest(scenario, plan_species(scenario, cache, log, plan), plan);
  plan_coupling(scenario, plan);
  plan_outputs(scenario, plan);
  return plan;
}

}  // namespace fw::host
