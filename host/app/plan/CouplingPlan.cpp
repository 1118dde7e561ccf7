// The coupling's part of the plan: every tree's frontal area on the grid (the canopy density the wind
// frames show) and, with two-way coupling, the drag density the wind feels; the modal integrator; the
// strong-wind correction of output frames; and the memory of the canopy drag and of Stam's forcing.
#include <fmt/format.h>

#include <stdexcept>

#include "fluid/CanopyField.hpp"
#include "host/app/plan/PlanBuilders.hpp"
#include "host/stages/ForestStages.hpp"
#include "trees/CanopyDrag.hpp"

namespace fw::host {

void plan_coupling(const io::Scenario& scenario, SimulationPlan& plan) {
  CouplingSettings& coupling = plan.coupling;
  coupling.integrator = scenario.forest.integrator;
  coupling.strong_wind_correction = scenario.forest.strong_wind_correction;
  if (plan.forest.instance_count() == 0) return;
  // A fixed dt past the semi-implicit integrator's limit would stop the run at its first step.
  const fluid::WindSettings& settings = plan.wind.settings;
  if (coupling.integrator == trees::ModalIntegrator::semi_implicit && !(settings.cfl > 0.0)) {
    const double limit = plan.forest.semi_implicit_dt_limit();
    if (settings.dt >= limit)
      throw std::invalid_argument(
          fmt::format("{}: forest.integrator: semi-implicit Euler is unstable at time.dt = {} s for the "
                      "fastest tree mode "
                      "(stable below {:.4g} s); lower time.dt or use forest.integrator: exact",
                      scenario.file.string(), settings.dt, limit));
  }
  fluid::CanopyField canopy(plan.wind.spec);
  for (int k = 0; k < plan.forest.instance_count(); ++k) trees::add_to_canopy(canopy, plan.forest, k);
  plan.canopy_density = canopy.frontal_area_density();
  plan.canopy_dropped_area = canopy.dropped_frontal_area();
  if (scenario.forest.two_way_coupling) {
    coupling.drag_density = canopy.drag_density();
    plan.memory.add("canopy drag", WindGrid::estimate_canopy_bytes(plan.wind.spec));
  }
  if (coupling.unresolved.enabled)
    plan.memory.add("unresolved turbulence",
                    ForestStages::estimate_unresolved_bytes(coupling.unresolved, plan.forest));
}

}  // namespace fw::host
