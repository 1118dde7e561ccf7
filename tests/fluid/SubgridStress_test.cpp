// The subgrid and wall stresses' rules (fluid/SubgridStress) and their CPU reference
// (fluid::reference::eddy_viscosity, diffuse_eddy, wall_stress), without a device.
#include <catch2/catch.hpp>

#include <cmath>
#include <vector>

#include "fluid/ReferenceStages.hpp"
#include "fluid/SubgridStress.hpp"
#include "fluid/WindSettings.hpp"

using namespace fw;
namespace ref = fw::fluid::reference;
using B = fluid::BoundaryType;

namespace {

// A periodic box, periodic or slip along z.
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

// The reference keeps double arithmetic and stores float: a float rounding of the value.
constexpr double kFloatStorage = 1e-7;

}  // namespace

TEST_CASE("WindSettings: the Smagorinsky constant must be >= 0 and below 1, the roughness length >= 0") {
  fluid::WindSettings st;
  CHECK_NOTHROW(st.validate());  // both off by default
  CHECK(st.smagorinsky_constant == 0.0);
  CHECK(st.wall_roughness_length == 0.0);
  using Catch::Matchers::Contains;
  st.smagorinsky_constant = 0.17;
  st.wall_roughness_length = 0.1;
  CHECK_NOTHROW(st.validate());
  for (double bad : {-0.01, 1.0, 3.0, double(NAN)}) {
    st.smagorinsky_constant = bad;
    CHECK_THROWS_WITH(st.validate(), Contains("WindSettings") && Contains("smagorinsky_constant"));
  }
  st.smagorinsky_constant = 0.1;
  for (double bad : {-0.1, double(NAN), double(INFINITY)}) {
    st.wall_roughness_length = bad;
    CHECK_THROWS_WITH(st.validate(), Contains("WindSettings") && Contains("wall_roughness_length"));
  }
}

TEST_CASE("SubgridStress: the log-law drag coefficient is (kappa / ln(h / 2 z0))^2 and needs 0 < z0 < h/2") {
  // h = 2 m, z0 = 0.1 m: z1 = 1 m, ln(10) = 2.302585, C_w = (0.41 / 2.302585)^2 = 0.031706.
  CHECK(fluid::wall_drag_coefficient(2.0, 0.1) == Approx(std::pow(0.41 / std::log(10.0), 2)).epsilon(1e-14));
  CHECK(fluid::wall_drag_coefficient(2.0, 0.1) == Approx(0.031706).epsilon(1e-4));
  // Rougher ground drags harder.
  CHECK(fluid::wall_drag_coefficient(2.0, 0.5) > fluid::wall_drag_coefficient(2.0, 0.1));
  for (double bad : {0.0, -0.1, 1.0, 1.5, double(NAN)})
    CHECK_THROWS_AS(fluid::wall_drag_coefficient(2.0, bad), std::invalid_argument);
  CHECK(fluid::eddy_viscosity_cap(2.0, 0.5) == Approx(fluid::kEddyDiffusionLimit * 4.0 / 0.5).epsilon(1e-15));
  CHECK_THROWS_AS(fluid::eddy_viscosity_cap(2.0, 0.0), std::invalid_argument);
}

TEST_CASE("SubgridStress: wall cells are the fluid cells on a wall ground and on top of solids") {
  auto spec = box_spec(6, 4, 5, 1.0, B::slip);
  std::vector<std::uint8_t> solid(spec.cell_count(), 0);
  for (int j = 0; j < spec.ny; ++j) {
    for (int i = 3; i < 6; ++i) solid[cell(spec, i, j, 0)] = solid[cell(spec, i, j, 1)] = 1;  // a step
    solid[cell(spec, 1, j, 3)] = 1;  // a floating slab: its roof is a wall, its underside is not
  }
  const auto walls = fluid::wall_cells(spec, solid);
  for (int j = 0; j < spec.ny; ++j) {
    CHECK(walls[cell(spec, 0, j, 0)] == 1.0f);  // on the ground
    CHECK(walls[cell(spec, 1, j, 0)] == 1.0f);
    CHECK(walls[cell(spec, 0, j, 1)] == 0.0f);
    CHECK(walls[cell(spec, 3, j, 0)] == 0.0f);  // solid
    CHECK(walls[cell(spec, 3, j, 2)] == 1.0f);  // on the step
    CHECK(walls[cell(spec, 5, j, 2)] == 1.0f);
    CHECK(walls[cell(spec, 5, j, 3)] == 0.0f);
    CHECK(walls[cell(spec, 1, j, 4)] == 1.0f);  // on the slab's roof
    CHECK(walls[cell(spec, 1, j, 2)] == 0.0f);  // under it
  }
  double count = 0.0;
  for (float w : walls) count += w;
  CHECK(count == 4 * (3 + 3 + 1));
  // A periodic or open ground is no wall: only the step's top and the roof remain.
  spec.boundary[FW_FACE_GROUND] = spec.boundary[FW_FACE_TOP] = B::periodic;
  CHECK_FALSE(fluid::ground_is_wall(spec));
  count = 0.0;
  for (float w : fluid::wall_cells(spec, solid)) count += w;
  CHECK(count == 4 * (3 + 1));
  CHECK_THROWS_AS(fluid::wall_cells(spec, std::vector<std::uint8_t>(7, 0)), std::invalid_argument);
}

TEST_CASE("eddy viscosity reference: a uniform shear u = G z gives (C_s h)^2 |G| in every fluid cell") {
  // Linear in z: the central differences inside and the one-sided ones at the slip walls are all exact.
  const auto spec = box_spec(6, 4, 8, 2.0, B::slip);
  // 1/s: -3/8 makes every face value exact in float; a negative shear has the same |S|.
  constexpr double G = -0.375, Cs = 0.17;
  fluid::MacVelocity vel(spec);
  for (int k = 0; k < spec.nz; ++k)
    for (int j = 0; j < spec.ny; ++j)
      for (int i = 0; i <= spec.nx; ++i)
        vel.u[ref::face_index(spec, 0, i, j, k)] = float(G * (k + 0.5) * 2.0);
  std::vector<std::uint8_t> solid(spec.cell_count(), 0);
  solid[cell(spec, 2, 1, 3)] = 1;
  const auto nu = ref::eddy_viscosity(spec, solid, vel, Cs, 1e9);
  const double expected = std::pow(Cs * spec.h, 2) * std::abs(G);
  for (int k = 0; k < spec.nz; ++k)
    for (int j = 0; j < spec.ny; ++j)
      for (int i = 0; i < spec.nx; ++i) {
        if (solid[cell(spec, i, j, k)]) {
          CHECK(nu[cell(spec, i, j, k)] == 0.0f);
          continue;
        }
        // The solid cell's faces carry the shear here (no boundary stage ran), so its neighbours see it too.
        CHECK(nu[cell(spec, i, j, k)] == Approx(expected).epsilon(kFloatStorage));
      }
  // The clamp: a cap below (C_s h)^2 |G| is what every fluid cell gets.
  const auto capped = ref::eddy_viscosity(spec, solid, vel, Cs, 0.5 * expected);
  for (std::size_t c = 0; c < capped.size(); ++c)
    CHECK(capped[c] == (solid[c] ? 0.0f : float(0.5 * expected)));
  // C_s = 0: no eddy viscosity at all.
  for (float x : ref::eddy_viscosity(spec, {}, vel, 0.0, 1e9)) CHECK(x == 0.0f);
}

TEST_CASE("eddy diffusion reference: a constant eddy viscosity damps a sine by 1 - 4 s sin^2(kh/2) a step") {
  // v = A sin(k x) on a periodic axis: the 7-point Laplacian's eigenvalue, exactly.
  const auto spec = box_spec(16, 4, 4, 1.5, B::periodic);
  const double kx = 2.0 * M_PI / (spec.nx * spec.h), nu = 0.2, dt = 0.5;
  fluid::MacVelocity vel(spec);
  for (int k = 0; k < spec.nz; ++k)
    for (int j = 0; j <= spec.ny; ++j)
      for (int i = 0; i < spec.nx; ++i)
        vel.v[ref::face_index(spec, 1, i, j, k)] = float(3.0 * std::sin(kx * (i + 0.5) * spec.h));
  const auto out = ref::diffuse_eddy(spec, {}, fluid::InflowState{}, vel,
                                     std::vector<float>(spec.cell_count(), float(nu)), dt, false);
  const double s = nu * dt / (spec.h * spec.h);
  const double factor = 1.0 - 4.0 * s * std::pow(std::sin(0.5 * kx * spec.h), 2);
  for (std::size_t f = 0; f < out.v.size(); ++f)
    CHECK(out.v[f] == Approx(factor * vel.v[f]).margin(3.0 * kFloatStorage * 4));  // a few float roundings
  for (float x : out.u) CHECK(x == 0.0f);
  CHECK_THROWS_AS(ref::diffuse_eddy(spec, {}, fluid::InflowState{}, vel, {1.0f}, dt, false),
                  std::invalid_argument);
}

TEST_CASE(
    "wall stress reference: uniform wind over a slip ground loses exactly the implicit log-law stress") {
  const auto spec = box_spec(4, 6, 3, 2.0, B::slip);
  const double z0 = 0.05, dt = 0.8, U[2] = {6.0, -2.5};
  fluid::MacVelocity vel(spec);
  std::fill(vel.u.begin(), vel.u.end(), float(U[0]));
  std::fill(vel.v.begin(), vel.v.end(), float(U[1]));
  const double cw = fluid::wall_drag_coefficient(spec.h, z0);
  const auto out = ref::wall_stress(spec, {}, vel, cw, dt);
  const double speed = std::hypot(U[0], U[1]);
  const double factor = 1.0 / (1.0 + dt * cw * speed / spec.h);
  for (int c = 0; c < 2; ++c)
    for (std::size_t f = 0; f < out.component(c).size(); ++f) {
      const bool ground = f < std::size_t(ref::extent(spec, c, 0) * ref::extent(spec, c, 1));
      CHECK(out.component(c)[f] == Approx((ground ? factor : 1.0) * U[c]).epsilon(kFloatStorage));
    }
  for (float x : out.w) CHECK(x == 0.0f);
}
