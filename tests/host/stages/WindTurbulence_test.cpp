// Synthetic inflow turbulence on the device (docs/design.md, "Turbulence"; issue 10, "Inflow"): what enters
// the domain has the requested intensity, integral length scale and inertial-range slope, the field stays
// divergence-free, and a run is deterministic and unchanged when the turbulence is off.
#include <fmt/format.h>
#include <catch2/catch.hpp>

#include <array>
#include <cmath>
#include <map>
#include <memory>
#include <string>
#include <utility>
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

namespace {

// The open ground (issue 44, part 3): a log-law inflow (z0 0.03 m) over a rough floor of the same z0,
// 2 m cells, intensity 0.13 asked at 20 m with L_u = 18 m (9 cells), upwind5 with C_s 0.16 and dt auto at
// CFL 0.8. The grid: 24 cells of fetch (the planes read lie 14 cells and more before the outflow, which
// moved no figure there against 32 cells), 64 across (128 m, 7 L_u, periodic), 32 high (64 m, a slip lid 2.4
// L_u above 20 m). The box is a run's (fluid::inflow_box_spec, the default cutoff_cells of 2) of the default
// size along x and z (128 and 32 cells: the smallest powers of two that hold 8 L_u and the domain), and the
// domain's period across. One such box realises sigma_u at 20 m within 5.8% (one standard deviation over 24
// seeds), so the test sweeps four seeds' boxes and averages them: 2.9%.
struct RoughGround {
  bool wall_stress = true;
  double smagorinsky_constant = fluid::WindSettings::kUpwind5SmagorinskyConstant;
  bool log_profile = true;
  double dt = 0.0;  // s; 0: dt auto at CFL 0.8
};
constexpr double kGroundSpeed = 10.0, kGroundHeight = 20.0, kGroundZ0 = 0.03, kGroundIntensity = 0.13;
constexpr double kGroundCell = 2.0, kGroundLength = 18.0;
constexpr std::uint64_t kGroundSeeds[] = {7, 8, 9, 10};

host::WindGridSetup rough_ground(const RoughGround& c, std::uint64_t seed) {
  host::WindGridSetup setup;
  setup.spec.nx = 24;
  setup.spec.ny = 64;
  setup.spec.nz = 32;
  setup.spec.h = kGroundCell;
  setup.spec.boundary = {B::inflow, B::outflow, B::periodic, B::periodic, B::slip, B::slip};
  setup.settings.advection = fluid::AdvectionScheme::upwind5;
  setup.settings.smagorinsky_constant = c.smagorinsky_constant;
  if (c.wall_stress) setup.settings.wall_roughness_length = kGroundZ0;
  if (c.dt > 0.0) {
    setup.settings.dt = c.dt;
  } else {
    setup.settings.cfl = 0.8;
  }
  setup.profile.reference_height = kGroundHeight;
  if (c.log_profile) {
    setup.profile.type = fluid::InflowProfile::Type::log;
    setup.profile.roughness_length = kGroundZ0;
  }
  setup.ambient = {kGroundSpeed, 0.0, 0.0};
  constexpr double kDefaultCutoffCells = 2.0;  // wind.turbulence.cutoff_cells
  constexpr int kDefaultBoxCells = 128;        // >= 8 L_u / h = 72 cells, a power of two
  setup.turbulence = std::make_shared<const fluid::TurbulenceBox>(
      fluid::inflow_box_spec({kDefaultBoxCells, setup.spec.ny, setup.spec.nz}, kGroundCell, kGroundLength,
                             kDefaultCutoffCells, 0, seed));
  return setup;
}

// What probes at 20 m record on face plane i: sigma_u / U over the two layers of u faces either side (19 and
// 21 m), each face's record over one period of the box after one flow-through, as a probe's about its own
// mean, averaged over the faces and the seeds; and the variance of the records in wavelengths of 7 to 10
// cells (U / f, Welch's estimate), likewise.
struct PlaneIntensity {
  double intensity = 0.0, band = 0.0;
};

std::map<int, PlaneIntensity> ground_intensities(host::ComputeContext& cc, const RoughGround& c,
                                                 const std::vector<int>& planes) {
  std::map<int, PlaneIntensity> out;
  for (std::uint64_t seed : kGroundSeeds) {
    const host::WindGridSetup setup = rough_ground(c, seed);
    host::WindGrid wind(cc, setup);
    wind.set_turbulence_sigma(kGroundIntensity * kGroundSpeed);
    wind.initialise_ambient();
    const auto& spec = wind.spec();
    const int layers[] = {int(kGroundHeight / spec.h) - 1, int(kGroundHeight / spec.h)};
    while (wind.time() < spec.nx * spec.h / kGroundSpeed) wind.step();
    const double stop = wind.time() + setup.turbulence->period()[0] / kGroundSpeed;
    std::map<int, std::vector<std::vector<double>>> records;  // [plane][face]
    double elapsed = 0.0;
    long steps = 0;
    while (wind.time() < stop) {
      elapsed += wind.step().dt, ++steps;
      const auto vel = wind.download_velocity();
      for (int i : planes) {
        auto& faces = records[i];
        faces.resize(std::size_t(2 * spec.ny));
        for (int l = 0; l < 2; ++l)
          for (int j = 0; j < spec.ny; ++j)
            faces[std::size_t(j + spec.ny * l)].push_back(vel.u[ref::face_index(spec, 0, i, j, layers[l])]);
      }
    }
    // dt auto barely moves (the largest speed changes little), so the records are taken as evenly spaced
    // at the mean dt for the spectrum.
    const double dt = elapsed / double(steps);
    constexpr std::size_t kSegment = 128;  // 13 s: df = 0.08 Hz, two bins in the band
    const double n = double(records.at(planes[0]).size() * std::size(kGroundSeeds));
    for (int i : planes)
      for (const auto& u : records[i]) {
        out[i].intensity += fluid::standard_deviation(u) / fluid::mean(u) / n;
        const fluid::Spectrum s = fluid::power_spectrum(u, dt, kSegment);
        const double df = s.frequency[1] - s.frequency[0];
        for (std::size_t q = 0; q < s.frequency.size(); ++q)
          if (s.frequency[q] >= kGroundSpeed / (10.0 * spec.h) &&
              s.frequency[q] <= kGroundSpeed / (7.0 * spec.h))
            out[i].band += s.density[q] * df / n;
      }
  }
  return out;
}

}  // namespace

TEST_CASE(
    "WindGrid turbulence: a sheared inflow over rough ground holds its intensity within 10% 10 cells "
    "downstream, under upwind5") {
  auto* cc = test::device_or_skip();
  if (!cc) return;
  const auto at = ground_intensities(*cc, {}, {0, 10});
  const PlaneIntensity &inflow = at.at(0), &downstream = at.at(10);
  WARN("intensity at 20 m: " << inflow.intensity << " at the inflow, " << downstream.intensity
                             << " 10 cells downstream (asked " << kGroundIntensity
                             << "); wavelengths of 7-10 cells keep " << downstream.band / inflow.band
                             << " of their variance");
  // The boxes' own realisation at 20 m spreads by 2.9% (above): 10% is more than three of those.
  CHECK(std::abs(inflow.intensity / kGroundIntensity - 1.0) < 0.10);
  CHECK(std::abs(downstream.intensity / kGroundIntensity - 1.0) < 0.10);  // the 10%
  CHECK(std::abs(downstream.intensity / inflow.intensity - 1.0) < 0.10);  // what the grid itself loses
  // The eddies of 7-10 cells: before issue 44's fix 0.47 of their variance was left 10 cells in (the box's
  // divergence, which the projection took, and first order over the inflow's first cell), after it 0.75 to
  // 0.90 over six sets of four seeds; 0.65 lies between.
  CHECK(downstream.band / inflow.band > 0.65);
}

// The intensity budget along the inflow (docs/numerics.md, "Where the inflow's intensity went"): the
// intensity at 20 m on the inflow plane, as injected, and 1, 2, 5, 10 and 15 cells downstream, with each
// suspect switched off in turn. A report with nothing to hold it to: `wind_tests "[report]"` prints it.
TEST_CASE("WindGrid turbulence: the intensity budget of a sheared inflow over rough ground", "[.][report]") {
  auto* cc = test::device_or_skip();
  if (!cc) return;
  const std::vector<int> planes = {0, 1, 2, 5, 10, 15};
  const std::pair<const char*, RoughGround> cases[] = {
      {"as in the test", {}},
      {"no wall stress", {.wall_stress = false}},
      {"no subgrid stress", {.smagorinsky_constant = 0.0}},
      {"a uniform profile", {.log_profile = false}},
      {"dt fixed at 0.1 s", {.dt = 0.1}},
      {"all four", {.wall_stress = false, .smagorinsky_constant = 0.0, .log_profile = false, .dt = 0.1}}};
  for (const auto& [name, c] : cases) {
    const auto at = ground_intensities(*cc, c, planes);
    std::string row;
    for (int i : planes) row += fmt::format(" {:.4f}", at.at(i).intensity);
    WARN(name << ": intensity at 20 m on planes 0, 1, 2, 5, 10, 15:" << row << "; 7-10 cells keep "
              << at.at(10).band / at.at(0).band << " of their variance at 10");
  }
}
