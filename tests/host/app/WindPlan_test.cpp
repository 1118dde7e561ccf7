// The wind grid's part of the plan on the host, no device: the advection scheme's stability limit against a
// fixed time step.
#include <catch2/catch.hpp>

#include <string>

#include "host/app/SimulationPlan.hpp"
#include "io/Scenario.hpp"
#include "tests/support/TempDir.hpp"

using Catch::Matchers::Contains;
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
                    Contains("time.dt") && Contains("upwind5") && Contains("1.2") && Contains("dt <= 0.48"));
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
