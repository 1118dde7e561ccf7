// host/stages/PointWindReadback: the wind at probe points, and the device memory the planner reports for it.
#include "host/stages/PointWindReadback.hpp"

#include <catch2/catch.hpp>

#include <array>
#include <vector>

#include "host/stages/WindGrid.hpp"
#include "tests/support/TestDevice.hpp"

using namespace fw;
using B = fluid::BoundaryType;

TEST_CASE(
    "PointWindReadback: a uniform wind reads the same everywhere, and its estimate is what it allocates",
    "[probes]") {
  auto* cc = test::device_or_skip();
  if (!cc) return;
  host::WindGridSetup setup;
  setup.spec.nx = 16;
  setup.spec.ny = 8;
  setup.spec.nz = 8;
  setup.spec.h = 2.0;
  setup.spec.boundary = {B::inflow, B::outflow, B::periodic, B::periodic, B::periodic, B::periodic};
  setup.ambient = {5.0, 0.0, 0.0};
  host::WindGrid wind(*cc, setup);
  wind.initialise_ambient();

  // Inside, on a face, and on the domain's corner (faces included).
  const std::vector<std::array<double, 3>> points = {{7.3, 5.1, 9.9}, {2.0, 8.0, 3.0}, {32.0, 16.0, 16.0}};
  const std::size_t before = cc->allocated_bytes();
  host::PointWindReadback sampler(*cc, setup.spec, points);
  CHECK(cc->allocated_bytes() - before == host::PointWindReadback::estimate_device_bytes(points.size()));
  CHECK(host::PointWindReadback::estimate_device_bytes(0) == 0);

  // The uniform inflow, projected: every face holds 5 m/s along x to float rounding (1e-5 of it).
  for (const auto& v : sampler.sample(wind.velocity())) {
    CHECK(v[0] == Approx(5.0).margin(5e-5));
    CHECK(v[1] == Approx(0.0).margin(5e-5));
    CHECK(v[2] == Approx(0.0).margin(5e-5));
  }
}
