// host/stages/PlaneStatistics: the device's profiles against the CPU reference (fluid::plane_profiles) and
// against a field whose moments are known in closed form.
#include <catch2/catch.hpp>

#include <algorithm>
#include <cmath>
#include <memory>
#include <vector>

#include "fluid/PlaneProfiles.hpp"
#include "host/stages/PlaneStatistics.hpp"
#include "host/stages/WindGrid.hpp"
#include "tests/support/Fields.hpp"
#include "tests/support/TestDevice.hpp"
#include "tests/support/Tunnels.hpp"

using namespace fw;
using fluid::Profile;
using B = fluid::BoundaryType;

namespace {

// The device forms each cell's product in float and the central moments from the raw ones: a term of order
// n is off by a few float roundings (2^-24) of U^n, U the field's largest speed, whatever the moment's own
// size. 16 roundings cover the centring, the product and the three terms of a third moment.
constexpr double kFloatRoundings = 16.0 * 0x1p-24;

// The tolerance of each profile for a field of largest speed `speed` (m/s) and largest subgrid flux
// `subgrid` (m^2/s^2).
double tolerance(Profile p, double speed, double subgrid) {
  switch (p) {
    case Profile::area:
      return 0.0;  // counts: exact
    case Profile::u:
    case Profile::v:
    case Profile::w:
      return kFloatRoundings * speed;
    case Profile::u_3:
    case Profile::w_3:
      return kFloatRoundings * speed * speed * speed;
    case Profile::u_diff:
    case Profile::v_diff:
    case Profile::sgs_tke:
    case Profile::lad:
      return kFloatRoundings * subgrid;
    case Profile::u_flux:
    case Profile::v_flux:
      return kFloatRoundings * (speed * speed + subgrid);
    default:
      return kFloatRoundings * speed * speed;
  }
}

void check_close(const fluid::PlaneProfiles& device, const fluid::PlaneProfiles& reference, double speed,
                 double subgrid) {
  REQUIRE(device.nz == reference.nz);
  for (int p = 0; p < fluid::kProfileCount; ++p)
    for (int k = 0; k < device.nz; ++k) {
      INFO(fluid::profile_variables()[std::size_t(p)].name << " at height " << k);
      CHECK(device.at(Profile(p), k) ==
            Approx(reference.at(Profile(p), k)).margin(tolerance(Profile(p), speed, subgrid)));
    }
}

host::PlaneStatistics statistics_of(host::ComputeContext& cc, const host::WindGrid& wind) {
  return host::PlaneStatistics(cc, wind.spec(), wind.local_spec(), wind.block(), host::Communicator::alone());
}

// The field of known moments (tests/support/Fields.hpp) on 24 x 16 x 8 cells of 2 m, periodic in x and y.
constexpr double U0 = test::SineShear::U0, G = test::SineShear::G, C = test::SineShear::C,
                 A = test::SineShear::A, Bw = test::SineShear::B;

host::WindGridSetup periodic_box() {
  host::WindGridSetup setup;
  auto& s = setup.spec;
  s.nx = 24, s.ny = 16, s.nz = 8, s.h = 2.0;
  s.boundary = {B::periodic, B::periodic, B::periodic, B::periodic, B::slip, B::slip};
  setup.settings.dt = 0.1;
  return setup;
}

fluid::MacVelocity analytic(const fluid::GridSpec& s) {
  return test::sine_shear_velocity(s);
}

// A wind grid of periodic_box() holding the analytic field.
std::unique_ptr<host::WindGrid> analytic_grid(host::ComputeContext& cc) {
  const host::WindGridSetup setup = periodic_box();
  auto wind = std::make_unique<host::WindGrid>(cc, setup);
  wind->upload_velocity(analytic(setup.spec));
  return wind;
}

}  // namespace

TEST_CASE(
    "PlaneStatistics: a sine in x and y over a linear profile in z gives its means, variances, third moments "
    "and fluxes on the device, to rounding",
    "[statistics]") {
  auto* cc = test::device_or_skip();
  if (!cc) return;
  const host::WindGridSetup setup = periodic_box();
  const auto grid = analytic_grid(*cc);
  host::WindGrid& wind = *grid;
  host::PlaneStatistics statistics = statistics_of(*cc, wind);
  const fluid::PlaneProfiles p = statistics.sample(wind.statistics_fields(), wind.max_speed_component());
  const double speed = U0 + G * setup.spec.nz * setup.spec.h + C;
  for (int k = 0; k < setup.spec.nz; ++k) {
    INFO("height " << k);
    const double z = (k + 0.5) * setup.spec.h;
    CHECK(p.at(Profile::area, k) == 1.0);
    CHECK(p.at(Profile::u, k) == Approx(U0 + G * z).margin(tolerance(Profile::u, speed, 0)));
    CHECK(p.at(Profile::v, k) == Approx(0.0).margin(tolerance(Profile::v, speed, 0)));
    CHECK(p.at(Profile::w, k) == Approx(0.0).margin(tolerance(Profile::w, speed, 0)));
    CHECK(p.at(Profile::u_2, k) == Approx(C * C / 2).margin(tolerance(Profile::u_2, speed, 0)));
    CHECK(p.at(Profile::v_2, k) == Approx(A * A / 2).margin(tolerance(Profile::v_2, speed, 0)));
    CHECK(p.at(Profile::w_2, k) == Approx(Bw * Bw / 2).margin(tolerance(Profile::w_2, speed, 0)));
    CHECK(p.at(Profile::u_3, k) == Approx(0.0).margin(tolerance(Profile::u_3, speed, 0)));
    CHECK(p.at(Profile::w_3, k) == Approx(0.0).margin(tolerance(Profile::w_3, speed, 0)));
    CHECK(p.at(Profile::u_w, k) == Approx(0.0).margin(tolerance(Profile::u_w, speed, 0)));
    CHECK(p.at(Profile::v_w, k) == Approx(A * Bw / 2).margin(tolerance(Profile::v_w, speed, 0)));
    CHECK(p.at(Profile::tke, k) ==
          Approx((C * C + A * A + Bw * Bw) / 4).margin(tolerance(Profile::tke, speed, 0)));
    // No subgrid model and no canopy: their terms are not summed.
    CHECK(p.at(Profile::u_diff, k) == 0.0);
    CHECK(p.at(Profile::sgs_tke, k) == 0.0);
    CHECK(p.at(Profile::lad, k) == 0.0);
  }
  // The largest speed at a cell centre: u's sine peaks at j = 3 or 4 (of 16), at the top layer, where v and w
  // peak too (i = 5 or 6 of 24); the centred values are the faces' here.
  double fastest = 0.0;
  const fluid::MacVelocity vel = analytic(setup.spec);
  const auto& s = setup.spec;
  for (int k = 0; k < s.nz; ++k)
    for (int j = 0; j < s.ny; ++j)
      for (int i = 0; i < s.nx; ++i) {
        const double u = 0.5 * (vel.u[std::size_t(i + (s.nx + 1) * (j + s.ny * k))] +
                                vel.u[std::size_t(i + 1 + (s.nx + 1) * (j + s.ny * k))]);
        const double v = vel.v[std::size_t(i + s.nx * (j + (s.ny + 1) * k))];
        const double w = vel.w[std::size_t(i + s.nx * (j + s.ny * k))];
        fastest = std::max(fastest, std::sqrt(u * u + v * v + w * w));
      }
  CHECK(statistics.largest_speed() == Approx(fastest).epsilon(kFloatRoundings));
  // The same field through the CPU reference.
  check_close(p, fluid::plane_profiles(setup.spec, analytic(setup.spec), {}), speed, 0.0);
}

TEST_CASE(
    "PlaneStatistics: a stepped tunnel with solids, a canopy, the subgrid flux -2 nu_t S_xz and the subgrid "
    "energy gives the CPU reference's profiles",
    "[statistics]") {
  auto* cc = test::device_or_skip();
  if (!cc) return;
  for (const bool tke : {false, true}) {
    INFO((tke ? "the tke model" : "Smagorinsky's model"));
    host::WindGridSetup setup =
        tke ? test::turbulent_tunnel() : test::tunnel(fluid::AdvectionScheme::upwind5);
    if (!tke) setup.settings.smagorinsky_constant = 0.16;
    host::WindGrid wind(*cc, setup);
    if (setup.turbulence) wind.set_turbulence_sigma(1.0);
    const std::vector<float> canopy = test::tunnel_canopy(setup.spec);
    wind.set_canopy(canopy);
    wind.initialise_ambient();
    for (int n = 0; n < 4; ++n) wind.step();
    host::PlaneStatistics statistics = statistics_of(*cc, wind);
    const fluid::PlaneProfiles p = statistics.sample(wind.statistics_fields(), wind.max_speed_component());
    const std::vector<float> nu = wind.download_eddy_viscosity();
    std::vector<float> e;
    if (tke) e = wind.download_subgrid_energy();
    const fluid::PlaneProfiles reference = fluid::plane_profiles(
        setup.spec, wind.download_velocity(), setup.solid, {&nu, tke ? &e : nullptr, &canopy});
    // The fields are not trivial: solids take part of some planes, the subgrid flux and the canopy are on.
    CHECK(*std::min_element(p.values[0].begin(), p.values[0].end()) < 1.0);
    double subgrid = 0.0;
    for (int k = 0; k < p.nz; ++k)
      subgrid = std::max({subgrid, std::abs(reference.at(Profile::u_diff, k)),
                          std::abs(reference.at(Profile::sgs_tke, k)), reference.at(Profile::lad, k)});
    CHECK(subgrid > 0.0);
    // Float gradients against double ones: the subgrid terms' largest value times the float roundings, and
    // the nu_t (up to about 1 m^2/s here) times the velocity's roundings over a cell.
    const float largest_nu = *std::max_element(nu.begin(), nu.end());
    check_close(p, reference, wind.max_speed_component(), subgrid + largest_nu * wind.max_speed_component());
  }
}

TEST_CASE(
    "PlaneStatistics: scales kept from the last sample take one pass, and a scale too fine or too coarse "
    "costs a second pass at the terms' own, never a wrong sum",
    "[statistics]") {
  auto* cc = test::device_or_skip();
  if (!cc) return;
  const auto grid = analytic_grid(*cc);
  host::WindGrid& wind = *grid;
  host::PlaneStatistics statistics = statistics_of(*cc, wind);
  const double speed = wind.max_speed_component();
  host::PlaneScales scales;
  const fluid::PlaneProfiles first = statistics.sample(wind.statistics_fields(), speed, {}, &scales);
  REQUIRE(scales.known);
  const long passes = statistics.extra_passes();
  CHECK(passes <= 1);  // the speed's bounds are loose for v and w's moments here
  // The same field at the kept scales: one pass.
  const fluid::PlaneProfiles kept = statistics.sample(wind.statistics_fields(), speed, {}, &scales);
  CHECK(statistics.extra_passes() == passes);
  // Scales far too fine (every term would pass 2^27) and far too coarse (every term rounded to 0): one more
  // pass each. A speed bound far too small likewise.
  host::PlaneScales fine = scales, coarse = scales;
  fine.exponents.fill(100);
  coarse.exponents.fill(-20);
  const fluid::PlaneProfiles from_fine = statistics.sample(wind.statistics_fields(), speed, {}, &fine);
  CHECK(statistics.extra_passes() == passes + 1);
  const fluid::PlaneProfiles from_coarse = statistics.sample(wind.statistics_fields(), speed, {}, &coarse);
  CHECK(statistics.extra_passes() == passes + 2);
  const fluid::PlaneProfiles low = statistics.sample(wind.statistics_fields(), 1e-3);
  CHECK(statistics.extra_passes() == passes + 3);
  // Scales differ by powers of two: the sums round each cell at another multiple, below float rounding.
  for (const fluid::PlaneProfiles* other : {&kept, &from_fine, &from_coarse, &low})
    check_close(*other, first, speed, 0.0);
}

TEST_CASE("PlaneStatistics: a region averages its own cells alone", "[statistics]") {
  auto* cc = test::device_or_skip();
  if (!cc) return;
  const host::WindGridSetup setup = periodic_box();
  const auto grid = analytic_grid(*cc);
  host::WindGrid& wind = *grid;
  const fluid::MacVelocity vel = analytic(setup.spec);
  host::PlaneStatistics statistics = statistics_of(*cc, wind);
  // x cells 0 .. 11 of 24: half of v's sine period in x, whose mean is 2 A / pi (sampled at the centres,
  // exactly the sum below); all of y.
  const host::PlaneRegion half{{0, 0}, {12, setup.spec.ny}};
  const fluid::PlaneProfiles p =
      statistics.sample(wind.statistics_fields(), wind.max_speed_component(), half);
  double expected = 0.0;
  for (int i = 0; i < 12; ++i) expected += vel.v[std::size_t(i)];  // row j = 0, k = 0: faces at the centres
  expected /= 12.0;
  CHECK(expected > 0.5);  // the half period's mean is far from the whole plane's 0
  for (int k = 0; k < setup.spec.nz; ++k) {
    INFO("height " << k);
    CHECK(p.at(Profile::area, k) == 1.0);
    CHECK(p.at(Profile::v, k) == Approx(expected).margin(tolerance(Profile::v, A, 0)));
  }
}

TEST_CASE("PlaneStatistics: allocates on the device exactly the bytes it estimates", "[statistics]") {
  auto* cc = test::device_or_skip();
  if (!cc) return;
  const auto grid = analytic_grid(*cc);
  const std::size_t before = cc->allocated_bytes();
  const host::PlaneStatistics statistics = statistics_of(*cc, *grid);
  CHECK(cc->allocated_bytes() - before == host::PlaneStatistics::estimate_device_bytes(grid->local_spec()));
}
