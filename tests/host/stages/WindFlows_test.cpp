// Flows with known answers, run on the device: plane Poiseuille flow and vortex shedding behind a cylinder.
#include <catch2/catch.hpp>

#include <cmath>
#include <vector>

#include "fluid/ReferenceStages.hpp"
#include "fluid/SolidMap.hpp"
#include "host/stages/WindGrid.hpp"
#include "tests/support/TestDevice.hpp"

using namespace fw;
namespace ref = fw::fluid::reference;
using B = fluid::BoundaryType;

TEST_CASE("WindGrid: plane Poiseuille flow reaches its parabola within 2%") {
  auto* cc = test::device_or_skip();
  if (!cc) return;
  // Channel of height H = 1 m between no-slip walls at y = 0 and y = H, periodic in x and z, driven by a
  // uniform body force g. Steady state: u(y) = g / (2 nu) y (H - y), peak g H^2 / (8 nu) = 1 m/s.
  const double H = 1.0, nu = 0.05, g = 0.4;
  host::WindGridSetup setup;
  setup.spec.nx = 4;
  setup.spec.ny = 32;
  setup.spec.nz = 2;
  setup.spec.h = H / 32;
  setup.spec.boundary = {B::periodic, B::periodic, B::no_slip, B::no_slip, B::periodic, B::periodic};
  setup.settings.viscosity = nu;
  setup.settings.body_force = {g, 0.0, 0.0};
  setup.settings.dt = 0.05;
  setup.settings.pressure.tolerance = 1e-5;
  host::WindGrid wind(*cc, setup);
  wind.initialise_ambient();  // at rest
  // The slowest mode decays as exp(-pi^2 nu t / H^2): after 25 s it is e^-12 of the start.
  while (wind.time() < 25.0 - 1e-9) wind.step();
  const auto vel = wind.download_velocity();
  const double peak = g * H * H / (8 * nu);
  double worst = 0.0;
  for (int j = 0; j < setup.spec.ny; ++j) {
    const double y = (j + 0.5) * setup.spec.h;
    const double exact = g / (2 * nu) * y * (H - y);
    for (int i = 0; i <= setup.spec.nx; ++i)
      worst = std::max(worst, std::abs(vel.u[ref::face_index(setup.spec, 0, i, j, 1)] - exact) / peak);
  }
  INFO("largest deviation from the parabola: " << 100 * worst << "% of the peak");
  CHECK(worst < 0.02);
  for (float v : vel.v) CHECK(std::abs(v) < 1e-4);
}

namespace {

// Frequency of an oscillating signal from its mean crossings, Hz (linear interpolation between samples).
double crossing_frequency(const std::vector<double>& t, const std::vector<double>& s) {
  double mean = 0.0;
  for (double x : s) mean += x;
  mean /= double(s.size());
  std::vector<double> up;  // times of upward crossings
  for (std::size_t n = 1; n < s.size(); ++n)
    if (s[n - 1] < mean && s[n] >= mean) {
      const double f = (mean - s[n - 1]) / (s[n] - s[n - 1]);
      up.push_back(t[n - 1] + f * (t[n] - t[n - 1]));
    }
  if (up.size() < 3) return 0.0;
  return double(up.size() - 1) / (up.back() - up.front());
}

}  // namespace

TEST_CASE("WindGrid: vortex shedding behind a cylinder at Re 150 has a Strouhal number of 0.15-0.22",
          "[slow]") {
  auto* cc = test::device_or_skip();
  if (!cc) return;
  // Quasi-2D: a vertical cylinder of diameter D = 1 m (8 cells) in a 20 D x 8 D channel, two periodic cells
  // deep. U = 1 m/s and nu = 1/150 m^2/s give Re = U D / nu = 150. MacCormack keeps numerical diffusion
  // well below the physical one. The cylinder sits half a cell off the centre line to start the shedding.
  constexpr int kCellsPerDiameter = 8;
  const double D = 1.0, U = 1.0, h = D / kCellsPerDiameter;
  host::WindGridSetup setup;
  auto& spec = setup.spec;
  spec.nx = 20 * kCellsPerDiameter;
  spec.ny = 8 * kCellsPerDiameter;
  spec.nz = 2;
  spec.h = h;
  spec.boundary = {B::inflow, B::outflow, B::slip, B::slip, B::periodic, B::periodic};
  setup.settings.advection = fluid::AdvectionScheme::maccormack;
  setup.settings.viscosity = U * D / 150.0;
  setup.settings.dt = 0.5 * h / U;  // CFL 0.5 at the inflow speed, about 0.8 at the fastest
  setup.settings.pressure.tolerance = 1e-4;
  setup.ambient = {U, 0.0, 0.0};
  fluid::SolidMap solids(spec);
  const double cx = 5 * D, cy = 4 * D + 0.5 * h;
  solids.add(fluid::SolidCylinder{"cylinder", {cx, cy, -1.0}, 0.5 * D, 3.0});
  setup.solid = solids.cells();
  host::WindGrid wind(*cc, setup);
  wind.initialise_ambient();

  // Probe: transverse velocity 3 D behind the cylinder, on the centre line; one float read a step, not the
  // whole field.
  const int pi = int(std::lround((cx + 3 * D) / h)), pj = int(std::lround(4 * D / h)), pk = 1;
  const std::size_t probe = ref::face_index(spec, 1, pi, pj, pk);
  std::vector<double> times, v;
  while (wind.time() < 150.0) {
    wind.step();
    if (wind.time() < 70.0) continue;  // let the wake become periodic first
    float value = 0.0f;
    cc->queue().enqueueReadBuffer(wind.velocity().v, CL_TRUE, probe * sizeof(float), sizeof(float), &value);
    times.push_back(wind.time());
    v.push_back(value);
  }
  double amplitude = 0.0;
  for (double x : v) amplitude = std::max(amplitude, std::abs(x));
  const double strouhal = crossing_frequency(times, v) * D / U;
  INFO("Strouhal number " << strouhal << ", probe amplitude " << amplitude << " m/s");
  WARN("vortex shedding: St = " << strouhal << ", |v| up to " << amplitude << " m/s");
  CHECK(amplitude > 0.1 * U);  // the wake really oscillates
  CHECK(strouhal > 0.15);
  CHECK(strouhal < 0.22);
}
