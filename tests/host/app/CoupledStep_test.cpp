// The coupled step's order and checks: dt choice, the end-time limit and the blow-up guards.
#include <catch2/catch.hpp>

#include <cmath>
#include <limits>
#include <string>

#include "host/app/CoupledStep.hpp"
#include "io/schema/Bounds.hpp"
#include "tests/support/TestDevice.hpp"

namespace {

// A 16 x 8 x 8 channel of 1 m cells, inflow west, outflow east, slip elsewhere, no trees.
fw::host::WindGridSetup channel(double cfl, double dt) {
  fw::host::WindGridSetup setup;
  setup.spec.nx = 16;
  setup.spec.ny = 8;
  setup.spec.nz = 8;
  setup.spec.h = 1.0;
  using fw::fluid::BoundaryType;
  setup.spec.boundary = {BoundaryType::inflow, BoundaryType::outflow, BoundaryType::slip,
                         BoundaryType::slip,   BoundaryType::slip,    BoundaryType::slip};
  setup.settings.cfl = cfl;
  setup.settings.dt = dt;
  setup.ambient = {5.0, 0.0, 0.0};
  return setup;
}

}  // namespace

TEST_CASE("CoupledStep: dt follows the CFL number and never passes the caller's limit", "[simulation]") {
  auto* cc = fw::test::device_or_skip();
  if (!cc) return;
  fw::host::CoupledStep coupled(*cc, channel(0.5, 0.0), fw::trees::Forest(), {},
                                fw::host::TimeInputs::steady({5.0, 0.0, 0.0}));
  coupled.start();
  const auto free = coupled.step();
  // Uniform 5 m/s on 1 m cells: dt = 0.5 * 1 / 5 (float32 velocity: 1e-6 relative).
  CHECK(free.wind.dt == Approx(0.1).epsilon(1e-6));
  CHECK(free.cfl == Approx(0.5).epsilon(1e-6));
  const auto capped = coupled.step(0.03);
  CHECK(capped.wind.dt == 0.03);
  CHECK(coupled.time() == Approx(free.wind.dt + 0.03).epsilon(1e-12));  // a sum of two doubles
}

TEST_CASE("CoupledStep: a non-finite velocity stops the next step, naming the step and the field",
          "[simulation]") {
  auto* cc = fw::test::device_or_skip();
  if (!cc) return;
  fw::host::CoupledStep coupled(*cc, channel(0.5, 0.0), fw::trees::Forest(), {},
                                fw::host::TimeInputs::steady({5.0, 0.0, 0.0}));
  coupled.start();
  coupled.step();
  fw::fluid::MacVelocity velocity = coupled.wind().download_velocity();
  velocity.v[velocity.v.size() / 2] = std::numeric_limits<float>::quiet_NaN();
  coupled.wind().upload_velocity(velocity);
  try {
    coupled.step();
    FAIL("no SimulationError");
  } catch (const fw::host::SimulationError& e) {
    const std::string message = e.what();
    INFO(message);
    CHECK(message.find("step 2 ") != std::string::npos);
    CHECK(message.find("field velocity is not finite") != std::string::npos);
  }
  CHECK(coupled.steps() == 1);  // nothing moved
}

TEST_CASE("CoupledStep: a fixed dt far past the CFL limit stops before the first step", "[simulation]") {
  auto* cc = fw::test::device_or_skip();
  if (!cc) return;
  // 5 m/s, 1 m cells, dt 2 s: CFL 10 > kRunawayCfl.
  fw::host::CoupledStep coupled(*cc, channel(0.0, 2.0), fw::trees::Forest(), {},
                                fw::host::TimeInputs::steady({5.0, 0.0, 0.0}));
  coupled.start();
  try {
    coupled.step();
    FAIL("no SimulationError");
  } catch (const fw::host::SimulationError& e) {
    const std::string message = e.what();
    INFO(message);
    CHECK(message.find("step 1 ") != std::string::npos);
    CHECK(message.find("Courant number 10.00") != std::string::npos);
  }
  CHECK(coupled.steps() == 0);
  // The same dt cut to the caller's limit is a legal step.
  CHECK(coupled.step(0.1).wind.dt == 0.1);
}

TEST_CASE("CoupledStep: the scenario's largest CFL number is the runaway limit a fixed dt stops at",
          "[simulation]") {
  // time.cfl's upper bound (io/schema/Bounds.hpp) is this class's limit, which io cannot include.
  CHECK(fw::io::schema::bounds::kMaxCfl == fw::host::CoupledStep::kRunawayCfl);
}
