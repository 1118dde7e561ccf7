// Decaying isotropic turbulence in a periodic box: how far down the eddy sizes each advection scheme keeps
// the inertial range's -5/3 spectrum (Kolmogorov), which is what the trees and leaves can feel.
//
// The box: 64^3 cells of 1 m, all axes periodic, started from the inflow's von Karman turbulence
// (fluid/TurbulenceBox: sigma 1 m/s, L_u 8 m), projected, then left to decay with the Smagorinsky stress at
// each scheme's own dt: auto. After one eddy turnover L_u / sigma = 8 s the cascade has re-formed its
// inertial range from the synthetic field; the shell spectrum E(m) (fluid/EnergySpectrum) is compared with
// the -5/3 line through the large eddies (wavelengths of 32 to 16 cells, m = 2 .. 4).
#include <catch2/catch.hpp>

#include <cmath>
#include <cstdlib>
#include <fstream>
#include <iostream>
#include <memory>

#include "fluid/EnergySpectrum.hpp"
#include "fluid/ReferenceStages.hpp"
#include "fluid/TurbulenceBox.hpp"
#include "host/stages/WindGrid.hpp"
#include "tests/support/TestDevice.hpp"

using namespace fw;
namespace ref = fw::fluid::reference;
using B = fluid::BoundaryType;

namespace {

constexpr int kCells = 64;
constexpr double kSigma = 1.0, kLength = 8.0;   // m/s, m
constexpr double kTurnover = kLength / kSigma;  // s
// The eddies ride a mean wind, as they do through a forest: over the turnover they cross 40 cells, so the
// scheme's damping of the small eddies over distance counts, as it does downstream of an inflow.
constexpr double kMeanWind = 5.0;  // m/s along x

struct Decay {
  std::vector<double> start, end;  // E(m), m = 1 .. 32
  long steps = 0;
};

Decay decay(host::ComputeContext& cc, fluid::AdvectionScheme scheme, double smagorinsky,
            fluid::StageProjection projection) {
  host::WindGridSetup setup;
  setup.spec.nx = setup.spec.ny = setup.spec.nz = kCells;
  setup.spec.h = 1.0;
  setup.spec.boundary = {B::periodic, B::periodic, B::periodic, B::periodic, B::periodic, B::periodic};
  setup.settings.advection = scheme;
  setup.settings.smagorinsky_constant = smagorinsky;
  setup.settings.stage_projection = projection;
  setup.settings.cfl = std::isfinite(host::advection_method(scheme).courant_limit)
                           ? host::advection_method(scheme).courant_limit
                           : 0.8;
  setup.settings.pressure.tolerance = 1e-4;
  host::WindGrid wind(cc, setup);
  fluid::TurbulenceBoxSpec box_spec;
  box_spec.cells = {kCells, kCells, kCells};
  box_spec.spacing = 1.0;
  box_spec.spectrum = {kSigma, kLength};
  box_spec.seed = 5;
  const fluid::TurbulenceBox box(box_spec);
  fluid::MacVelocity vel(setup.spec);
  for (int c = 0; c < 3; ++c)
    for (int k = 0; k < ref::extent(setup.spec, c, 2); ++k)
      for (int j = 0; j < ref::extent(setup.spec, c, 1); ++j)
        for (int i = 0; i < ref::extent(setup.spec, c, 0); ++i) {
          const std::size_t point =
              std::size_t(i % kCells) + kCells * (std::size_t(j % kCells) + kCells * std::size_t(k % kCells));
          vel.component(c)[ref::face_index(setup.spec, c, i, j, k)] =
              float(box.values()[3 * point + std::size_t(c)] + (c == 0 ? kMeanWind : 0.0));
        }
  wind.upload_velocity(vel);
  wind.project();
  Decay d;
  d.start = fluid::shell_energy_spectrum(setup.spec, wind.download_velocity());
  while (wind.time() < kTurnover) {
    wind.step_by(std::min(wind.cfl_dt(wind.max_speed_components()), kTurnover - wind.time()));
    ++d.steps;
  }
  d.end = fluid::shell_energy_spectrum(setup.spec, wind.download_velocity());
  return d;
}

// E(m) m^(5/3) over its mean on m = 2 .. 4: 1 on the -5/3 line through the large eddies.
std::vector<double> compensated(const std::vector<double>& E) {
  double anchor = 0.0;
  for (int m = 2; m <= 4; ++m) anchor += E[std::size_t(m - 1)] * std::pow(m, 5.0 / 3.0) / 3.0;
  std::vector<double> out;
  for (std::size_t m = 1; m <= E.size(); ++m)
    out.push_back(E[m - 1] * std::pow(double(m), 5.0 / 3.0) / anchor);
  return out;
}

}  // namespace

TEST_CASE("validation: decaying turbulence keeps the -5/3 spectrum down to 8 cells with upwind5",
          "[validation]") {
  auto* cc = test::device_or_skip();
  if (!cc) return;
  struct Case {
    fluid::AdvectionScheme scheme;
    double smagorinsky;
    fluid::StageProjection projection = fluid::StageProjection::final_stage;
  };
  const Case cases[] = {{fluid::AdvectionScheme::semi_lagrangian, 0.16},
                        {fluid::AdvectionScheme::maccormack, 0.16},
                        {fluid::AdvectionScheme::upwind5, 0.16},
                        {fluid::AdvectionScheme::upwind5, 0.10},
                        {fluid::AdvectionScheme::upwind5, 0.16, fluid::StageProjection::every_stage}};
  // FORESTWIND_SPECTRA_CSV: where to write the spectra (scheme, C_s, m, E) for docs/numerics.md's figure.
  const char* csv_path = std::getenv("FORESTWIND_SPECTRA_CSV");
  std::ofstream csv;
  if (csv_path) {
    csv.open(csv_path);
    csv << "scheme,smagorinsky,m,wavelength_cells,E_start,E_end\n";
  }
  std::cout << "decaying turbulence, 64^3 with a 5 m/s mean wind, after " << kTurnover
            << " s: E(m) m^(5/3) over its mean on m = 2..4 (1: on the -5/3 line), m = 64 / wavelength\n";
  for (const Case& c : cases) {
    const Decay d = decay(*cc, c.scheme, c.smagorinsky, c.projection);
    const auto end = compensated(d.end);
    const bool stages = c.projection == fluid::StageProjection::every_stage;
    std::cout << "  " << fluid::to_string(c.scheme) << (stages ? " every stage projected" : "") << " C_s "
              << c.smagorinsky << " (" << d.steps << " steps):";
    for (int m : {2, 4, 6, 8, 10, 12, 16, 20, 24, 32})
      std::cout << " " << m << ":" << end[std::size_t(m - 1)];
    std::cout << std::endl;
    for (std::size_t m = 1; csv_path && m <= d.end.size(); ++m)
      csv << fluid::to_string(c.scheme) << (stages ? "+stages" : "") << "," << c.smagorinsky << "," << m
          << "," << double(kCells) / m << "," << d.start[m - 1] << "," << d.end[m - 1] << "\n";
    INFO(fluid::to_string(c.scheme) << " C_s " << c.smagorinsky);
    if (c.scheme == fluid::AdvectionScheme::upwind5) {
      // The measure: within a factor of 2 of the -5/3 line down to wavelengths of 8 cells.
      for (int m = 2; m <= kCells / 8; ++m) {
        INFO("m " << m << " (wavelength " << kCells / m << " cells)");
        CHECK(end[std::size_t(m - 1)] > 0.5);
        CHECK(end[std::size_t(m - 1)] < 2.0);
      }
    }
    if (c.scheme == fluid::AdvectionScheme::semi_lagrangian)
      CHECK(end[kCells / 8 - 1] < 0.5);  // the measure sees the damping that upwind5 removes
  }
}
