// Deardorff's subgrid energy model (fluid/SubgridTke) and its CPU reference (fluid::reference::tke_*),
// without a device: the constants, the three balances the model is built on (decay, homogeneous shear, a
// canopy in a steady wind), and the ghost rules.
#include <catch2/catch.hpp>

#include <cmath>
#include <vector>

#include "fluid/ReferenceStages.hpp"
#include "fluid/SubgridStress.hpp"
#include "fluid/SubgridTke.hpp"
#include "fluid/WindSettings.hpp"

using namespace fw;
namespace ref = fw::fluid::reference;
using B = fluid::BoundaryType;

namespace {

fluid::GridSpec box_spec(int nx, int ny, int nz, double h, B vertical) {
  fluid::GridSpec spec;
  spec.nx = nx;
  spec.ny = ny;
  spec.nz = nz;
  spec.h = h;
  spec.boundary = {B::periodic, B::periodic, B::periodic, B::periodic, vertical, vertical};
  return spec;
}

std::size_t cell(const fluid::GridSpec& spec, int i, int j, int k) {
  return std::size_t(i) + std::size_t(spec.nx) * (std::size_t(j) + std::size_t(spec.ny) * std::size_t(k));
}

fluid::MacVelocity uniform_wind(const fluid::GridSpec& spec, const std::array<double, 3>& wind) {
  fluid::MacVelocity vel(spec);
  for (int c = 0; c < 3; ++c)
    for (float& q : vel.component(c)) q = float(wind[c]);
  return vel;
}

// u = G (z - z_mid): a uniform shear |S|^2 = G^2, the face values multiples of G h / 2.
fluid::MacVelocity uniform_shear(const fluid::GridSpec& spec, double G) {
  fluid::MacVelocity vel(spec);
  for (int k = 0; k < spec.nz; ++k)
    for (int j = 0; j < spec.ny; ++j)
      for (int i = 0; i <= spec.nx; ++i)
        vel.u[ref::face_index(spec, 0, i, j, k)] = float(G * (k + 0.5 - 0.5 * spec.nz) * spec.h);
  return vel;
}

double relative_spread(const std::vector<float>& e, const std::vector<std::uint8_t>& solid, double value) {
  double worst = 0.0;
  for (std::size_t c = 0; c < e.size(); ++c)
    if (solid.empty() || !solid[c]) worst = std::max(worst, std::abs(e[c] - value) / value);
  return worst;
}

}  // namespace

TEST_CASE("SubgridTke: C_eps is 0.93 at l = h, a wall cell's l is 0.9 h, and the shear balance is C_s 0.18") {
  const double h = 2.0;
  CHECK(fluid::tke_mixing_length(h, false) == h);
  CHECK(fluid::tke_mixing_length(h, true) == Approx(0.9 * h).epsilon(1e-15));  // 1.8 z at z = h / 2
  CHECK(fluid::tke_dissipation_coefficient(h, h) == Approx(0.93).epsilon(1e-15));
  CHECK(fluid::tke_dissipation_coefficient(0.9 * h, h) == Approx(0.19 + 0.74 * 0.9).epsilon(1e-15));
  const auto tc = fluid::tke_coefficients(h);
  CHECK(tc.viscosity_length[0] == Approx(0.1 * h).epsilon(1e-15));
  CHECK(tc.dissipation_rate[1] == Approx((0.19 + 0.74 * 0.9) / (0.9 * h)).epsilon(1e-15));
  // In the shear balance nu_t = C_m l sqrt(e) = sqrt(C_m^3 / C_eps) l^2 |S|: Smagorinsky's (C_s l)^2 |S|.
  const double strain = 0.3, e = fluid::tke_shear_equilibrium(h, h, strain * strain);
  const double cs = std::sqrt(0.1 * h * std::sqrt(e) / (strain * h * h));
  CHECK(cs == Approx(std::pow(0.1 * 0.1 * 0.1 / 0.93, 0.25)).epsilon(1e-12));
  CHECK(cs == Approx(0.181).margin(5e-4));
  CHECK_THROWS_AS(fluid::tke_coefficients(0.0), std::invalid_argument);
  // The device's parameters are the same numbers in float.
  const FwTke t = fluid::tke_device_parameters(h);
  CHECK(t.viscosity_length[1] == float(tc.viscosity_length[1]));
  CHECK(t.canopy_sink == float(fluid::kCanopySinkFactor));
  CHECK(t.floor == float(fluid::kTkeFloor));
}

TEST_CASE("SubgridTke: with the tke model WindSettings refuses a Smagorinsky constant") {
  fluid::WindSettings st;
  st.subgrid = fluid::SubgridModel::tke;
  CHECK_NOTHROW(st.validate());
  st.smagorinsky_constant = 0.17;
  CHECK_THROWS_WITH(st.validate(), Catch::Contains("smagorinsky_constant") && Catch::Contains("tke"));
  CHECK(fluid::to_string(fluid::SubgridModel::tke) == "tke");
  CHECK(fluid::to_string(fluid::SubgridModel::smagorinsky) == "smagorinsky");
}

TEST_CASE(
    "SubgridTke reference: without strain e decays as e0 / (1 + C_eps sqrt(e0) t / 2l)^2, to first order "
    "in dt") {
  // A uniform wind through a periodic box: no strain, nothing to diffuse, advection moves a uniform field
  // onto itself, so each step is e / (1 + dt C_eps sqrt(e) / l), the implicit step of de/dt = -C_eps
  // e^(3/2) / l, whose closed form is the decay above. Its error is first order: at t = 20 s, e0 = 1,
  // l = h = 1 m it is 0.106 dt relative (from the recursion in double), 0.53% at dt = 0.05 s.
  const auto spec = box_spec(6, 4, 4, 1.0, B::periodic);
  const auto vel = uniform_wind(spec, {3.0, -1.0, 0.5});
  constexpr double e0 = 1.0, duration = 20.0;
  double errors[2];
  for (int n = 0; n < 2; ++n) {
    const double dt = n == 0 ? 0.05 : 0.025;
    std::vector<float> e(spec.cell_count(), float(e0));
    double recursion = e0;
    for (int s = 0; s < int(std::lround(duration / dt)); ++s) {
      e = ref::tke_step(spec, {}, vel, {}, e, dt);
      recursion /= 1.0 + dt * 0.93 * std::sqrt(recursion);
    }
    const double exact = fluid::tke_decay(e0, spec.h, spec.h, duration);
    CHECK(exact == Approx(e0 / std::pow(1.0 + 0.93 * duration / 2.0, 2)).epsilon(1e-14));
    // Float storage of ~800 steps: a few 1e-7 each.
    CHECK(relative_spread(e, {}, recursion) < 1e-4);
    errors[n] = (e[0] - exact) / exact;
    WARN("decay, dt " << dt << " s: e(" << duration << " s) = " << e[0] << ", closed form " << exact
                      << ", relative error " << errors[n]);
  }
  CHECK(std::abs(errors[0]) < 0.01);                          // the stated tolerance at dt = 0.05 s
  CHECK(errors[0] / errors[1] == Approx(2.0).epsilon(0.05));  // first order
}

TEST_CASE(
    "SubgridTke reference: a uniform shear settles at e = (C_m / C_eps) l^2 |S|^2 from above and below") {
  // u = G z between outflow ground and top (no wall, so l = h everywhere, and zero-gradient e): |S|^2 = G^2
  // in every cell (the one-sided differences at the edges are exact for a linear profile). Production
  // C_m l sqrt(e) G^2 equals dissipation C_eps e^(3/2) / l at the equilibrium, and the implicit step keeps
  // it as its fixed point. Linearised, e relaxes at sqrt(C_m C_eps) G = 0.15 1/s here: 150 s leave 1e-9.
  const auto spec = box_spec(4, 3, 8, 1.0, B::outflow);
  constexpr double G = 0.5, dt = 0.5;
  const auto vel = uniform_shear(spec, G);
  const double expected = 0.1 / 0.93 * spec.h * spec.h * G * G;
  CHECK(fluid::tke_shear_equilibrium(spec.h, spec.h, G * G) == Approx(expected).epsilon(1e-14));
  for (double start : {4.0 * expected, fluid::kTkeFloor}) {
    INFO("from e = " << start);
    std::vector<float> e(spec.cell_count(), float(start)), nu;
    for (int n = 0; n < 300; ++n) e = ref::tke_step(spec, {}, vel, {}, e, dt, &nu);
    CHECK(relative_spread(e, {}, expected) < 1e-5);  // float storage
    // nu_t = sqrt(C_m^3 / C_eps) l^2 G, from the old e of the last step (already settled).
    CHECK(nu[0] == Approx(std::sqrt(1e-3 / 0.93) * G).epsilon(1e-5));
  }
  // The start the grid takes is that balance directly.
  CHECK(relative_spread(ref::tke_equilibrium(spec, {}, vel), {}, expected) < 1e-6);
}

TEST_CASE(
    "SubgridTke reference: in a canopy in a steady wind e settles where the wakes' production meets the "
    "drag's sink and the dissipation") {
  // Uniform U = 3 m/s through a uniform drag density k = 0.2 1/m, no strain:
  //   k U^3 = 2 k U e + C_eps e^(3/2) / l   =>   e = 2.1155 m^2/s^2 at l = h = 1 m,
  // below U^2 / 2 = 4.5, the balance without the dissipation. The wind itself is held (the stages do not
  // move it); from below and above e relaxes to the balance at about 2 k U + 1.5 C_eps sqrt(e) / l.
  const auto spec = box_spec(4, 4, 3, 1.0, B::periodic);
  constexpr double U = 3.0, k = 0.2, dt = 0.5;
  const auto vel = uniform_wind(spec, {U, 0.0, 0.0});
  const std::vector<float> drag(spec.cell_count(), float(k));
  const double expected = fluid::tke_canopy_equilibrium(spec.h, spec.h, k, U);
  CHECK(expected == Approx(2.11545).epsilon(1e-5));
  const double x = std::sqrt(expected);
  CHECK(k * U * U * U == Approx(2.0 * k * U * expected + 0.93 * x * x * x).epsilon(1e-12));
  CHECK(expected < 0.5 * U * U);
  CHECK(fluid::tke_canopy_equilibrium(spec.h, spec.h, 0.0, U) == 0.0);
  for (double start : {10.0, fluid::kTkeFloor}) {
    INFO("from e = " << start);
    std::vector<float> e(spec.cell_count(), float(start));
    for (int n = 0; n < 200; ++n) e = ref::tke_step(spec, {}, vel, drag, e, dt);
    CHECK(relative_spread(e, {}, expected) < 1e-5);
  }
  // Outside the canopy the same wind only lets e decay.
  std::vector<float> e(spec.cell_count(), float(expected));
  e = ref::tke_step(spec, {}, vel, {}, e, dt);
  CHECK(e[0] == Approx(expected / (1.0 + dt * 0.93 * x)).epsilon(1e-6));
}

TEST_CASE(
    "SubgridTke reference: walls, outflow and solids pass no subgrid energy, an inflow face drains it") {
  // A uniform e in a still flow: with zero gradient across walls, outflow faces and solid faces, every
  // fluid cell decays alike (only the dissipation acts, at l = h or, on a wall, 0.9 h); across the inflow
  // face the cells exchange with the inflow's e = 0 and lose more. Solids hold 0.
  fluid::GridSpec spec = box_spec(8, 6, 5, 2.0, B::slip);
  spec.boundary[FW_FACE_WEST] = B::inflow;
  spec.boundary[FW_FACE_EAST] = B::outflow;
  spec.boundary[FW_FACE_TOP] = B::outflow;
  std::vector<std::uint8_t> solid(spec.cell_count(), 0);
  for (int k = 0; k < 2; ++k)
    for (int j = 2; j < 4; ++j) solid[cell(spec, 4, j, k)] = solid[cell(spec, 5, j, k)] = 1;
  const double e0 = 0.8, dt = 0.4;
  const fluid::MacVelocity still(spec);
  const std::vector<float> energy(spec.cell_count(), float(e0));
  // The advection alone keeps a uniform field uniform in any wind, whatever the ghosts but the inflow's.
  const auto moved = ref::tke_advect(spec, solid, uniform_wind(spec, {-2.0, 1.5, -3.0}), energy, dt);
  std::vector<float> nu;
  const auto e = ref::tke_step(spec, solid, still, {}, energy, dt, &nu);
  const auto walls = fluid::wall_cells(spec, solid);
  const auto tc = fluid::tke_coefficients(spec.h);
  for (int k = 0; k < spec.nz; ++k)
    for (int j = 0; j < spec.ny; ++j)
      for (int i = 0; i < spec.nx; ++i) {
        const std::size_t c = cell(spec, i, j, k);
        INFO("cell " << i << ", " << j << ", " << k);
        if (solid[c]) {
          CHECK(e[c] == 0.0f);
          CHECK(moved[c] == 0.0f);
          CHECK(nu[c] == 0.0f);
          continue;
        }
        CHECK(moved[c] == Approx(e0).epsilon(1e-6));
        const bool wall = walls[c] != 0.0f;
        const double decayed = e0 / (1.0 + dt * tc.dissipation_rate[wall] * std::sqrt(e0));
        if (i > 0) {
          CHECK(e[c] == Approx(decayed).epsilon(1e-6));
        } else {  // the inflow face: K = 2 nu_t, e_inflow = 0
          const double drained = (e0 - dt * 2.0 * nu[c] * e0 / (spec.h * spec.h)) /
                                 (1.0 + dt * tc.dissipation_rate[wall] * std::sqrt(e0));
          CHECK(e[c] == Approx(drained).epsilon(1e-6));
          CHECK(e[c] < decayed);
        }
      }
  // Into the domain across the inflow face the advection brings the inflow's 0.
  const auto entering = ref::tke_advect(spec, solid, uniform_wind(spec, {2.0, 0.0, 0.0}), energy, dt);
  CHECK(entering[cell(spec, 0, 0, 3)] == Approx(e0 * (1.0 - 2.0 * dt / spec.h)).epsilon(1e-6));
  CHECK(entering[cell(spec, 1, 0, 3)] == Approx(e0).epsilon(1e-6));
}

TEST_CASE("SubgridTke reference: e stays finite and at least the floor at any dt, its nu_t under the cap") {
  fluid::GridSpec spec = box_spec(10, 8, 6, 2.0, B::no_slip);
  spec.boundary[FW_FACE_WEST] = B::inflow;
  spec.boundary[FW_FACE_EAST] = B::outflow;
  std::vector<std::uint8_t> solid(spec.cell_count(), 0);
  solid[cell(spec, 3, 3, 0)] = solid[cell(spec, 3, 4, 0)] = 1;
  fluid::MacVelocity vel(spec);
  std::uint32_t state = 12345u;  // a small LCG: the values only need to be rough and repeatable
  auto next = [&](double amplitude) {
    state = state * 1664525u + 1013904223u;
    return amplitude * (double(state >> 8) / double(1u << 24) * 2.0 - 1.0);
  };
  for (int c = 0; c < 3; ++c)
    for (float& q : vel.component(c)) q = float(next(8.0));
  std::vector<float> e(spec.cell_count()), drag(spec.cell_count());
  for (std::size_t c = 0; c < e.size(); ++c) {
    e[c] = float(std::abs(next(3.0)));
    drag[c] = float(std::abs(next(0.5)));
  }
  for (double dt : {0.1, 2.0, 20.0}) {
    INFO("dt " << dt << " s");
    std::vector<float> nu;
    const auto out = ref::tke_step(spec, solid, vel, drag, e, dt, &nu);
    const float cap = float(fluid::eddy_viscosity_cap(spec.h, dt));
    for (std::size_t c = 0; c < out.size(); ++c) {
      REQUIRE(std::isfinite(out[c]));
      CHECK(out[c] >= (solid[c] ? 0.0f : float(fluid::kTkeFloor)));
      CHECK(nu[c] <= cap);
    }
  }
  CHECK_THROWS_AS(ref::tke_viscosity(spec, solid, {1.0f}, 1.0), std::invalid_argument);
  CHECK_THROWS_AS(ref::tke_update(spec, solid, vel, e, {1.0f}, e, 0.1, 1.0), std::invalid_argument);
}

TEST_CASE(
    "SubgridTke reference: the start is the shear balance, with the wall's mixing length on the ground") {
  const auto spec = box_spec(4, 3, 6, 2.0, B::slip);
  constexpr double G = -0.25;
  const auto e = ref::tke_equilibrium(spec, {}, uniform_shear(spec, G));
  const double open = fluid::tke_shear_equilibrium(spec.h, spec.h, G * G);
  const double wall = fluid::tke_shear_equilibrium(0.9 * spec.h, spec.h, G * G);
  for (int k = 0; k < spec.nz; ++k)
    CHECK(e[cell(spec, 1, 2, k)] == Approx(k == 0 ? wall : open).epsilon(1e-6));
  CHECK(wall < open);
  // No strain: the floor.
  for (float x : ref::tke_equilibrium(spec, {}, uniform_wind(spec, {4.0, 0.0, 0.0})))
    CHECK(x == float(fluid::kTkeFloor));
}
