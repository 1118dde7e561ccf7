// The turbulence's part of the plan: the unit-sigma inflow box of wind.turbulence with its sigma_u over
// time, and Stam's forcing of the trees by the eddies the grid cannot resolve with its intensity over time.
#include <cmath>
#include <memory>

#include "fluid/TurbulenceBox.hpp"
#include "host/app/plan/PlanBuilders.hpp"
#include "host/stages/ForestStages.hpp"
#include "io/settings/WindSource.hpp"

namespace fw::host {

namespace {

// The unit-sigma_u box on a grid of cell size h (fluid::inflow_box_spec: points every h / 2, so that every
// face of an inflow plane sits on a box point; no eddy shorter than the grid carries; swept along the
// horizontal axis closer to the wind at t = 0). Unequal sigma_u, sigma_v, sigma_w scale the box's
// components: its x and y take the along- and across-wind values by that same axis (equal values, the
// intensity form, need no such choice).
fluid::TurbulenceBoxSpec inflow_box_spec(const io::TurbulenceSettings& turbulence, double h,
                                         const std::array<double, 3>& wind_at_start) {
  const bool along_x = std::abs(wind_at_start[0]) >= std::abs(wind_at_start[1]);
  fluid::TurbulenceBoxSpec spec = fluid::inflow_box_spec(
      turbulence.box_cells, h, turbulence.length_scale, turbulence.cutoff_cells, along_x ? 0 : 1,
      turbulence.seed);                                    // unit sigma_u: scaled by sigma_u(t)
  const auto sigma = turbulence.standard_deviations(1.0);  // [along, across, vertical]
  if (sigma[0] > 0.0) {
    spec.component_scale = {(along_x ? sigma[0] : sigma[1]) / sigma[0],
                            (along_x ? sigma[1] : sigma[0]) / sigma[0], sigma[2] / sigma[0]};
  }
  return spec;
}

}  // namespace

void plan_turbulence(const io::WindSource& wind_source, SimulationPlan& plan) {
  if (!wind_source.turbulence) return;
  const io::TurbulenceSettings& turbulence = *wind_source.turbulence;
  WindGridSetup& wind = plan.wind;
  const fluid::TurbulenceBoxSpec& box =
      plan.turbulence_box.emplace(inflow_box_spec(turbulence, wind.spec.h, wind.ambient));
  box.validate();
  // Synthesising the box takes a minute and gigabytes at the largest sizes (fluid/TurbulenceBox.hpp): only
  // the run that sweeps it needs it.
  if (plan.purpose == PlanFor::run) wind.turbulence = std::make_shared<const fluid::TurbulenceBox>(box);
  plan.inputs.turbulence_sigma = [turbulence, source = wind_source](double t) {
    const auto v = io::wind_vector(source, t);
    return turbulence.standard_deviations(std::hypot(v[0], v[1], v[2]))[0];
  };
  plan.memory.add("inflow turbulence", WindBoundaries::turbulence_bytes(plan.wind.spec, box));

  if (!turbulence.unresolved) return;
  trees::UnresolvedTurbulenceSettings& unresolved = plan.coupling.unresolved;
  unresolved.enabled = true;
  unresolved.cutoff_cells = turbulence.cutoff_cells;
  unresolved.cell_size = wind.spec.h;
  unresolved.integral_length = turbulence.length_scale;
  unresolved.seed = turbulence.seed;
  // sigma_u / U: the intensity as given, or sigma_u over the wind speed of the moment.
  plan.inputs.unresolved_intensity = [turbulence, source = wind_source](double t) {
    if (turbulence.intensity) return *turbulence.intensity;
    const auto v = io::wind_vector(source, t);
    const double speed = std::hypot(v[0], v[1], v[2]);
    return speed > 0.0 ? turbulence.standard_deviations(speed)[0] / speed : 0.0;
  };
  unresolved.intensity = plan.inputs.unresolved_intensity(0.0);
  unresolved.validate();
}

}  // namespace fw::host
