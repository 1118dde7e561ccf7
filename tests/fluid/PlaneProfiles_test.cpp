// fluid/PlaneProfiles: the profiles of fields whose plane moments are known in closed form.
#include <catch2/catch.hpp>

#include <cmath>
#include <fstream>
#include <iterator>
#include <numbers>
#include <set>
#include <string>
#include <vector>

#include "fluid/PlaneProfiles.hpp"
#include "tests/support/Fields.hpp"

using namespace fw::fluid;
namespace test = fw::test;
using B = BoundaryType;

namespace {

// Sums of a few hundred doubles of order 1: a few ulps of the largest term.
constexpr double kRounding = 1e-12;

// 24 x 16 x 8 cells of 2 m, periodic in x and y.
GridSpec periodic_box() {
  GridSpec spec;
  spec.nx = 24, spec.ny = 16, spec.nz = 8, spec.h = 2.0;
  spec.boundary = {B::periodic, B::periodic, B::periodic, B::periodic, B::slip, B::slip};
  return spec;
}

// The field of known moments (tests/support/Fields.hpp).
constexpr double U0 = test::SineShear::U0, G = test::SineShear::G, C = test::SineShear::C,
                 A = test::SineShear::A, Bw = test::SineShear::B;

MacVelocity analytic(const GridSpec& s) {
  return test::sine_shear_velocity(s);
}

}  // namespace

TEST_CASE(
    "plane profiles: a sine in x and y over a linear profile in z gives its means, variances, third "
    "moments and fluxes to rounding",
    "[fluid]") {
  const GridSpec spec = periodic_box();
  const MacVelocity vel = analytic(spec);
  const PlaneProfiles p = plane_profiles(spec, vel, {});
  // The faces hold floats: the expected values are the float-rounded field's, to a few float ulps.
  constexpr double kFloat = 1e-6;
  for (int k = 0; k < spec.nz; ++k) {
    INFO("height " << k);
    const double z = (k + 0.5) * spec.h;
    CHECK(p.at(Profile::area, k) == 1.0);
    CHECK(p.at(Profile::u, k) == Approx(U0 + G * z).epsilon(kFloat));
    CHECK(std::abs(p.at(Profile::v, k)) < kFloat);
    CHECK(std::abs(p.at(Profile::w, k)) < kFloat);
    CHECK(p.at(Profile::u_2, k) == Approx(C * C / 2).epsilon(kFloat));
    CHECK(p.at(Profile::v_2, k) == Approx(A * A / 2).epsilon(kFloat));
    CHECK(p.at(Profile::w_2, k) == Approx(Bw * Bw / 2).epsilon(kFloat));
    CHECK(std::abs(p.at(Profile::u_3, k)) < kFloat);
    CHECK(std::abs(p.at(Profile::w_3, k)) < kFloat);
    CHECK(std::abs(p.at(Profile::u_w, k)) < kFloat);
    CHECK(p.at(Profile::v_w, k) == Approx(A * Bw / 2).epsilon(kFloat));
    CHECK(p.at(Profile::tke, k) == Approx((C * C + A * A + Bw * Bw) / 4).epsilon(kFloat));
    // Nothing subgrid or canopy was given.
    CHECK(p.at(Profile::u_diff, k) == 0.0);
    CHECK(p.at(Profile::sgs_tke, k) == 0.0);
    CHECK(p.at(Profile::lad, k) == 0.0);
    CHECK(p.at(Profile::u_flux, k) == Approx(p.at(Profile::u_w, k)).margin(kRounding));
  }
}

TEST_CASE("plane profiles: the subgrid flux is -2 nu_t S_xz averaged over the plane", "[fluid]") {
  // With nu_t = 0.1 m^2/s everywhere: S_xz = (du/dz + dw/dx) / 2 and dw/dx averages to 0 over a period, so
  // u_diff = -nu_t G wherever du/dz is a central difference (inside) and on the slip ground and lid, where it
  // turns one-sided over a linear profile: the same G. S_yz has dv/dz = 0 and dw/dy = 0: v_diff = 0.
  const GridSpec spec = periodic_box();
  const MacVelocity vel = analytic(spec);
  const std::vector<float> nu(spec.cell_count(), 0.1f), e(spec.cell_count(), 0.02f),
      a(spec.cell_count(), 0.3f);
  const PlaneProfiles p = plane_profiles(spec, vel, {}, {&nu, &e, &a});
  constexpr double kFloat = 1e-6;
  for (int k = 0; k < spec.nz; ++k) {
    INFO("height " << k);
    CHECK(p.at(Profile::u_diff, k) == Approx(-0.1 * G).epsilon(kFloat));
    CHECK(std::abs(p.at(Profile::v_diff, k)) < kFloat);
    CHECK(p.at(Profile::u_flux, k) ==
          Approx(p.at(Profile::u_w, k) + p.at(Profile::u_diff, k)).margin(kRounding));
    CHECK(p.at(Profile::sgs_tke, k) == Approx(0.02).epsilon(kFloat));
    CHECK(p.at(Profile::lad, k) == Approx(0.3).epsilon(kFloat));
  }
}

TEST_CASE("plane profiles: solid cells leave the plane's average, and a solid plane has area 0", "[fluid]") {
  const GridSpec spec = periodic_box();
  MacVelocity vel = analytic(spec);
  // The lowest height solid; at height 1 the half x < Lx / 2 solid, where the sine in x is positive, so the
  // fluid half's v is the mean of the sine's negative half period at 12 cell centres (near -2 A / pi).
  std::vector<std::uint8_t> solid(spec.cell_count(), 0);
  for (int j = 0; j < spec.ny; ++j)
    for (int i = 0; i < spec.nx; ++i) {
      solid[std::size_t(i + spec.nx * j)] = 1;
      if (i < spec.nx / 2) solid[std::size_t(i + spec.nx * (j + spec.ny))] = 1;
    }
  const PlaneProfiles p = plane_profiles(spec, vel, solid);
  CHECK(p.at(Profile::area, 0) == 0.0);
  CHECK(p.at(Profile::u, 0) == 0.0);
  CHECK(p.at(Profile::area, 1) == 0.5);
  // The discrete mean of sin over the half period of 12 cell centres: -(1/12) sum sin(pi (i + 1/2) / 12).
  double sum = 0.0;
  for (int i = 0; i < spec.nx / 2; ++i) sum += std::sin(std::numbers::pi * (i + 0.5) / (spec.nx / 2));
  CHECK(p.at(Profile::v, 1) == Approx(-A * sum / (spec.nx / 2)).epsilon(1e-6));
  CHECK(p.at(Profile::area, 2) == 1.0);
}

TEST_CASE(
    "plane profiles: every variable has a unique name, units and a long name, as docs/statistics.md lists "
    "them",
    "[fluid]") {
  std::ifstream page(std::string(FORESTWIND_SOURCE_DIR) + "/docs/statistics.md");
  REQUIRE(page);
  const std::string docs{std::istreambuf_iterator<char>(page), std::istreambuf_iterator<char>()};
  std::set<std::string> names;
  for (const ProfileVariable& v : profile_variables()) {
    CHECK(std::string(v.units).size() > 0);
    CHECK(std::string(v.long_name).size() > 0);
    names.insert(v.name);
    const std::string row = std::string("| `") + v.name + "` | " + v.units + " | " + v.long_name + " | " +
                            (std::string(v.standard_name).empty() ? "-" : v.standard_name) + " |";
    INFO("docs/statistics.md's row: " << row);
    CHECK(docs.find(row) != std::string::npos);
  }
  CHECK(names.size() == std::size_t(kProfileCount));
  CHECK(std::string(profile_variables()[std::size_t(Profile::u_w)].name) == "u_w");
  const GridSpec spec = periodic_box();
  CHECK_THROWS_AS(plane_profiles(spec, MacVelocity(spec), std::vector<std::uint8_t>(3, 0)),
                  std::invalid_argument);
}
