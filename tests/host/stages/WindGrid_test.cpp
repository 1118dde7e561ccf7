// The wind grid as a whole on the device: input validation, conservation, obstacles, time step, determinism.
#include <catch2/catch.hpp>

#include <cmath>
#include <iterator>
#include <limits>
#include <vector>

#include "fluid/Heightmap.hpp"
#include "fluid/ReferenceStages.hpp"
#include "fluid/SolidMap.hpp"
#include "host/stages/WindGrid.hpp"
#include "tests/support/TestDevice.hpp"

using namespace fw;
namespace ref = fw::fluid::reference;
using B = fluid::BoundaryType;

namespace {

host::WindGridSetup channel(int nx, int ny, int nz, double h) {
  host::WindGridSetup setup;
  setup.spec.nx = nx;
  setup.spec.ny = ny;
  setup.spec.nz = nz;
  setup.spec.h = h;
  setup.spec.boundary = {B::inflow, B::outflow, B::periodic, B::periodic, B::periodic, B::periodic};
  setup.settings.dt = 0.1;
  setup.settings.pressure.tolerance = 1e-4;
  setup.ambient = {5.0, 0.0, 0.0};
  return setup;
}

}  // namespace

TEST_CASE("WindGrid: bad dimensions, cell size and boundary types throw before anything is allocated") {
  auto* cc = test::device_or_skip();
  if (!cc) return;
  auto expect_error = [&](host::WindGridSetup setup, const std::string& fragment) {
    try {
      host::WindGrid wind(*cc, setup);
      FAIL("no exception for a setup that should fail with '" << fragment << "'");
    } catch (const std::invalid_argument& e) {
      INFO(e.what());
      CHECK(std::string(e.what()).find(fragment) != std::string::npos);
    }
  };
  auto setup = channel(16, 8, 8, 1.0);
  setup.spec.nx = 0;
  expect_error(setup, "dimensions must be positive");
  setup = channel(16, 8, 8, 1.0);
  setup.spec.nz = -4;
  expect_error(setup, "dimensions must be positive");
  setup = channel(16, 8, 8, 0.0);
  expect_error(setup, "cell size must be > 0");
  setup = channel(16, 8, 8, -2.0);
  expect_error(setup, "cell size must be > 0");
  setup = channel(16, 8, 8, 1.0);
  setup.spec.boundary[FW_FACE_TOP] = static_cast<B>(7);
  expect_error(setup, "unknown boundary type");
}

TEST_CASE("WindGrid: a grid larger than the device memory is refused from an estimate, without allocating") {
  auto* cc = test::device_or_skip();
  if (!cc) return;
  // 1200^3 cells (1.7e9) fit the 32-bit indices but need ~100 GB: far beyond any device here.
  auto setup = channel(1200, 1200, 1200, 1.0);
  const auto bytes = host::WindGrid::estimate_device_bytes(setup);
  REQUIRE(bytes > cc->device().global_memory_bytes);
  const std::size_t before = cc->allocated_bytes();
  CHECK_THROWS_WITH(host::WindGrid(*cc, setup), Catch::Contains("device memory"));
  // Refused from the estimate alone: not one buffer was allocated (the context counts every one).
  CHECK(cc->allocated_bytes() == before);
}

TEST_CASE("WindGrid: uniform inflow through an empty periodic-sided channel stays uniform over 100 steps") {
  auto* cc = test::device_or_skip();
  if (!cc) return;
  host::WindGrid wind(*cc, channel(24, 8, 8, 2.0));
  wind.initialise_ambient();
  for (int n = 0; n < 100; ++n) wind.step();
  const auto vel = wind.download_velocity();
  double worst = 0.0;  // relative to the 5 m/s inflow
  for (float u : vel.u) worst = std::max(worst, std::abs(u - 5.0) / 5.0);
  for (float v : vel.v) worst = std::max(worst, std::abs(v) / 5.0);
  for (float w : vel.w) worst = std::max(worst, std::abs(w) / 5.0);
  CHECK(worst < 1e-5);
  CHECK(wind.time() == Approx(10.0));
}

namespace {

// A 48 x 24 x 16 channel of 1 m cells, inflow 4 m/s from the west, slip elsewhere, fixed dt 0.1 s (Courant
// numbers summing to under 1, inside every scheme's limit), solved to 1e-5, with `solids`' cells solid.
host::WindGridSetup obstacle_channel(fluid::AdvectionScheme advection) {
  host::WindGridSetup setup;
  auto& spec = setup.spec;
  spec.nx = 48;
  spec.ny = 24;
  spec.nz = 16;
  spec.h = 1.0;
  spec.boundary = {B::inflow, B::outflow, B::slip, B::slip, B::slip, B::slip};
  setup.settings.dt = 0.1;
  setup.settings.pressure.tolerance = 1e-5;
  setup.settings.advection = advection;
  setup.ambient = {4.0, 0.0, 0.0};
  return setup;
}

// Runs 60 steps, each projection converged within the tolerance asked for by the solver's own measure (the
// true relative residual), which the mass balances of the callers rest on.
fluid::MacVelocity run_obstacle_channel(host::ComputeContext& cc, const host::WindGridSetup& setup) {
  host::WindGrid wind(cc, setup);
  wind.initialise_ambient();
  for (int n = 0; n < 60; ++n) {
    const host::WindStepReport report = wind.step();
    INFO("step " << n << ": " << report.pressure.solver << ", " << report.pressure.iterations
                 << " iterations to " << report.pressure.relative_residual);
    REQUIRE(report.pressure.converged);
    REQUIRE(report.pressure.relative_residual <= setup.settings.pressure.tolerance);
  }
  return wind.download_velocity();
}

// The largest |velocity| on any face of a solid cell, and how many such faces there are (shared ones twice).
std::pair<double, std::size_t> solid_face_leak(const fluid::GridSpec& spec, const fluid::SolidMap& solids,
                                               const fluid::MacVelocity& vel) {
  std::size_t faces = 0;
  double leak = 0.0;
  for (int k = 0; k < spec.nz; ++k)
    for (int j = 0; j < spec.ny; ++j)
      for (int i = 0; i < spec.nx; ++i) {
        if (!solids.solid(i, j, k)) continue;
        for (int c = 0; c < 3; ++c)
          for (int side = 0; side < 2; ++side) {
            int idx[3] = {i, j, k};
            idx[c] += side;
            leak = std::max(
                leak, std::abs(double(vel.component(c)[ref::face_index(spec, c, idx[0], idx[1], idx[2])])));
            ++faces;
          }
      }
  return {leak, faces};
}

// The volume flux through the plane of x faces i, m^3/s.
double flux_through(const fluid::GridSpec& spec, const fluid::MacVelocity& vel, int i) {
  double sum = 0.0;
  for (int k = 0; k < spec.nz; ++k)
    for (int j = 0; j < spec.ny; ++j) sum += vel.u[ref::face_index(spec, 0, i, j, k)];
  return sum * spec.h * spec.h;
}

const fluid::AdvectionScheme kSchemes[] = {fluid::AdvectionScheme::semi_lagrangian,
                                           fluid::AdvectionScheme::maccormack,
                                           fluid::AdvectionScheme::upwind5};

}  // namespace

TEST_CASE(
    "WindGrid: no flow passes through solid faces, and the flow goes around a box, under every scheme") {
  auto* cc = test::device_or_skip();
  if (!cc) return;
  const auto advection = GENERATE(from_range(std::begin(kSchemes), std::end(kSchemes)));
  INFO("advection " << fluid::to_string(advection));
  host::WindGridSetup setup = obstacle_channel(advection);
  const auto& spec = setup.spec;
  fluid::SolidMap solids(spec);
  solids.add(fluid::SolidBox{"block", {18.0, 12.0, 8.0}, {4.0, 8.0, 8.0}, 0.0});  // x 16-20, y 8-16, z 4-12
  setup.solid = solids.cells();
  const auto vel = run_obstacle_channel(*cc, setup);

  // Every face of a solid cell carries exactly zero velocity.
  const auto [leak, solid_faces] = solid_face_leak(spec, solids, vel);
  CHECK(solid_faces == 4 * 8 * 8 * 6);
  CHECK(leak == 0.0);

  // Mass is conserved through every cross-section: the flux through x = 18 (inside the block's span)
  // equals the inflow flux, so the air that the block stops goes around it.
  const double inflow = flux_through(spec, vel, 0);
  CHECK(inflow == Approx(4.0 * 24 * 16).epsilon(1e-6));
  CHECK(flux_through(spec, vel, 18) ==
        Approx(inflow).epsilon(1e-4));  // solver tolerance 1e-5 plus float sums
  // Around: faster than the inflow beside and above the block, slower in its wake.
  CHECK(vel.u[ref::face_index(spec, 0, 18, 4, 8)] > 4.4);    // beside (y 4.5)
  CHECK(vel.u[ref::face_index(spec, 0, 18, 12, 14)] > 4.4);  // above (z 14.5)
  CHECK(vel.u[ref::face_index(spec, 0, 22, 12, 8)] < 2.0);   // 2 m behind the lee face
  // And it is divergence-free.
  const auto levels = fluid::build_fine_pressure_level(spec, setup.solid);
  CHECK(ref::max_divergence(spec, levels, vel) * spec.h / 4.0 < 1e-4);
}

TEST_CASE("WindGrid: the flow crosses a ridge of terrain, faster over its crest, under every scheme") {
  auto* cc = test::device_or_skip();
  if (!cc) return;
  const auto advection = GENERATE(from_range(std::begin(kSchemes), std::end(kSchemes)));
  INFO("advection " << fluid::to_string(advection));
  host::WindGridSetup setup = obstacle_channel(advection);
  const auto& spec = setup.spec;
  // A ridge across the channel, 6 m high at x = 20 m with a Gaussian flank of 5 m: a third of the 16 m
  // column, so the blocked flow speeds up over the crest by about 1 / (1 - 6/16) = 1.6 in the mean.
  std::vector<double> heights;
  const int columns = spec.nx, rows = spec.ny;
  for (int row = 0; row < rows; ++row)
    for (int column = 0; column < columns; ++column) {
      const double x = column + 0.5;
      heights.push_back(6.0 * std::exp(-std::pow((x - 20.0) / 5.0, 2)));
    }
  fluid::SolidMap solids(spec);
  REQUIRE(solids.add_terrain(fluid::Heightmap(columns, rows, 1.0, {0.5, 0.5}, heights)) > 0);
  setup.solid = solids.cells();
  const auto vel = run_obstacle_channel(*cc, setup);

  CHECK(solid_face_leak(spec, solids, vel).first == 0.0);
  const double inflow = flux_through(spec, vel, 0);
  CHECK(flux_through(spec, vel, 20) ==
        Approx(inflow).epsilon(1e-4));  // solver tolerance 1e-5 plus float sums
  // Just above the crest (cells 6 and up are fluid there): faster than the inflow, as the mass balance asks.
  double crest = 0.0;
  for (int j = 0; j < spec.ny; ++j) crest += vel.u[ref::face_index(spec, 0, 20, j, 7)] / spec.ny;
  CHECK(crest > 1.3 * 4.0);
  const auto levels = fluid::build_fine_pressure_level(spec, setup.solid);
  CHECK(ref::max_divergence(spec, levels, vel) * spec.h / 4.0 < 1e-4);
}

TEST_CASE("WindGrid: the CFL time step is cfl * h / max|u|, capped at max_dt") {
  auto* cc = test::device_or_skip();
  if (!cc) return;
  auto setup = channel(16, 8, 8, 2.0);
  setup.settings.cfl = 0.5;
  setup.settings.max_dt = 10.0;
  host::WindGrid wind(*cc, setup);
  wind.initialise_ambient();
  CHECK(wind.step().dt == Approx(0.5 * 2.0 / 5.0).epsilon(1e-6));
  setup.settings.max_dt = 0.1;
  host::WindGrid capped(*cc, setup);
  capped.initialise_ambient();
  CHECK(capped.step().dt == Approx(0.1));
}

TEST_CASE("WindGrid: a NaN in the field stops the CFL step with a message naming the step") {
  auto* cc = test::device_or_skip();
  if (!cc) return;
  auto setup = channel(16, 8, 8, 2.0);
  setup.settings.cfl = 0.5;
  host::WindGrid wind(*cc, setup);
  wind.initialise_ambient();
  wind.step();
  auto vel = wind.download_velocity();
  vel.v[10] = std::numeric_limits<float>::quiet_NaN();
  wind.upload_velocity(vel);
  CHECK_THROWS_WITH(wind.step(), Catch::Contains("step 2"));
}

TEST_CASE("WindGrid: the same setup run twice gives bit-identical fields") {
  auto* cc = test::device_or_skip();
  if (!cc) return;
  auto setup = channel(24, 16, 8, 1.0);
  setup.spec.boundary = {B::inflow, B::outflow, B::slip, B::slip, B::no_slip, B::slip};
  setup.settings.advection = fluid::AdvectionScheme::maccormack;
  setup.settings.vorticity_confinement = 0.2;
  setup.gusts.push_back(
      FwGust{0.2f, 2.0f, 3.0f, 4.0f, {6.0f, 8.0f, 4.0f}, {5.0f, 0.0f, 0.0f}, {0.0f, 1.0f, 0.0f}});
  fluid::SolidMap solids(setup.spec);
  solids.add(fluid::SolidCylinder{"post", {10.0, 8.0, 0.0}, 2.5, 6.0});
  setup.solid = solids.cells();
  auto run = [&] {
    host::WindGrid wind(*cc, setup);
    wind.initialise_ambient();
    for (int n = 0; n < 20; ++n) wind.step();
    return wind.download_velocity();
  };
  const auto a = run(), b = run();
  for (int c = 0; c < 3; ++c) CHECK(a.component(c) == b.component(c));
  // The gust and the post made the field non-trivial.
  double vmax = 0.0;
  for (float v : a.v) vmax = std::max(vmax, double(std::abs(v)));
  CHECK(vmax > 0.5);
}
