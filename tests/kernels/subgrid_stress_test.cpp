// The subgrid and wall stresses (kernels/subgrid_stress.cl): the kernels against fluid::reference
// eddy_viscosity, diffuse_eddy and wall_stress, and their physics through host::WindGrid's "subgrid" and
// "wall" stages.
#include <catch2/catch.hpp>

#include <cmath>
#include <cstring>
#include <map>
#include <string>
#include <vector>

#include "fluid/PressureLevels.hpp"
#include "fluid/ReferenceStages.hpp"
#include "fluid/SubgridStress.hpp"
#include "host/stages/FluidStages.hpp"
#include "host/stages/WindGrid.hpp"
#include "tests/support/Fields.hpp"
#include "tests/support/TestDevice.hpp"

using namespace fw;
namespace ref = fw::fluid::reference;
using B = fluid::BoundaryType;

namespace {

constexpr double kSmagorinsky = 0.17;  // Lilly's value, inside the typical 0.1-0.2
constexpr double kRoughness = 0.1;     // m: short vegetation
constexpr double kAirDensity = 1.225;  // kg/m^3, only to state the momentum in newtons

// Eddy viscosity: nine float differences of velocities of ~10 m/s over 2h and a square root; relative to the
// field's largest value that is a few float ulps of the velocities over |S| ~ 0.5 1/s, about 1e-6.
constexpr double kViscosityTolerance = 1e-5;
// Eddy diffusion: q plus a small update, so a few float ulps of the largest velocity.
constexpr double kDiffusionTolerance = 2e-6;
// Wall stress: one square root, a few sums and one division per face, so a few float ulps of each face.
constexpr double kWallTolerance = 2e-6;

// mixed_boundary_spec (inflow west, outflow east, periodic south/north, slip top) with the given ground.
fluid::GridSpec spec_with_ground(B ground, fluid::GridSpec spec = test::mixed_boundary_spec()) {
  spec.boundary[FW_FACE_GROUND] = ground;
  return spec;
}

// The yawed test box (k 2-5) over a terrain step: one cell high for i 10-15, two cells from i 16 on.
std::vector<std::uint8_t> terrain_and_box(const fluid::GridSpec& spec) {
  auto solid = test::box_solid(spec);
  for (int k = 0; k < 2; ++k)
    for (int j = 0; j < spec.ny; ++j)
      for (int i = 10; i < spec.nx; ++i)
        if (k == 0 || i >= 16)
          solid[std::size_t(i) + std::size_t(spec.nx) * (j + std::size_t(spec.ny) * k)] = 1;
  return solid;
}

// A shear flow u = 0.5 z, v = 0.2 z (1/s, z the face's height) with random perturbations of 0.5, 0.5 and
// 0.3 m/s.
fluid::MacVelocity shear_flow(const fluid::GridSpec& spec, std::uint32_t seed) {
  auto vel = test::random_velocity(spec, 0.5, seed);
  for (int c = 0; c < 2; ++c) {
    const double shear = c == 0 ? 0.5 : 0.2;
    const int ex = ref::extent(spec, c, 0), ey = ref::extent(spec, c, 1);
    for (int k = 0; k < spec.nz; ++k)
      for (int j = 0; j < ey; ++j)
        for (int i = 0; i < ex; ++i)
          vel.component(c)[ref::face_index(spec, c, i, j, k)] += shear * (k + 0.5) * spec.h;
  }
  for (auto& w : vel.w) w *= 0.6f;
  return vel;
}

struct SgsFixture {
  host::ComputeContext& cc;
  fluid::GridSpec spec;
  std::vector<std::uint8_t> solid = terrain_and_box(spec);
  fluid::PressureLevel fine = fluid::build_fine_pressure_level(spec, solid);
  fluid::InflowState inflow = test::test_inflow(spec);
  host::FluidStages stages{cc, spec};
  cl::Buffer mask = cc.buffer(fine.cell_count());

  SgsFixture(host::ComputeContext& c, B ground, const fluid::GridSpec& grid = test::mixed_boundary_spec())
      : cc(c), spec(spec_with_ground(ground, grid)) {
    stages.set_profile(test::upload_profile(cc, inflow, spec));
    cc.queue().enqueueWriteBuffer(mask, CL_TRUE, 0, fine.cell_count(), fine.mask.data());
  }
  void set_dt(float dt) {
    FwStep s{};
    s.dt = dt;
    s.time = 3.0f;
    for (int a = 0; a < 3; ++a) s.ambient[a] = inflow.ambient[a];
    host::set_step_turbulence(s, inflow);
    stages.set_step(s);
  }
};

double max_of(const std::vector<float>& x) {
  double m = 0.0;
  for (float v : x) m = std::max(m, double(v));
  return m;
}

// Largest |a - b| / |b| over faces (faces with b = 0 compared absolutely).
double face_relative_error(const std::vector<float>& a, const std::vector<float>& b) {
  double worst = 0.0;
  for (std::size_t i = 0; i < a.size(); ++i)
    worst = std::max(worst, std::abs(double(a[i]) - b[i]) / std::max(std::abs(double(b[i])), 1e-30));
  return worst;
}

bool identical(const fluid::MacVelocity& a, const fluid::MacVelocity& b) {
  for (int c = 0; c < 3; ++c)
    if (a.component(c).size() != b.component(c).size() ||
        std::memcmp(a.component(c).data(), b.component(c).data(), a.component(c).size() * sizeof(float)) != 0)
      return false;
  return true;
}

// A box of nx x ny x nz cells of size h, periodic in x and y, `vertical` on the ground and the top.
fluid::GridSpec periodic_box(int nx, int ny, int nz, double h, B vertical) {
  fluid::GridSpec spec;
  spec.nx = nx;
  spec.ny = ny;
  spec.nz = nz;
  spec.h = h;
  spec.boundary = {B::periodic, B::periodic, B::periodic, B::periodic, vertical, vertical};
  return spec;
}

}  // namespace

TEST_CASE("subgrid: eddy viscosity and eddy diffusion kernels match the CPU reference over a terrain step",
          "[subgrid]") {
  auto* cc = test::device_or_skip();
  if (!cc) return;
  // The ragged grid's ranges end in part-filled work-groups (test::ragged_spec).
  const fluid::GridSpec grid = GENERATE(test::mixed_boundary_spec(), test::ragged_spec());
  for (B ground : {B::no_slip, B::slip})
    for (bool wall_slip : {false, true}) {
      INFO("grid " << grid.nx << " x " << grid.ny << " x " << grid.nz << ", ground "
                   << fluid::to_string(ground) << ", wall_slip " << wall_slip);
      SgsFixture f(*cc, ground, grid);
      const double dt = 0.4;
      f.set_dt(float(dt));
      const auto vel = shear_flow(f.spec, 11);
      auto dvel = f.stages.allocate_velocity();
      auto diffused = f.stages.allocate_velocity();
      test::upload(*cc, vel, dvel);
      cl::Buffer nu = cc->buffer(f.spec.cell_count() * sizeof(float));
      const double cap = fluid::eddy_viscosity_cap(f.spec.h, dt);
      f.stages.enqueue_eddy_viscosity(float(kSmagorinsky), float(cap), f.mask, dvel, nu);
      const auto device_nu = test::download(*cc, nu, f.spec.cell_count());
      const auto expected_nu = ref::eddy_viscosity(f.spec, f.solid, vel, kSmagorinsky, cap);
      CHECK(test::relative_error(device_nu, expected_nu) < kViscosityTolerance);
      CHECK(max_of(expected_nu) < cap);   // the formula is compared here, not the clamp
      CHECK(max_of(expected_nu) > 0.02);  // (0.34 m)^2 x |S| of order 0.5 1/s
      for (std::size_t c = 0; c < f.solid.size(); ++c)
        if (f.solid[c]) CHECK(device_nu[c] == 0.0f);

      f.stages.enqueue_diffuse_eddy(wall_slip, f.mask, nu, dvel, diffused);
      const auto expected = ref::diffuse_eddy(f.spec, f.solid, f.inflow, vel, expected_nu, dt, wall_slip);
      CHECK(test::relative_error(test::download(*cc, diffused, f.spec), expected) < kDiffusionTolerance);
      if (wall_slip) {  // the rule changes the faces above the solids' tops, and only u and v
        const auto no_slip_rule = ref::diffuse_eddy(f.spec, f.solid, f.inflow, vel, expected_nu, dt, false);
        CHECK_FALSE(identical(no_slip_rule, expected));
        CHECK(no_slip_rule.w == expected.w);
      }
    }
}

TEST_CASE(
    "subgrid: with the inflow turbulence on, the eddy diffusion's inflow ghosts match the CPU reference",
    "[subgrid]") {
  // The west ghosts of u, v and w are prescribed; with the turbulence on the kernel reads them from the
  // shell that set_step samples, the reference from the box itself.
  auto* cc = test::device_or_skip();
  if (!cc) return;
  SgsFixture f(*cc, B::no_slip);
  test::add_small_turbulence(f.inflow);
  f.stages.set_profile(test::upload_profile(*cc, f.inflow, f.spec));
  const double dt = 0.4;
  f.set_dt(float(dt));
  const auto vel = shear_flow(f.spec, 13);
  auto dvel = f.stages.allocate_velocity();
  auto diffused = f.stages.allocate_velocity();
  test::upload(*cc, vel, dvel);
  cl::Buffer nu = cc->buffer(f.spec.cell_count() * sizeof(float));
  const double cap = fluid::eddy_viscosity_cap(f.spec.h, dt);
  f.stages.enqueue_eddy_viscosity(float(kSmagorinsky), float(cap), f.mask, dvel, nu);
  const auto expected_nu = ref::eddy_viscosity(f.spec, f.solid, vel, kSmagorinsky, cap);
  f.stages.enqueue_diffuse_eddy(true, f.mask, nu, dvel, diffused);
  const auto expected = ref::diffuse_eddy(f.spec, f.solid, f.inflow, vel, expected_nu, dt, true);
  // The diffusion's tolerance, plus the float box sample's few ulps (as in the ghosts' tests).
  CHECK(test::relative_error(test::download(*cc, diffused, f.spec), expected) < kDiffusionTolerance + 1e-5);
  // The turbulence must reach the result: the laminar inflow gives another field.
  auto laminar = f.inflow;
  laminar.turbulence_sigma = 0.0f;
  const auto without = ref::diffuse_eddy(f.spec, f.solid, laminar, vel, expected_nu, dt, true);
  CHECK(test::relative_error(without, expected) > 1e-4);
}

TEST_CASE("subgrid: the clamp at 0.15 h^2 / dt matches the CPU reference where the strain is large",
          "[subgrid]") {
  auto* cc = test::device_or_skip();
  if (!cc) return;
  SgsFixture f(*cc, B::slip);
  const double dt = 8.0;  // cap 0.075 m^2/s: below (C_s h)^2 |S| in part of the field
  f.set_dt(float(dt));
  const auto vel = shear_flow(f.spec, 12);
  auto dvel = f.stages.allocate_velocity();
  auto diffused = f.stages.allocate_velocity();
  test::upload(*cc, vel, dvel);
  cl::Buffer nu = cc->buffer(f.spec.cell_count() * sizeof(float));
  const double cap = fluid::eddy_viscosity_cap(f.spec.h, dt);
  f.stages.enqueue_eddy_viscosity(float(kSmagorinsky), float(cap), f.mask, dvel, nu);
  const auto device_nu = test::download(*cc, nu, f.spec.cell_count());
  const auto expected_nu = ref::eddy_viscosity(f.spec, f.solid, vel, kSmagorinsky, cap);
  CHECK(test::relative_error(device_nu, expected_nu) < kViscosityTolerance);
  std::size_t capped = 0, free = 0;
  for (float x : expected_nu) {
    if (x == float(cap)) ++capped;
    if (x > 0.0f && x < float(cap)) ++free;
  }
  CHECK(capped > 100);
  CHECK(free > 100);
  // The diffusion at the clamp, nu dt / h^2 = 0.15, still matches.
  f.stages.enqueue_diffuse_eddy(true, f.mask, nu, dvel, diffused);
  const auto device = test::download(*cc, diffused, f.spec);
  const auto expected = ref::diffuse_eddy(f.spec, f.solid, f.inflow, vel, expected_nu, dt, true);
  CHECK(test::relative_error(device, expected) < kDiffusionTolerance);
}

TEST_CASE("subgrid: a uniform shear u = G z gives (C_s h)^2 |G| in every cell on the device", "[subgrid]") {
  auto* cc = test::device_or_skip();
  if (!cc) return;
  // 40 cells along x: two whole lane blocks and a part one.
  const auto spec = periodic_box(40, 6, 16, 1.0, B::slip);
  host::FluidStages stages(*cc, spec);
  constexpr double G = 0.5;  // 1/s; face values G (k + 1/2) h are exact in float, so are the differences
  fluid::MacVelocity vel(spec);
  for (int k = 0; k < spec.nz; ++k)
    for (int j = 0; j < spec.ny; ++j)
      for (int i = 0; i <= spec.nx; ++i)
        vel.u[ref::face_index(spec, 0, i, j, k)] = float(G * (k + 0.5) * spec.h);
  auto dvel = stages.allocate_velocity();
  test::upload(*cc, vel, dvel);
  const auto fine = fluid::build_fine_pressure_level(spec, {});
  cl::Buffer mask = cc->buffer(fine.cell_count()), nu = cc->buffer(spec.cell_count() * sizeof(float));
  cc->queue().enqueueWriteBuffer(mask, CL_TRUE, 0, fine.cell_count(), fine.mask.data());
  stages.enqueue_eddy_viscosity(float(kSmagorinsky), 1e9f, mask, dvel, nu);
  const double expected = std::pow(kSmagorinsky * spec.h, 2) * G;
  // One-sided at the slip walls and central inside: both exact for a linear profile, so only the float
  // rounding of (C_s h)^2 and of the square root remain.
  for (float x : test::download(*cc, nu, spec.cell_count())) CHECK(x == Approx(expected).epsilon(1e-6));
}

TEST_CASE("subgrid: a helical shear decays at nu_t k^2 with nu_t = (C_s h)^2 |S| through WindGrid",
          "[subgrid]") {
  // u = A sin(k z), v = A cos(k z) on a fully periodic box: |S| = A k is the same in every cell (central
  // differences: A sin(k h) / h), so nu_t is uniform, and both components decay at nu_t k^2 with
  // nu_t = (C_s h)^2 k A(t):  dA/dt = -(C_s h)^2 k^3 A^2,  A(t) = A0 / (1 + (C_s h)^2 k^3 A0 t).
  // The fields do not depend on x or y, so advection and the projection leave them exactly alone.
  // Discretely, step n multiplies A by 1 - dt nu_n (4 / h^2) sin^2(k h / 2), nu_n = (C_s h)^2 A_n sin(k h) /
  // h.
  auto* cc = test::device_or_skip();
  if (!cc) return;
  host::WindGridSetup setup;
  setup.spec = periodic_box(4, 4, 32, 1.0, B::periodic);
  constexpr double Cs = 0.2, A0 = 10.0, dt = 1.0;  // nu_t dt / h^2 = 0.078: the clamp stays out of it
  constexpr int kSteps = 300;
  setup.settings.smagorinsky_constant = Cs;
  setup.settings.dt = dt;
  const auto& spec = setup.spec;
  const double k = 2.0 * M_PI / (spec.nz * spec.h), h = spec.h;
  host::WindGrid wind(*cc, setup);
  fluid::MacVelocity vel(spec);
  for (int c = 0; c < 2; ++c) {
    const int ex = ref::extent(spec, c, 0), ey = ref::extent(spec, c, 1);
    for (int kk = 0; kk < spec.nz; ++kk)
      for (int j = 0; j < ey; ++j)
        for (int i = 0; i < ex; ++i) {
          const double z = (kk + 0.5) * h;
          vel.component(c)[ref::face_index(spec, c, i, j, kk)] =
              float(A0 * (c == 0 ? std::sin(k * z) : std::cos(k * z)));
        }
  }
  wind.upload_velocity(vel);
  for (int n = 0; n < kSteps; ++n) wind.step();
  const auto out = wind.download_velocity();

  // Amplitude of each component: its projection on sin or cos, and what is left over.
  double amplitude[2], leftover = 0.0;
  for (int c = 0; c < 2; ++c) {
    const int ex = ref::extent(spec, c, 0), ey = ref::extent(spec, c, 1);
    double sum = 0.0;
    for (int kk = 0; kk < spec.nz; ++kk)
      for (int j = 0; j < ey; ++j)
        for (int i = 0; i < ex; ++i) {
          const double z = (kk + 0.5) * h;
          sum += out.component(c)[ref::face_index(spec, c, i, j, kk)] *
                 (c == 0 ? std::sin(k * z) : std::cos(k * z));
        }
    amplitude[c] = 2.0 * sum / (double(spec.nz) * ex * ey);
  }
  for (int c = 0; c < 2; ++c) {
    const int ex = ref::extent(spec, c, 0), ey = ref::extent(spec, c, 1);
    for (int kk = 0; kk < spec.nz; ++kk)
      for (int j = 0; j < ey; ++j)
        for (int i = 0; i < ex; ++i) {
          const double z = (kk + 0.5) * h;
          const double fit = amplitude[c] * (c == 0 ? std::sin(k * z) : std::cos(k * z));
          leftover = std::max(leftover, std::abs(out.component(c)[ref::face_index(spec, c, i, j, kk)] - fit));
        }
  }
  double discrete = A0;
  const double lambda = 4.0 / (h * h) * std::pow(std::sin(0.5 * k * h), 2);
  for (int n = 0; n < kSteps; ++n)
    discrete *= 1.0 - dt * std::pow(Cs * h, 2) * discrete * std::sin(k * h) / h * lambda;
  const double t = kSteps * dt;
  const double continuum = A0 / (1.0 + std::pow(Cs * h, 2) * std::pow(k, 3) * A0 * t);
  WARN("helical shear: A(" << t << " s) = " << amplitude[0] << ", " << amplitude[1] << " m/s; discrete "
                           << discrete << ", continuum " << continuum << " (A0 = " << A0 << ")");
  // Float steps against the double recursion: 300 roundings of ~1e-7 relative each.
  CHECK(amplitude[0] == Approx(discrete).epsilon(1e-4));
  CHECK(amplitude[1] == Approx(discrete).epsilon(1e-4));
  // The shape stays a pure sine: the nonlinearity has nothing to act on when |S| is uniform.
  CHECK(leftover < 1e-4 * A0);
  // The decay has to be substantial for the comparison to mean something.
  CHECK(continuum < 0.6 * A0);
  // Against the continuum: the second-order truncation at k h = 0.196 slows the rate by
  // (1 - (kh)^2/6)(1 - (kh)^2/12) = 0.990, which moves A(t) by 0.5% here; 1.5% allows for it and fails a
  // factor-of-sqrt(2) or C_s-not-squared error by far.
  CHECK(amplitude[0] == Approx(continuum).epsilon(0.015));
}

TEST_CASE("subgrid: the eddy diffusion conserves momentum where the eddy viscosity varies", "[subgrid]") {
  // Periodic sideways over slip walls, a random shear flow: each pair of u (or v) faces exchanges the same
  // flux and the slip ghosts exchange none, so the sum of u over the faces (the periodic twin counted once)
  // does not change, though nu_t varies by a factor of three from cell to cell.
  auto* cc = test::device_or_skip();
  if (!cc) return;
  const auto spec = periodic_box(16, 12, 10, 2.0, B::slip);
  host::FluidStages stages(*cc, spec);
  FwStep s{};
  s.dt = 2.0f;
  stages.set_step(s);
  auto vel = shear_flow(spec, 31);
  test::match_periodic_faces(spec, vel);
  const auto fine = fluid::build_fine_pressure_level(spec, {});
  cl::Buffer mask = cc->buffer(fine.cell_count()), nu = cc->buffer(spec.cell_count() * sizeof(float));
  cc->queue().enqueueWriteBuffer(mask, CL_TRUE, 0, fine.cell_count(), fine.mask.data());
  auto dvel = stages.allocate_velocity();
  auto diffused = stages.allocate_velocity();
  test::upload(*cc, vel, dvel);
  stages.enqueue_eddy_viscosity(float(kSmagorinsky), float(fluid::eddy_viscosity_cap(spec.h, s.dt)), mask,
                                dvel, nu);
  const auto nu_t = test::download(*cc, nu, spec.cell_count());
  double lo = 1e30, hi = 0.0;
  for (float x : nu_t) lo = std::min(lo, double(x)), hi = std::max(hi, double(x));
  CHECK(hi > 3.0 * lo);
  stages.enqueue_diffuse_eddy(false, mask, nu, dvel, diffused);
  const auto out = test::download(*cc, diffused, spec);
  for (int c = 0; c < 2; ++c) {
    INFO("component " << c);
    const int ex = ref::extent(spec, c, 0), ey = ref::extent(spec, c, 1);
    double net = 0.0, moved = 0.0;  // m/s summed over faces
    for (int k = 0; k < spec.nz; ++k)
      for (int j = 0; j < ey - (c == 1); ++j)
        for (int i = 0; i < ex - (c == 0); ++i) {
          const std::size_t f = ref::face_index(spec, c, i, j, k);
          net += double(out.component(c)[f]) - vel.component(c)[f];
          moved += std::abs(double(out.component(c)[f]) - vel.component(c)[f]);
        }
    // Float rounding of the faces' updates, ~1e-7 of ~10 m/s each, against ~1e-2 m/s moved per face.
    CHECK(std::abs(net) < 1e-5 * moved);
    CHECK(moved > 1.0);
  }
}

TEST_CASE("wall: the wall stress kernels match the CPU reference over a terrain step and a box roof",
          "[wall]") {
  auto* cc = test::device_or_skip();
  if (!cc) return;
  SgsFixture f(*cc, B::slip);
  const double dt = 0.6;
  f.set_dt(float(dt));
  const auto vel = shear_flow(f.spec, 21);
  auto dvel = f.stages.allocate_velocity();
  test::upload(*cc, vel, dvel);
  const auto walls = fluid::wall_cells(f.spec, f.solid);
  const host::CellBox box = host::nonzero_cell_box(f.spec, walls);
  CHECK(box.first[2] == 0);
  CHECK(box.count[2] >= 6);  // the ground, the step's two levels and the box's roof near k = 6
  const double cw = fluid::wall_drag_coefficient(f.spec.h, kRoughness);
  auto list = f.stages.upload_wall_faces(host::list_wall_faces(f.spec, walls));
  f.stages.enqueue_wall_stress(float(cw), list, dvel);
  const auto device = test::download(*cc, dvel, f.spec);
  const auto expected = ref::wall_stress(f.spec, f.solid, vel, cw, dt);
  std::size_t changed = 0;
  for (int c = 0; c < 2; ++c) {
    INFO("component " << c);
    CHECK(face_relative_error(device.component(c), expected.component(c)) < kWallTolerance);
    for (std::size_t i = 0; i < vel.component(c).size(); ++i) {
      const float before = vel.component(c)[i], after = device.component(c)[i];
      CHECK(std::abs(after) <= std::abs(before));  // implicit: slows down, never reverses
      CHECK(after * before >= 0.0f);
      changed += after != before;
    }
  }
  CHECK(device.w == vel.w);
  // Every wall cell's u and v faces, about 4 a cell shared between neighbours: of order 2 x 24 x 16.
  double wall_count = 0.0;
  for (float x : walls) wall_count += x;
  CHECK(changed > std::size_t(1.5 * wall_count));
  CHECK(changed < std::size_t(4.5 * wall_count));
}

TEST_CASE("wall: one step on a uniform wind removes rho u_star^2 x area x dt of momentum", "[wall]") {
  // Periodic x and y over a slip ground: every ground cell is a wall cell, every ground face has weight 1.
  // Implicitly, U_1 -> U_1 / (1 + dt C_w |U_1| / h), so the layer (mass rho h A) loses
  // rho A dt C_w |U^n| U^(n+1): the log law's tau = rho u*^2 with u*^2 = C_w |U^n| |U^(n+1)|.
  auto* cc = test::device_or_skip();
  if (!cc) return;
  const auto spec = periodic_box(8, 6, 3, 2.0, B::slip);
  host::FluidStages stages(*cc, spec);
  const double dt = 0.8, U[2] = {6.0, -2.5}, z0 = 0.05;
  FwStep s{};
  s.dt = float(dt);
  stages.set_step(s);
  fluid::MacVelocity vel(spec);
  std::fill(vel.u.begin(), vel.u.end(), float(U[0]));
  std::fill(vel.v.begin(), vel.v.end(), float(U[1]));
  auto dvel = stages.allocate_velocity();
  test::upload(*cc, vel, dvel);
  const double cw = fluid::wall_drag_coefficient(spec.h, z0);
  auto list = stages.upload_wall_faces(host::list_wall_faces(spec, fluid::wall_cells(spec, {})));
  stages.enqueue_wall_stress(float(cw), list, dvel);
  const auto out = test::download(*cc, dvel, spec);

  const double speed = std::hypot(U[0], U[1]);
  const double factor = 1.0 / (1.0 + dt * cw * speed / spec.h);
  double loss[2] = {0.0, 0.0};  // N s over the layer
  for (int c = 0; c < 2; ++c) {
    const int ex = ref::extent(spec, c, 0), ey = ref::extent(spec, c, 1);
    for (int k = 0; k < spec.nz; ++k)
      for (int j = 0; j < ey; ++j)
        for (int i = 0; i < ex; ++i) {
          const float q = out.component(c)[ref::face_index(spec, c, i, j, k)];
          // A few float ulps: the division and the speed's square root.
          CHECK(q == Approx((k == 0 ? factor : 1.0) * U[c]).epsilon(kWallTolerance));
          const bool seam_twin = (c == 0 ? i : j) == (c == 0 ? spec.nx : spec.ny);  // counted once
          if (k == 0 && !seam_twin) loss[c] += kAirDensity * (U[c] - q) * std::pow(spec.h, 3);
        }
  }
  const double area = spec.nx * spec.ny * spec.h * spec.h;
  const double u_star_squared = cw * speed * (factor * speed);  // C_w |U^n| |U^(n+1)|
  const double expected = kAirDensity * u_star_squared * area * dt;
  // Sums of differences of ~0.3 m/s between floats of ~6 m/s: about 1e-6 relative.
  CHECK(std::hypot(loss[0], loss[1]) == Approx(expected).epsilon(1e-5));
  CHECK(loss[0] / loss[1] == Approx(U[0] / U[1]).epsilon(1e-5));  // along the wind
  // The same u* from the log law's form kappa |U| / ln(z1 / z0), the speed taken as the geometric mean.
  const double u_star = fluid::kVonKarman * std::sqrt(speed * factor * speed) / std::log(0.5 * spec.h / z0);
  CHECK(u_star * u_star == Approx(u_star_squared).epsilon(1e-12));
  for (float w : out.w) CHECK(w == 0.0f);
}

TEST_CASE("wall: a body force balancing the wall stress drives the first cell to the log-law speed",
          "[wall][subgrid]") {
  // A column of nz cells over a slip ground, periodic sideways, pushed by g. In the steady state the ground
  // carries the whole force, u*^2 = g H (H = nz h), so the log law gives U_1 = (u* / kappa) ln(z_1 / z0) =
  // sqrt(g H / C_w). Split into stages, the first cell enters the wall stage at V and leaves it at
  // U = V / (1 + dt C_w V / h), and the balance reads C_w U V = g H: the log-law speed is the geometric mean
  // of the two, and U is below it by about (V - U) / 2 = g H dt / (2 h) (1% here). With nz > 1 the subgrid
  // stage carries the force down to the first cell; only a momentum-conserving eddy diffusion keeps the
  // balance (the non-conservative nu_t laplacian(u) made the wall carry 1.69 g H).
  auto* cc = test::device_or_skip();
  if (!cc) return;
  const double g = 0.01, z0 = 0.05, dt = 1.0, direction = 30.0 * M_PI / 180.0;  // m/s^2, m, s
  for (int nz : {1, 4}) {
    INFO(nz << " layers");
    host::WindGridSetup setup;
    setup.spec = periodic_box(2, 2, nz, 2.0, B::slip);
    setup.settings.wall_roughness_length = z0;
    setup.settings.smagorinsky_constant = nz > 1 ? kSmagorinsky : 0.0;
    setup.settings.body_force = {g * std::cos(direction), g * std::sin(direction), 0.0};
    setup.settings.dt = dt;
    host::WindGrid wind(*cc, setup);
    CHECK(wind.wall_stress_enabled());
    // From rest: the single layer relaxes like tanh(t g / U_1), time constant 100 s; the column of four
    // diffuses in over H^2 / nu_t ~ 1000 s. 3000 s leave less than 1e-7 of either (checked at 6000 s).
    for (int n = 0; n < 3000; ++n) wind.step();
    const auto out = wind.download_velocity();
    const double u = out.u[0], v = out.v[0];
    for (int f = 0; f < 6; ++f) CHECK(out.u[f] == out.u[0]);  // the first layer is horizontally uniform
    const double h = setup.spec.h, H = nz * h;
    const double cw = fluid::wall_drag_coefficient(h, z0);
    const double speed = std::hypot(u, v);
    const double entering = speed / (1.0 - dt * cw * speed / h);  // V, from U = V / (1 + dt C_w V / h)
    const double u_star = std::sqrt(g * H);
    const double log_law = u_star / fluid::kVonKarman * std::log(0.5 * h / z0);
    WARN(nz << " layers: U_1 = " << speed << " m/s leaving the wall stage, " << entering
            << " entering; log law " << log_law << " m/s for u* = " << u_star
            << " m/s; C_w U V / (g H) = " << cw * speed * entering / (g * H));
    // The balance, to float precision: each step adds g dt = 0.01 m/s to floats of up to 5.5 m/s, whose
    // half ulp is 2.4e-5 of that increment, and the steady state carries that rounding.
    CHECK(cw * speed * entering == Approx(g * H).epsilon(1e-4));
    CHECK(std::sqrt(speed * entering) == Approx(log_law).epsilon(1e-4));
    // The first cell's own speed: below the log law by the splitting offset g H dt / (2 h U) (0.5% for one
    // layer, 1.0% for four), and by no more.
    CHECK(speed < log_law);
    CHECK(speed > log_law * (1.0 - 1.2 * g * H * dt / (2.0 * h * log_law)));
    CHECK(std::atan2(v, u) == Approx(direction).epsilon(1e-5));  // the stress opposes the wind
  }
}

TEST_CASE("subgrid and wall: switched off, the step is bit-identical and neither stage runs",
          "[subgrid][wall]") {
  auto* cc = test::device_or_skip();
  if (!cc) return;
  host::WindGridSetup setup;
  setup.spec = spec_with_ground(B::slip);
  setup.solid = terrain_and_box(setup.spec);
  setup.settings.dt = 0.3;
  setup.profile.type = fluid::InflowProfile::Type::log;
  setup.profile.reference_height = 10.0;
  setup.profile.roughness_length = 0.5;
  setup.ambient = {7.0, 3.0, 0.0};
  constexpr int kSteps = 8;
  auto run = [&](const host::WindGridSetup& s, std::map<std::string, double>* stages) {
    host::WindGrid wind(*cc, s);
    wind.set_stage_timing(stages != nullptr);
    wind.initialise_ambient();
    for (int n = 0; n < kSteps; ++n) wind.step();
    if (stages) *stages = wind.stage_ms();
    return wind.download_velocity();
  };
  const auto plain = run(setup, nullptr);
  auto zero = setup;
  zero.settings.smagorinsky_constant = 0.0;
  zero.settings.wall_roughness_length = 0.0;
  std::map<std::string, double> stages;
  CHECK(identical(run(zero, &stages), plain));
  CHECK(stages.count("advect") == 1);
  CHECK(stages.count("subgrid") == 0);
  CHECK(stages.count("wall") == 0);
  CHECK(host::WindGrid::estimate_device_bytes(zero) == host::WindGrid::estimate_device_bytes(setup));

  // Switched on, both stages run, change the field, and keep it finite.
  auto on = setup;
  on.settings.smagorinsky_constant = kSmagorinsky;
  on.settings.wall_roughness_length = kRoughness;
  const auto turbulent = run(on, &stages);
  CHECK(stages.count("subgrid") == 1);
  CHECK(stages.count("wall") == 1);
  CHECK_FALSE(identical(turbulent, plain));
  for (int c = 0; c < 3; ++c)
    for (float x : turbulent.component(c)) REQUIRE(std::isfinite(x));
  // nu_t is one float a cell more on the device, and the wall stress its face list.
  CHECK(host::WindGrid::estimate_device_bytes(on) == host::WindGrid::estimate_device_bytes(setup) +
                                                         on.spec.cell_count() * sizeof(float) +
                                                         host::WallStress::estimate_device_bytes(on, {}));
}

TEST_CASE("wall: a roughness length of h/2 or more is refused before anything is allocated", "[wall]") {
  auto* cc = test::device_or_skip();
  if (!cc) return;
  host::WindGridSetup setup;
  setup.spec = periodic_box(4, 4, 2, 2.0, B::slip);
  setup.settings.wall_roughness_length = 1.0;  // = h/2: the first cell centre sits at z0
  using Catch::Matchers::Contains;
  CHECK_THROWS_WITH(host::WindGrid(*cc, setup), Contains("WindGrid") && Contains("wall_roughness_length"));
  setup.settings.wall_roughness_length = 0.99;
  CHECK_NOTHROW(host::WindGrid(*cc, setup));
}

TEST_CASE("subgrid and wall: stage cost on a 128 x 128 x 64 grid", "[.][bench]") {
  auto* cc = test::device_or_skip();
  if (!cc) return;
  host::WindGridSetup setup;
  auto& spec = setup.spec;
  spec.nx = 128;
  spec.ny = 128;
  spec.nz = 64;
  spec.h = 2.0;
  spec.boundary = {B::inflow, B::outflow, B::periodic, B::periodic, B::slip, B::slip};
  setup.settings.dt = 0.2;
  setup.settings.smagorinsky_constant = kSmagorinsky;
  setup.settings.wall_roughness_length = kRoughness;
  setup.ambient = {8.0, 0.0, 0.0};
  // A hill 20 m (10 cells) high in the middle: the wall cells then span 11 layers.
  setup.solid.assign(spec.cell_count(), 0);
  for (int k = 0; k < spec.nz; ++k)
    for (int j = 0; j < spec.ny; ++j)
      for (int i = 0; i < spec.nx; ++i) {
        const double r2 = (std::pow(i - 64.0, 2) + std::pow(j - 64.0, 2)) / (20.0 * 20.0);
        if (k + 0.5 < 10.0 * std::exp(-r2))
          setup.solid[std::size_t(i) + std::size_t(spec.nx) * (j + std::size_t(spec.ny) * k)] = 1;
      }
  host::WindGrid wind(*cc, setup);
  wind.initialise_ambient();
  wind.step();  // warm-up: kernel builds
  wind.set_stage_timing(true);
  wind.reset_stage_ms();
  constexpr int kSteps = 5;
  for (int n = 0; n < kSteps; ++n) wind.step();
  double total = 0.0;
  for (const auto& [name, ms] : wind.stage_ms()) total += ms;
  for (const auto& [name, ms] : wind.stage_ms()) WARN(name << ": " << ms / kSteps << " ms/step");
  WARN("subgrid: " << wind.stage_ms().at("subgrid") / kSteps << " ms/step, wall: "
                   << wind.stage_ms().at("wall") / kSteps << " ms/step, of " << total / kSteps << " ms/step");
  CHECK(wind.stage_ms().count("subgrid") == 1);
}
