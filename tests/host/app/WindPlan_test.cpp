// The wind grid's part of the plan on the host, no device: the advection scheme's stability limit against a
// fixed time step.
#include <catch2/catch.hpp>

#include <string>

#include "host/app/SimulationPlan.hpp"
#include "io/Scenario.hpp"
#include "tests/support/TempDir.hpp"

using Catch::Matchers::Contains;
using Catch::Matchers::StartsWith;
using fw::test::TempDir;

namespace {

// A uniform 5 m/s wind over 2 m cells, with the given advection scheme and fixed dt.
fw::host::SimulationPlan plan_with(const TempDir& dir, const std::string& advection, double dt) {
  const std::string text = "scenario: wind_plan\ntime: {end: 2.0, dt: " + std::to_string(dt) +
                           "}\n"
                           "domain: {size: [32, 16, 16], cell_size: 2.0}\n"
                           "wind: {speed: 5.0, direction: 270, profile: {type: uniform}}\n"
                           "solver: {advection: " +
                           advection + "}\n";
  return fw::host::plan_simulation(fw::io::load_scenario(dir.write("wind.yaml", text)), nullptr, nullptr);
}

}  // namespace

TEST_CASE("WindPlan: a fixed dt past upwind5's Courant limit at the peak wind is refused, naming time.dt",
          "[simulation][plan]") {
  TempDir dir("fw_wind_plan");
  // 5 m/s x 0.5 s / 2 m = 1.25 > 1.2: refused; 0.45 s gives 1.125.
  CHECK_THROWS_WITH(plan_with(dir, "upwind5", 0.5),
                    StartsWith(dir.path() + "/wind.yaml:2: time.dt: a step <= 0.48 s") &&
                        Contains("upwind5") && Contains("1.2"));
  CHECK_NOTHROW(plan_with(dir, "upwind5", 0.45));
  // The semi-Lagrangian schemes are stable at any Courant number.
  CHECK_NOTHROW(plan_with(dir, "maccormack", 0.5));
}

TEST_CASE("WindPlan: the peak wind is the ambient's largest speed times the profile's top, plus gusts",
          "[simulation][plan]") {
  TempDir dir("fw_wind_plan");
  const auto plan = plan_with(dir, "semi_lagrangian", 0.1);
  CHECK(fw::host::peak_wind_speed(plan) == Approx(5.0).epsilon(1e-6));  // uniform profile, no gusts
}

TEST_CASE("WindPlan: time.end or time.spin_up of more steps than a run can take is refused at its line",
          "[simulation][plan]") {
  TempDir dir("fw_wind_plan");
  // 2 m cells in a steady 5 m/s wind: dt auto at CFL 0.8 is 0.32 s; 10^9 steps of it are 3.2e8 s. Within
  // time.end's own bound (10^9 s), the steps are the planner's to count (issue 44: the end time 1e30 hung
  // it).
  const auto plan_text = [&](const std::string& time) {
    return fw::io::load_scenario(dir.write("steps.yaml", "scenario: steps\ntime: " + time +
                                                             "\n"
                                                             "domain: {size: [32, 16, 16], cell_size: 2.0}\n"
                                                             "wind: {speed: 5.0, direction: 270}\n"));
  };
  const auto plan = [&](const std::string& time) {
    return fw::host::plan_simulation(plan_text(time), nullptr, nullptr, 1, fw::host::PlanFor::check);
  };
  CHECK_THROWS_WITH(plan("{end: 1e9, cfl: 0.8}"),
                    StartsWith(dir.path() + "/steps.yaml:2: time.end: at most 1e9 steps expected") &&
                        Contains("got '1e9' s: 3.125e9 steps of the CFL step of 0.32 s"));
  CHECK_THROWS_WITH(plan("{end: 10, spin_up: 1e9}"),
                    StartsWith(dir.path() + "/steps.yaml:2: time.spin_up: at most 1e9 steps expected"));
  // A fixed step tiny against a long run: the steps of time.dt.
  CHECK_THROWS_WITH(plan("{end: 1e5, dt: 1e-5}"), Contains("1e10 steps of time.dt = 1e-5 s"));
  // 3e8 s (9.5 years) at 0.32 s a step is 9.4e8 steps: a run that long is possible.
  CHECK(plan("{end: 3e8, cfl: 0.8}").end_time == 3e8);
}
