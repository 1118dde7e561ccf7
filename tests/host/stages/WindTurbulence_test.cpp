// Synthetic inflow turbulence on the device (docs/design.md, "Turbulence"; issue 10, "Inflow"): what enters
// the domain has the requested intensity, integral length scale and inertial-range slope, the field stays
// divergence-free, and a run is deterministic and unchanged when the turbulence is off.
#include <catch2/catch.hpp>

#include <array>
#include <cmath>
#include <map>
#include <memory>
#include <vector>

#include "fluid/FlowStatistics.hpp"
#include "fluid/ReferenceStages.hpp"
#include "fluid/TurbulenceBox.hpp"
#include "host/stages/WindGrid.hpp"
#include "tests/support/TestDevice.hpp"

using namespace fw;
using B = fluid::BoundaryType;
namespace ref = fw::fluid::reference;

namespace {

constexpr double kMeanSpeed = 10.0;      // m/s, uniform profile
constexpr double kSigma = 1.5;           // m/s: intensity 15%
constexpr double kIntegralLength = 4.0;  // m, four cells
constexpr double kDt = 0.05;             // s: CFL 0.5 at the mean speed, below 1 with the fluctuations

// A wind tunnel of 1 m cells, 64 long, periodic across (y) so the box's y period can match it, slip floor
// and roof. The box has points every h/2, so that every face of the inflow plane sits on a box point (as the
// run's plan builds it, host/app/SimulationPlan). It is 64 L_u long and 8 L_u across, so that one sweep holds
// enough independent eddies for its statistics to converge: TurbulenceBox_test found realised sigma within
// 3% and the integral scale within 7% at these proportions.
host::WindGridSetup tunnel(std::uint64_t seed) {
  host::WindGridSetup setup;
  setup.spec.nx = 64;
  setup.spec.ny = 32;
  setup.spec.nz = 24;
  setup.spec.h = 1.0;
  setup.spec.boundary = {B::inflow, B::outflow, B::periodic, B::periodic, B::slip, B::slip};
  setup.settings.dt = kDt;
  setup.ambient = {kMeanSpeed, 0.0, 0.0};
  fluid::TurbulenceBoxSpec box;
  box.cells = {512, 64, 64};
  box.spacing = 0.5;
  box.spectrum = {1.0, kIntegralLength};
  box.seed = seed;
  setup.turbulence = std::make_shared<const fluid::TurbulenceBox>(box);
  return setup;
}

// Statistics of u over every face line (j, k) of one x-plane of faces, averaged over the lines.
struct PlaneStatistics {
  double sigma = 0.0, integral_length = 0.0, slope = 0.0;
};

PlaneStatistics plane_statistics(const std::vector<std::vector<double>>& lines) {
  PlaneStatistics out;
  const double n = double(lines.size());
  for (const auto& u : lines) {
    out.sigma += fluid::standard_deviation(u) / n;
    out.integral_length += fluid::integral_time_scale(u, kDt) * fluid::mean(u) / n;  // Taylor: L = U T
    // Segments of 6.4 s: df = 0.16 Hz. The inertial range of the von Karman spectrum starts near k L = 3
    // (f = 3 U / (2 pi L) = 0.9 Hz, L = L_u / 0.7468); above 2.5 Hz (wavelengths under 4 cells, a quarter
    // of the box's Nyquist wavenumber) the lattice's cut of the transverse wavenumbers steepens it by ~15%
    // (TurbulenceBox_test). Fit between.
    out.slope += fluid::log_log_slope(fluid::power_spectrum(u, kDt, 128), 0.9, 2.5) / n;
  }
  return out;
}

struct TunnelRun {
  std::map<int, PlaneStatistics> planes;  // by face index i
  double max_divergence = 0.0;            // 1/s, over the run
};

// Runs `steps` steps and takes the statistics of u on the face planes `planes` (face index i).
TunnelRun run_tunnel(host::ComputeContext& cc, int steps, const std::vector<int>& planes,
                     fluid::AdvectionScheme scheme) {
  host::WindGridSetup setup = tunnel(7);
  setup.settings.advection = scheme;
  host::WindGrid wind(cc, setup);
  wind.set_turbulence_sigma(kSigma);
  wind.initialise_ambient();
  const auto& spec = wind.spec();
  std::map<int, std::vector<std::vector<double>>> lines;
  for (int i : planes) lines[i].resize(std::size_t(spec.ny) * spec.nz);
  TunnelRun out;
  for (int n = 0; n < steps; ++n) {
    wind.step();
    const auto vel = wind.download_velocity();
    for (int i : planes)
      for (int k = 0; k < spec.nz; ++k)
        for (int j = 0; j < spec.ny; ++j)
          lines[i][std::size_t(j) + spec.ny * k].push_back(vel.u[ref::face_index(spec, 0, i, j, k)]);
    if (n % 32 == 0) out.max_divergence = std::max(out.max_divergence, wind.max_divergence());
  }
  for (int i : planes) out.planes[i] = plane_statistics(lines[i]);
  return out;
}

}  // namespace

TEST_CASE("WindGrid turbulence: the inflow plane has the requested intensity, length scale and -5/3 slope") {
  auto* cc = test::device_or_skip();
  if (!cc) return;
  // One period of the box passes in 256 m / 10 m/s = 25.6 s = 512 steps: the inflow plane sweeps the whole
  // box once, so its statistics are the box's over the heights the grid holds.
  const std::vector<int> planes = {0, 2, 8, 32};
  for (auto scheme : {fluid::AdvectionScheme::semi_lagrangian, fluid::AdvectionScheme::maccormack}) {
    const TunnelRun run = run_tunnel(*cc, 512, planes, scheme);
    for (int i : planes) {
      const PlaneStatistics& p = run.planes.at(i);
      WARN(fluid::to_string(scheme) << ", " << i << " cells behind the inflow: intensity "
                                    << p.sigma / kMeanSpeed << " (asked " << kSigma / kMeanSpeed << "), L_u "
                                    << p.integral_length << " m (asked " << kIntegralLength << "), slope "
                                    << p.slope);
    }
    const PlaneStatistics& inflow = run.planes.at(0);
    CHECK(std::abs(inflow.sigma / kSigma - 1.0) < 0.10);                     // the 10%
    CHECK(std::abs(inflow.integral_length / kIntegralLength - 1.0) < 0.20);  // the 20%
    CHECK(std::abs(inflow.slope + 5.0 / 3.0) < 0.3);                         // the issue's +-0.3
    // Divergence after projection: the solver stops at a relative residual of 1e-3, so what is left is
    // about 1e-3 of the divergence the inflow brings (of order sigma / h = 1.5 1/s); 1e-2 1/s leaves a
    // margin for the max norm over the L2 norm of the stopping test.
    CHECK(run.max_divergence < 1e-2);
  }
}

TEST_CASE("WindGrid turbulence: the same seed gives the same field, another seed another") {
  auto* cc = test::device_or_skip();
  if (!cc) return;
  auto run = [&](std::uint64_t seed) {
    host::WindGrid wind(*cc, tunnel(seed));
    wind.set_turbulence_sigma(kSigma);
    wind.initialise_ambient();
    for (int n = 0; n < 10; ++n) wind.step();
    return wind.download_velocity();
  };
  const auto a = run(7), b = run(7), c = run(8);
  CHECK(a.u == b.u);
  CHECK(a.v == b.v);
  CHECK(a.w == b.w);
  CHECK(a.u != c.u);
}

TEST_CASE("WindGrid turbulence: sigma 0 is the laminar run bit for bit") {
  auto* cc = test::device_or_skip();
  if (!cc) return;
  auto run = [&](bool with_box) {
    host::WindGridSetup setup = tunnel(7);
    if (!with_box) setup.turbulence.reset();
    host::WindGrid wind(*cc, setup);
    wind.initialise_ambient();
    for (int n = 0; n < 5; ++n) wind.step();
    return wind.download_velocity();
  };
  const auto laminar = run(false), zero_sigma = run(true);
  CHECK(laminar.u == zero_sigma.u);
  CHECK(laminar.v == zero_sigma.v);
  CHECK(laminar.w == zero_sigma.w);
}

TEST_CASE("WindGrid turbulence: a negative or non-finite sigma is refused") {
  auto* cc = test::device_or_skip();
  if (!cc) return;
  host::WindGrid wind(*cc, tunnel(7));
  CHECK_THROWS_WITH(wind.set_turbulence_sigma(-1.0), Catch::Contains("WindGrid: turbulence sigma"));
  CHECK_THROWS_WITH(wind.set_turbulence_sigma(NAN), Catch::Contains("WindGrid: turbulence sigma"));
}

TEST_CASE("WindGrid mean forcing: a periodic channel is held at the target speed at the reference height") {
  auto* cc = test::device_or_skip();
  if (!cc) return;
  // Periodic in x and y, a no-slip floor and viscosity: the floor's drag decelerates the flow, and the
  // forcing's integral part must settle on the body force that balances it.
  host::WindGridSetup setup;
  setup.spec.nx = 8;
  setup.spec.ny = 8;
  setup.spec.nz = 16;
  setup.spec.h = 1.0;
  setup.spec.boundary = {B::periodic, B::periodic, B::periodic, B::periodic, B::no_slip, B::slip};
  setup.settings.viscosity = 0.5;  // m^2/s: a laminar channel that reaches steady state in ~H^2/nu = 500 s
  setup.settings.dt = 0.2;
  setup.profile.reference_height = 8.0;
  setup.ambient = {3.0, -1.0, 0.0};
  setup.forcing.relaxation_time = 5.0;
  host::WindGrid wind(*cc, setup);
  wind.initialise_ambient();
  std::array<double, 2> mean{0, 0};
  // 300 s: 60 relaxation times for the controller, and most of the viscous spin-up.
  while (wind.time() < 300.0 - 1e-9) wind.step();
  mean = wind.reference_layer_mean();
  const auto a = wind.forcing_acceleration();
  INFO("layer mean (" << mean[0] << ", " << mean[1] << ") m/s, forcing (" << a[0] << ", " << a[1]
                      << ") m/s^2");
  // The controller's error decays as exp(-t / (2 tau)) against a drag that changes slowly: after 300 s it
  // is far below 1% of the target.
  CHECK(mean[0] == Approx(3.0).epsilon(0.01));
  CHECK(mean[1] == Approx(-1.0).epsilon(0.01));
  // The forcing pushes along the wind, against the floor's drag.
  CHECK(a[0] > 0.0);
  CHECK(a[1] < 0.0);
  CHECK(a[0] / a[1] == Approx(-3.0).epsilon(0.05));
}

TEST_CASE("WindGrid turbulence: over rough open ground the profile and intensity hold over 50 cells") {
  auto* cc = test::device_or_skip();
  if (!cc) return;
  // A log-law inflow over a rough wall of the same z0, with Smagorinsky and clamped MacCormack (the scheme
  // that keeps resolved turbulence; semi-Lagrangian loses sigma twice as fast, see the inflow test's
  // output). The grid: 1 m cells, 64 long, 24 high, periodic across.
  constexpr double kZ0 = 0.05, kReference = 10.0, kSpeed = 10.0;
  host::WindGridSetup setup;
  setup.spec.nx = 64;
  setup.spec.ny = 32;
  setup.spec.nz = 24;
  setup.spec.h = 1.0;
  setup.spec.boundary = {B::inflow, B::outflow, B::periodic, B::periodic, B::slip, B::slip};
  setup.settings.advection = fluid::AdvectionScheme::maccormack;
  setup.settings.smagorinsky_constant = 0.16;
  setup.settings.wall_roughness_length = kZ0;
  setup.settings.dt = kDt;
  setup.profile.type = fluid::InflowProfile::Type::log;
  setup.profile.reference_height = kReference;
  setup.profile.roughness_length = kZ0;
  setup.ambient = {kSpeed, 0.0, 0.0};
  // L_u = 12 m: eddies of twelve cells, which the grid carries over a fetch; the box is 128 m long.
  fluid::TurbulenceBoxSpec box;
  box.cells = {256, 64, 64};
  box.spacing = 0.5;
  box.spectrum = {1.0, 12.0};
  box.seed = 11;
  setup.turbulence = std::make_shared<const fluid::TurbulenceBox>(box);
  host::WindGrid wind(*cc, setup);
  // The inflow's sigma_u in equilibrium with the wall: sigma_u = 2.5 u* in a neutral surface layer
  // (Panofsky & Dutton), u* = kappa U_ref / ln(z_ref / z0). A weaker inflow grows toward it near the ground.
  constexpr double kKarman = 0.41;
  const double friction_velocity = kKarman * kSpeed / std::log(kReference / kZ0);
  wind.set_turbulence_sigma(2.5 * friction_velocity);
  wind.initialise_ambient();
  // One flow-through (64 m at ~10 m/s) to set up, then one box period (128 m) of statistics at two stations
  // 50 cells apart, every face of each station's cross-section at three heights.
  const int upstream = 4, downstream = 54;
  const std::vector<int> levels = {4, 9, 16};  // cell layers: z = 4.5, 9.5 and 16.5 m
  while (wind.time() < 6.4 - 1e-9) wind.step();
  std::map<int, std::map<int, std::vector<std::vector<double>>>> series;  // [station][level][line]
  for (int n = 0; n < 256; ++n) {
    wind.step();
    const auto vel = wind.download_velocity();
    for (int i : {upstream, downstream})
      for (int k : levels) {
        auto& lines = series[i][k];
        lines.resize(std::size_t(setup.spec.ny));
        for (int j = 0; j < setup.spec.ny; ++j)
          lines[std::size_t(j)].push_back(vel.u[ref::face_index(setup.spec, 0, i, j, k)]);
      }
  }
  for (int k : levels) {
    double mean_up = 0, mean_down = 0, sigma_up = 0, sigma_down = 0;
    const double n = double(setup.spec.ny);
    for (const auto& u : series[upstream][k])
      mean_up += fluid::mean(u) / n, sigma_up += fluid::standard_deviation(u) / n;
    for (const auto& u : series[downstream][k])
      mean_down += fluid::mean(u) / n, sigma_down += fluid::standard_deviation(u) / n;
    WARN("z = " << (k + 0.5) << " m: U " << mean_up << " -> " << mean_down << " m/s, sigma_u " << sigma_up
                << " -> " << sigma_down << " m/s over 50 cells");
    CHECK(mean_down / mean_up == Approx(1.0).epsilon(0.20));    // the 20%
    CHECK(sigma_down / sigma_up == Approx(1.0).epsilon(0.20));  // the 20%
  }
}

namespace {

// The inflow's intensity at the inflow plane and 10 cells downstream under `scheme`: eddies of L_u = 9 cells
// at 13% (the case, on 1 m cells) with Smagorinsky C_s 0.16. dt 0.04 s keeps the summed Courant
// number near 1 with the fluctuations (upwind5's limit: 1.2). The box is 64 L_u long, as in the inflow test
// above, so that one sweep (57.6 s) holds enough eddies for sigma to converge to a few per cent.
constexpr double kIntensity = 0.13;
std::array<double, 2> downstream_intensity(host::ComputeContext& cc, fluid::AdvectionScheme scheme) {
  constexpr double kLength = 9.0, kStep = 0.04;
  host::WindGridSetup setup = tunnel(7);
  auto box = setup.turbulence->spec();
  box.spectrum = {1.0, kLength};
  box.cells[0] = int(64 * kLength / box.spacing);
  setup.turbulence = std::make_shared<const fluid::TurbulenceBox>(box);
  setup.settings.advection = scheme;
  setup.settings.smagorinsky_constant = 0.16;
  setup.settings.dt = kStep;
  host::WindGrid wind(cc, setup);
  wind.set_turbulence_sigma(kIntensity * kMeanSpeed);
  wind.initialise_ambient();
  const auto& spec = wind.spec();
  const int planes[] = {0, 10};
  std::vector<std::vector<double>> lines[2];
  for (auto& l : lines) l.resize(std::size_t(spec.ny) * spec.nz);
  const int steps = int(std::lround(box.cells[0] * box.spacing / kMeanSpeed / kStep));
  for (int n = 0; n < steps; ++n) {
    wind.step();
    const auto vel = wind.download_velocity();
    for (int p = 0; p < 2; ++p)
      for (int k = 0; k < spec.nz; ++k)
        for (int j = 0; j < spec.ny; ++j)
          lines[p][std::size_t(j) + spec.ny * k].push_back(vel.u[ref::face_index(spec, 0, planes[p], j, k)]);
  }
  std::array<double, 2> intensity{0.0, 0.0};
  for (int p = 0; p < 2; ++p)
    for (const auto& u : lines[p])
      intensity[p] += fluid::standard_deviation(u) / kMeanSpeed / double(lines[p].size());
  WARN(fluid::to_string(scheme) << ": intensity " << intensity[0] << " at the inflow, " << intensity[1]
                                << " 10 cells downstream (asked " << kIntensity << ")");
  return intensity;
}

}  // namespace

TEST_CASE("WindGrid turbulence: with upwind5 the inflow's intensity holds within 10% 10 cells downstream") {
  auto* cc = test::device_or_skip();
  if (!cc) return;
  const std::array<double, 2> intensity = downstream_intensity(*cc, fluid::AdvectionScheme::upwind5);
  CHECK(std::abs(intensity[0] / kIntensity - 1.0) < 0.10);
  CHECK(std::abs(intensity[1] / kIntensity - 1.0) < 0.10);  // the 10%
}

// The semi-Lagrangian schemes' losses on the same case, a report with nothing to hold them to: hidden, so
// that CI does not spend on them twice upwind5's time; `wind_tests "[report]"` prints them.
TEST_CASE("WindGrid turbulence: what the semi-Lagrangian schemes keep of the inflow's intensity",
          "[.][report]") {
  auto* cc = test::device_or_skip();
  if (!cc) return;
  for (auto scheme : {fluid::AdvectionScheme::semi_lagrangian, fluid::AdvectionScheme::maccormack})
    downstream_intensity(*cc, scheme);
}
