#include "host/app/SimulationPlan.hpp"

#include <algorithm>
#include <cmath>
#include <stdexcept>
#include <string>

#include <fmt/format.h>

#include "host/app/plan/PlanBuilders.hpp"
#include "io/Scenario.hpp"

namespace fw::host {

SimulationPlan plan_simulation(const io::Scenario& scenario, const trees::BasisCache* cache,
                               std::ostream* log, int ranks, PlanFor purpose) {
  SimulationPlan plan;
  plan.purpose = purpose;
  plan_wind(scenario, ranks, plan);
  plan_turbulence(scenario.wind, plan);
  plan_forest(scenario, plan_species(scenario, cache, log, plan), cache, plan);
  plan_damage(scenario, plan);
  plan_coupling(scenario, plan);
  plan_outputs(scenario, plan);
  return plan;
}

double peak_wind_speed(const SimulationPlan& plan) {
  double peak = 0.0;
  const double every = std::max(1.0, plan.end_time / kPeakWindSamples);  // s
  for (double t = 0.0;; t = std::min(t + every, plan.end_time)) {
    const auto v = plan.inputs.ambient_wind(t);
    peak = std::max(peak, std::hypot(v[0], v[1], v[2]));
    if (t >= plan.end_time) break;
  }
  const std::vector<float> shape = plan.wind.profile.sample_cell_centres(plan.wind.spec.nz, plan.wind.spec.h);
  const double factor = shape.empty() ? 1.0 : double(*std::max_element(shape.begin(), shape.end()));
  double gust = 0.0;
  for (const FwGust& g : plan.wind.gusts) gust = std::max(gust, double(g.peak_speed));
  return peak * factor + gust;
}

double planned_dt(const SimulationPlan& plan) {
  const fluid::WindSettings& settings = plan.wind.settings;
  if (!(settings.cfl > 0.0)) return settings.dt;
  return WindGrid::cfl_dt(settings, plan.wind.spec, {plan.peak_wind, 0.0, 0.0});
}

long planned_spin_up_steps(const SimulationPlan& plan) {
  if (!(plan.spin_up > 0.0)) return 0;
  return long(std::ceil(plan.spin_up / planned_dt(plan)));
}

}  // namespace fw::host
