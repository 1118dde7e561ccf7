// The wind grid's part of the plan: the grid with "auto" faces resolved for the wind at t = 0, the solver
// settings, the inflow profile, the solids (obstacles and terrain), the gusts, the mean forcing of a
// periodic domain, the ambient wind over time, and the grid's blocks over the run's ranks.
#include <fmt/format.h>

#include <algorithm>
#include <cmath>
#include <stdexcept>
#include <variant>

#include "fluid/SolidMap.hpp"
#include "host/app/plan/PlanBuilders.hpp"
#include "io/ScenarioError.hpp"
#include "io/ScenarioSchema.hpp"
#include "io/WindScenario.hpp"
#include "io/schema/Bounds.hpp"
#include "io/schema/TimeKeys.hpp"

namespace fw::host {

namespace {

// The FwGust of a gust event: its travel resolved, its direction along the ambient wind at its start (with
// no wind then, along +x, so that the gust is still well defined).
FwGust device_gust(const io::GustEvent& event, const std::array<double, 3>& wind_at_start) {
  FwGust gust{};
  gust.start = float(event.start);
  gust.duration = float(event.duration);
  gust.peak_speed = float(event.peak_speed);
  gust.radius = float(event.radius);
  const double speed = std::hypot(wind_at_start[0], wind_at_start[1], wind_at_start[2]);
  for (int a = 0; a < 3; ++a) {
    gust.center[a] = float(event.center[a]);
    gust.travel[a] = float(event.travel[a]);
    gust.direction[a] = float(speed > 0.0 ? wind_at_start[a] / speed : (a == 0 ? 1.0 : 0.0));
  }
  return gust;
}

// The step `check` plans with, in words: where it comes from.
std::string planned_step_words(const SimulationPlan& plan) {
  const fluid::WindSettings& settings = plan.wind.settings;
  if (!(settings.cfl > 0.0)) return fmt::format("time.dt = {} s", io::schema::number_text(settings.dt));
  return fmt::format("the CFL step of {:.3g} s (dt auto, CFL {}, {} m cells, peak wind {:.3g} m/s)",
                     planned_dt(plan), settings.cfl, plan.wind.spec.h, plan.peak_wind);
}

// A span of simulated time (time.end, time.spin_up) takes at most bounds::kMaxRunSteps steps of the planned
// step: past it a run would not end in any wall time, nor could the planner count its frames.
void check_steps(const io::WindScenario& scenario, const SimulationPlan& plan, double span, int line,
                 std::string_view key) {
  const double steps = std::ceil(span / planned_dt(plan));
  if (steps <= io::schema::bounds::kMaxRunSteps) return;
  throw io::ScenarioError(
      scenario.file.string(), line, std::string(key),
      fmt::format("at most {} steps expected (a run takes no more), got '{}' s: {} steps of {}",
                  io::schema::number_text(io::schema::bounds::kMaxRunSteps), io::schema::number_text(span),
                  io::schema::number_text(steps), planned_step_words(plan)));
}

}  // namespace

void plan_wind(const io::WindScenario& scenario, int ranks, SimulationPlan& plan) {
  WindGridSetup& wind = plan.wind;
  wind.spec = scenario.grid_spec(0.0);
  wind.settings = scenario.wind_settings();
  wind.profile = scenario.wind.profile;
  wind.ambient = scenario.wind_vector(0.0);
  fluid::SolidMap solids(wind.spec);
  for (const auto& obstacle : scenario.obstacles) {
    std::visit([&](const auto& shape) { solids.add(shape); }, obstacle);
  }
  if (scenario.terrain && scenario.terrain->map) solids.add_terrain(*scenario.terrain->map);
  wind.solid = solids.cells();
  // std::count of the zeros vectorises; a grid may have 2^31 cells.
  plan.solid_cells = wind.solid.size() - std::size_t(std::count(wind.solid.begin(), wind.solid.end(), 0));
  for (const auto& event : scenario.events)
    wind.gusts.push_back(device_gust(event, scenario.wind_vector(event.start)));
  if (scenario.wind.forcing) wind.forcing.relaxation_time = scenario.wind.forcing->relaxation_time;
  WindGrid::validate(wind);

  plan.end_time = scenario.time.end;
  plan.spin_up = scenario.time.spin_up;
  plan.inputs.ambient_wind = [source = scenario.wind](double t) { return io::wind_vector(source, t); };
  plan.peak_wind = peak_wind_speed(plan);
  check_steps(scenario, plan, plan.end_time, scenario.time.end_line,
              io::schema::key(io::schema::kTimeKeys, "time.end").path);
  check_steps(scenario, plan, plan.spin_up, scenario.time.spin_up_line,
              io::schema::key(io::schema::kTimeKeys, "time.spin_up").path);
  // A fixed dt past the scheme's stability limit at the peak wind would blow up in the first gusty minute.
  const AdvectionMethod& advection = advection_method(wind.settings.advection);
  const double limit = advection.courant_limit;
  if (!(wind.settings.cfl > 0.0) && std::isfinite(limit)) {
    const double peak = plan.peak_wind;
    if (peak * wind.settings.dt / wind.spec.h > limit)
      throw io::ScenarioError(
          scenario.file.string(), scenario.time.dt_line,
          std::string(io::schema::key(io::schema::kTimeKeys, "time.dt").path),
          fmt::format(
              "a step <= {:.4g} s expected ({} is stable up to a Courant number (|u| + |v| + |w|) dt / "
              "h of {}; at the peak wind of {:.1f} m/s, ambient times the profile's top plus gusts, "
              "and h = {} m), got '{}'; lower time.dt or use dt: auto",
              limit * wind.spec.h / peak, advection.name(), limit, peak, wind.spec.h, wind.settings.dt));
  }
  // In one process a scenario's decomposition is ignored, so that the same file runs alone and over ranks.
  const double courant =
      wind.settings.cfl > 0.0 ? wind.settings.cfl : plan.peak_wind * wind.settings.dt / wind.spec.h;
  try {
    plan.decomposition =
        fluid::Decomposition::make(wind.spec, ranks, ranks > 1 ? scenario.domain.decomposition : std::nullopt,
                                   advection.halo_cells(courant));
  } catch (const fluid::DecompositionError& e) {
    throw std::invalid_argument(fmt::format("{}:{}: domain.decomposition: {}", scenario.file.string(),
                                            scenario.domain.decomposition_line, e.what()));
  }
  // The planner has no device: the rows mapping's chunk of 1 gives the largest estimate of the two.
  // This process's share: the whole grid alone; over ranks the largest rank's is PlanReport's to show.
  plan.memory.add("wind grid", WindGrid::estimate_device_bytes(wind),
                  WindGrid::estimate_largest_buffer_bytes(wind.spec));
}

}  // namespace fw::host
