// The shell energy spectrum (fluid/EnergySpectrum) on fields whose spectrum is known.
#include <catch2/catch.hpp>

#include <cmath>
#include <numbers>

#include "fluid/EnergySpectrum.hpp"
#include "fluid/ReferenceStages.hpp"

using namespace fw;
namespace ref = fw::fluid::reference;
using B = fluid::BoundaryType;

namespace {

fluid::GridSpec cube(int n) {
  fluid::GridSpec spec;
  spec.nx = spec.ny = spec.nz = n;
  spec.h = 1.0;
  spec.boundary = {B::periodic, B::periodic, B::periodic, B::periodic, B::periodic, B::periodic};
  return spec;
}

}  // namespace

TEST_CASE("energy spectrum: one wave puts its energy in its own shell, the mean in none") {
  const auto spec = cube(16);
  fluid::MacVelocity vel(spec);
  // v = 3 + 2 sin(2 pi 3 x / 16) on v's faces (x at cell centres): energy 2^2 / 4 = 1 in shell 3.
  for (int k = 0; k < 16; ++k)
    for (int j = 0; j <= 16; ++j)
      for (int i = 0; i < 16; ++i)
        vel.v[ref::face_index(spec, 1, i, j, k)] =
            float(3.0 + 2.0 * std::sin(2.0 * std::numbers::pi * 3.0 * (i + 0.5) / 16.0));
  const auto E = fluid::shell_energy_spectrum(spec, vel);
  REQUIRE(E.size() == 8);
  for (std::size_t m = 0; m < E.size(); ++m) {
    INFO("shell " << m + 1);
    CHECK(E[m] == Approx(m == 2 ? 1.0 : 0.0).margin(1e-6));  // float storage of the field
  }
}

TEST_CASE("energy spectrum: the shells hold the energy of every wave inside the sphere (Parseval)") {
  const auto spec = cube(8);
  fluid::MacVelocity vel(spec);
  double energy = 0.0;  // of the waves below, each (amplitude^2) / 4 for a component
  const double amplitudes[3] = {0.5, 1.5, 1.0};
  const int waves[3][3] = {{1, 2, 0}, {0, 1, 3}, {2, 2, 1}};  // |m| = 2.24, 3.16, 3: shells 2, 3 and 3
  for (int c = 0; c < 3; ++c) {
    energy += amplitudes[c] * amplitudes[c] / 4.0;
    const int ex = ref::extent(spec, c, 0), ey = ref::extent(spec, c, 1), ez = ref::extent(spec, c, 2);
    for (int k = 0; k < ez; ++k)
      for (int j = 0; j < ey; ++j)
        for (int i = 0; i < ex; ++i) {
          const double phase =
              2.0 * std::numbers::pi * (waves[c][0] * i + waves[c][1] * j + waves[c][2] * k) / 8.0;
          vel.component(c)[ref::face_index(spec, c, i, j, k)] = float(amplitudes[c] * std::cos(phase));
        }
  }
  const auto E = fluid::shell_energy_spectrum(spec, vel);
  double sum = 0.0;
  for (double e : E) sum += e;
  CHECK(sum == Approx(energy).epsilon(1e-6));
  CHECK(E[1] == Approx(0.25 * 0.5 * 0.5).epsilon(1e-6));
  CHECK(E[2] == Approx(0.25 * (1.5 * 1.5 + 1.0)).epsilon(1e-6));
}

TEST_CASE("energy spectrum: a grid that is not a periodic cube is refused") {
  auto spec = cube(8);
  spec.ny = 4;
  CHECK_THROWS_WITH(fluid::shell_energy_spectrum(spec, fluid::MacVelocity(spec)), Catch::Contains("cube"));
}
