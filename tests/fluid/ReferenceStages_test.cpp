// The CPU reference is the oracle of the kernel tests, so its own physics is checked here.
#include <catch2/catch.hpp>

#include <algorithm>
#include <cmath>
#include <random>

#include "fluid/InflowProfile.hpp"
#include "fluid/PressureLevels.hpp"
#include "fluid/ReferenceStages.hpp"

using namespace fw::fluid;
namespace ref = fw::fluid::reference;
using B = BoundaryType;

namespace {

GridSpec small_spec() {
  GridSpec spec;
  spec.nx = 12;
  spec.ny = 8;
  spec.nz = 6;
  spec.h = 1.5;
  spec.boundary = {B::inflow, B::outflow, B::periodic, B::periodic, B::no_slip, B::slip};
  return spec;
}

InflowState uniform_inflow(const GridSpec& spec, float u) {
  InflowState inflow;
  inflow.ambient = {u, 0.0f, 0.0f};
  inflow.profile.assign(spec.nz, 1.0f);
  return inflow;
}

}  // namespace

TEST_CASE(
    "reference gusts: a parcel at the centre of a resting gust rises to peak_speed and returns to rest") {
  GridSpec spec = small_spec();
  MacVelocity vel(spec);
  // Centre on u-face (6, 4, 3): world (9.0, 6.75, 5.25).
  const FwGust gust{1.0f, 2.0f, 5.0f, 3.0f, {9.0f, 6.75f, 5.25f}, {0.0f, 0.0f, 0.0f}, {1.0f, 0.0f, 0.0f}};
  const std::size_t centre = ref::face_index(spec, 0, 6, 4, 3);
  const double dt = 0.01;
  double t = 0.0;
  for (; t < 2.0 - 1e-9; t += dt) ref::add_gusts(spec, vel, {gust}, t, dt);  // to the envelope's peak
  // Midpoint-rule integration of the 1-cos rate: exact to O(dt^2).
  CHECK(vel.u[centre] == Approx(5.0).epsilon(1e-3));
  CHECK(std::abs(vel.v[ref::face_index(spec, 1, 6, 4, 3)]) == 0.0);
  // Two radii away the Gaussian has fallen to exp(-4) of the peak.
  CHECK(vel.u[ref::face_index(spec, 0, 2, 4, 3)] == Approx(5.0 * std::exp(-(6.0 * 6.0) / 9.0)).epsilon(1e-3));
  for (; t < 3.5; t += dt) ref::add_gusts(spec, vel, {gust}, t, dt);  // past the end (t = 3 s)
  CHECK(std::abs(vel.u[centre]) < 1e-4);
}

TEST_CASE(
    "reference advection: a uniform inflow field is unchanged by semi-Lagrangian and MacCormack steps") {
  GridSpec spec = small_spec();
  spec.boundary = {B::inflow, B::outflow, B::periodic, B::periodic, B::periodic, B::periodic};
  const auto inflow = uniform_inflow(spec, 3.0f);
  MacVelocity vel(spec);
  for (auto& u : vel.u) u = 3.0f;
  for (const auto& out : {ref::advect_semi_lagrangian(spec, inflow, vel, vel, 0.4),
                          ref::advect_maccormack(spec, inflow, vel, vel, 0.4)}) {
    for (float u : out.u) REQUIRE(u == Approx(3.0).margin(1e-6));
    for (float v : out.v) REQUIRE(v == Approx(0.0).margin(1e-6));
  }
}

TEST_CASE("reference advection: a linear shear is carried exactly along the flow") {
  // u = 2 m/s everywhere, v(x) linear in x: after dt, v(x) = v(x - u dt). Trilinear interpolation is exact
  // for a linear field, and the back-trace is exact for a uniform velocity.
  GridSpec spec = small_spec();
  spec.boundary = {B::slip, B::slip, B::periodic, B::periodic, B::periodic, B::periodic};
  const auto inflow = uniform_inflow(spec, 0.0f);
  MacVelocity vel(spec);
  for (auto& u : vel.u) u = 2.0f;
  auto v_of_x = [](double x) { return 0.1 * x; };
  for (int k = 0; k < spec.nz; ++k)
    for (int j = 0; j <= spec.ny; ++j)
      for (int i = 0; i < spec.nx; ++i)
        vel.v[ref::face_index(spec, 1, i, j, k)] = float(v_of_x((i + 0.5) * spec.h));
  MacVelocity through = vel;  // advect v through the uniform u alone
  for (auto& v : through.v) v = 0.0f;
  const auto out = ref::advect_semi_lagrangian(spec, inflow, through, vel, 0.5);
  for (int i = 2; i < spec.nx - 1; ++i) {  // away from the clamped edges
    const double x = (i + 0.5) * spec.h;
    CHECK(out.v[ref::face_index(spec, 1, i, 3, 2)] == Approx(v_of_x(x - 2.0 * 0.5)).epsilon(1e-6));
  }
}

TEST_CASE("reference projection: CG makes a random field divergence-free and keeps prescribed faces") {
  GridSpec spec = small_spec();
  const auto level = build_fine_pressure_level(spec, {});
  const auto inflow = uniform_inflow(spec, 4.0f);
  MacVelocity vel(spec);
  std::mt19937 rng(3);
  std::uniform_real_distribution<float> dist(-2.0f, 2.0f);
  for (int c = 0; c < 3; ++c)
    for (auto& x : vel.component(c)) x = dist(rng);
  ref::enforce_boundaries(spec, level, inflow, vel);
  const float west_face = vel.u[ref::face_index(spec, 0, 0, 2, 2)];
  const auto b = ref::divergence_rhs(spec, level, vel);
  std::vector<float> phi;
  const int iterations = ref::solve_pressure_cg(spec, level, b, phi, 1e-10, 2000);
  ref::subtract_gradient(spec, level, phi, vel);
  CHECK(iterations > 0);
  CHECK(ref::max_divergence(spec, level, vel) * spec.h / 6.0 < 1e-5);  // float storage of the faces
  CHECK(vel.u[ref::face_index(spec, 0, 0, 2, 2)] == west_face);        // inflow face untouched
  CHECK(west_face == Approx(4.0));
  CHECK(vel.w[ref::face_index(spec, 2, 3, 3, 0)] == 0.0f);  // no-slip ground: no normal flow
}

TEST_CASE(
    "reference prolongation: linear interpolation is exact for a linear field, zero-gradient at walls") {
  GridSpec spec;
  spec.nx = 16;
  spec.ny = 12;
  spec.nz = 8;
  spec.h = 1.0;
  spec.boundary = {B::no_slip, B::no_slip, B::no_slip, B::no_slip, B::no_slip, B::no_slip};
  const auto levels = build_pressure_levels(spec, {}, 64);
  REQUIRE(levels.size() >= 2);
  const auto& fine = levels[0];
  const auto& coarse = levels[1];
  // e = g . x with x in fine-cell units: coarse centres at 2I + 1, fine centres at i + 0.5.
  const double g[3] = {0.5, 0.25, -0.125};
  auto linear = [&](double x, double y, double z) { return 1.0 + g[0] * x + g[1] * y + g[2] * z; };
  std::vector<float> e(coarse.cell_count());
  for (int K = 0; K < coarse.nz; ++K)
    for (int J = 0; J < coarse.ny; ++J)
      for (int I = 0; I < coarse.nx; ++I)
        e[I + coarse.nx * (J + coarse.ny * K)] = float(linear(2 * I + 1, 2 * J + 1, 2 * K + 1));
  std::vector<float> phi(fine.cell_count(), 0.0f);
  constexpr double kLinearSlope = 0.25;
  ref::prolong_add(spec, fine, coarse, e, kLinearSlope, phi);
  const int n[3] = {fine.nx, fine.ny, fine.nz};
  double max_error = 0.0;
  for (int k = 0; k < fine.nz; ++k)
    for (int j = 0; j < fine.ny; ++j)
      for (int i = 0; i < fine.nx; ++i) {
        // Along an axis where the child's side is the wall the correction keeps the parent's value there.
        const int f[3] = {i, j, k};
        double x[3];
        for (int a = 0; a < 3; ++a) {
          const bool at_wall = f[a] == 0 || f[a] == n[a] - 1;
          x[a] = at_wall ? 2 * (f[a] / 2) + 1 : f[a] + 0.5;
        }
        max_error =
            std::max(max_error, std::abs(phi[i + fine.nx * (j + fine.ny * k)] - linear(x[0], x[1], x[2])));
      }
  // float32 storage of values of order 5: a few ulps. (Piecewise-constant interpolation is off by g / 2.)
  CHECK(max_error < 1e-5);
}
