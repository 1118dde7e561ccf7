#include "io/WindFrame.hpp"

#include <catch2/catch.hpp>

#include <array>
#include <cmath>
#include <functional>
#include <limits>
#include <stdexcept>
#include <vector>

using fw::fluid::GridSpec;
using fw::fluid::MacVelocity;
using Field = std::function<std::array<double, 3>(double, double, double)>;

namespace {

// A small grid with a non-trivial origin and cell size, so that index/world mix-ups show.
GridSpec small_spec() {
  GridSpec spec;
  spec.nx = 5;
  spec.ny = 4;
  spec.nz = 6;
  spec.h = 0.5;
  spec.origin = {1.0, -2.0, 3.0};
  return spec;
}

// Face values of `field` (world coordinates, m -> m/s): u(i,j,k) at origin + h (i, j+1/2, k+1/2), etc.
MacVelocity mac_from(const GridSpec& spec, const Field& field) {
  MacVelocity vel(spec);
  for (int c = 0; c < 3; ++c) {
    const int ex = spec.nx + (c == 0), ey = spec.ny + (c == 1), ez = spec.nz + (c == 2);
    for (int k = 0; k < ez; ++k) {
      for (int j = 0; j < ey; ++j) {
        for (int i = 0; i < ex; ++i) {
          const double x = spec.origin[0] + spec.h * (i + (c == 0 ? 0.0 : 0.5));
          const double y = spec.origin[1] + spec.h * (j + (c == 1 ? 0.0 : 0.5));
          const double z = spec.origin[2] + spec.h * (k + (c == 2 ? 0.0 : 0.5));
          vel.component(c)[std::size_t(i + ex * (j + ey * k))] = float(field(x, y, z)[std::size_t(c)]);
        }
      }
    }
  }
  return vel;
}

std::array<double, 3> cell_centre(const GridSpec& spec, int i, int j, int k) {
  return {spec.origin[0] + spec.h * (i + 0.5), spec.origin[1] + spec.h * (j + 0.5),
          spec.origin[2] + spec.h * (k + 0.5)};
}

// A general linear field v = A x + b (m/s); its curl is constant.
const double A[3][3] = {{0.3, -1.2, 0.7}, {2.1, -0.4, 0.25}, {-0.6, 1.5, 0.9}};
const double b[3] = {4.0, -3.0, 0.5};
std::array<double, 3> linear(double x, double y, double z) {
  std::array<double, 3> v{};
  for (int r = 0; r < 3; ++r) v[std::size_t(r)] = A[r][0] * x + A[r][1] * y + A[r][2] * z + b[r];
  return v;
}

}  // namespace

TEST_CASE("cell_centred_velocity: averaging a linear field to cell centres is exact", "[output]") {
  const GridSpec spec = small_spec();
  const MacVelocity vel = mac_from(spec, linear);
  const std::vector<float> centred = fw::io::cell_centred_velocity(spec, vel);
  REQUIRE(centred.size() == 3 * spec.cell_count());
  for (int k = 0; k < spec.nz; ++k) {
    for (int j = 0; j < spec.ny; ++j) {
      for (int i = 0; i < spec.nx; ++i) {
        const auto p = cell_centre(spec, i, j, k);
        const auto expected = linear(p[0], p[1], p[2]);
        const std::size_t cell = std::size_t(i + spec.nx * (j + spec.ny * k));
        for (int c = 0; c < 3; ++c) {
          // Tolerance: float32 storage of values up to ~10 m/s (a few ulp).
          CHECK(centred[3 * cell + std::size_t(c)] == Approx(expected[std::size_t(c)]).margin(1e-5));
        }
      }
    }
  }
}

TEST_CASE("make_wind_frame: carries the grid placement, time, step and per-cell arrays", "[output]") {
  const GridSpec spec = small_spec();
  const MacVelocity vel = mac_from(spec, linear);
  const std::size_t cells = spec.cell_count();
  std::vector<float> pressure(cells, 1.5f);
  std::vector<std::uint8_t> solid(cells, 0);
  solid[3] = 1;
  const auto frame = fw::io::make_wind_frame(spec, vel, pressure, solid, {}, 2.25, 90);
  CHECK(frame.dims == std::array<int, 3>{5, 4, 6});
  CHECK(frame.h == 0.5);
  CHECK(frame.origin == spec.origin);
  CHECK(frame.time == 2.25);
  CHECK(frame.step == 90);
  CHECK(frame.velocity == fw::io::cell_centred_velocity(spec, vel));
  CHECK(frame.pressure == pressure);
  CHECK(frame.solid == solid);
  CHECK(frame.canopy_density.empty());
  CHECK(frame.is_solid(3));
  CHECK_FALSE(frame.is_solid(4));
  CHECK(frame.cell_index(1, 2, 3) == 1 + 5 * (2 + 4 * 3));

  CHECK_THROWS_AS(fw::io::make_wind_frame(spec, vel, std::vector<float>(cells - 1), {}, {}, 0.0, 0),
                  std::invalid_argument);
  CHECK_THROWS_WITH(fw::io::make_wind_frame(spec, vel, {}, {}, std::vector<float>(7), 0.0, 0),
                    Catch::Matchers::StartsWith("WindFrame: canopy_density: expected 0 or 120 values"));
  MacVelocity short_u = vel;
  short_u.u.pop_back();
  CHECK_THROWS_AS(fw::io::make_wind_frame(spec, short_u, {}, {}, {}, 0.0, 0), std::invalid_argument);
}

TEST_CASE("wind_vorticity: a solid-body rotation has vorticity (0, 0, 2 Omega)", "[output]") {
  const GridSpec spec = small_spec();
  const double rotation_rate = 0.8;  // rad/s
  const MacVelocity vel = mac_from(spec, [&](double x, double y, double) {
    return std::array<double, 3>{-rotation_rate * y, rotation_rate * x, 0.0};
  });
  const auto frame = fw::io::make_wind_frame(spec, vel, {}, {}, {}, 0.0, 0);
  const std::vector<float> w = fw::io::wind_vorticity(frame);
  REQUIRE(w.size() == 3 * spec.cell_count());
  for (int k = 1; k + 1 < spec.nz; ++k) {
    for (int j = 1; j + 1 < spec.ny; ++j) {
      for (int i = 1; i + 1 < spec.nx; ++i) {
        const std::size_t cell = frame.cell_index(i, j, k);
        // Tolerance: float32 velocities (~1e-7 relative of ~2 m/s) differenced over 2h = 1 m.
        CHECK(w[3 * cell + 0] == Approx(0.0).margin(1e-5));
        CHECK(w[3 * cell + 1] == Approx(0.0).margin(1e-5));
        CHECK(w[3 * cell + 2] == Approx(2.0 * rotation_rate).margin(1e-5));
      }
    }
  }
}

TEST_CASE("wind_vorticity: the curl of a linear field is exact everywhere, one-sided at the edges",
          "[output]") {
  const GridSpec spec = small_spec();
  const auto frame = fw::io::make_wind_frame(spec, mac_from(spec, linear), {}, {}, {}, 0.0, 0);
  const std::vector<float> w = fw::io::wind_vorticity(frame);
  const double curl[3] = {A[2][1] - A[1][2], A[0][2] - A[2][0], A[1][0] - A[0][1]};
  for (std::size_t cell = 0; cell < frame.cell_count(); ++cell) {
    for (int c = 0; c < 3; ++c) {
      // Tolerance: float32 values up to ~10 m/s differenced over h = 0.5 m.
      CHECK(w[3 * cell + std::size_t(c)] == Approx(curl[c]).margin(1e-4));
    }
  }

  // An axis one cell thick contributes no derivative (no division by zero).
  GridSpec flat = spec;
  flat.nz = 1;
  const auto flat_frame = fw::io::make_wind_frame(flat, mac_from(flat, linear), {}, {}, {}, 0.0, 0);
  const std::vector<float> wf = fw::io::wind_vorticity(flat_frame);
  for (std::size_t cell = 0; cell < flat_frame.cell_count(); ++cell) {
    CHECK(wf[3 * cell + 0] == Approx(A[2][1]).margin(1e-4));   // dw/dy only
    CHECK(wf[3 * cell + 1] == Approx(-A[2][0]).margin(1e-4));  // -dw/dx only
    CHECK(wf[3 * cell + 2] == Approx(curl[2]).margin(1e-4));
  }
}

TEST_CASE("wind_vorticity: across a periodic axis' seam the difference is central, wrapped", "[output]") {
  // u = sin(2 pi y / L) over a domain periodic in y of length L: the wrapped central difference gives
  // wz = -du/dy = -cos(k y) sin(k h) / h in every cell, the seam's first and last included. A one-sided
  // difference there would be off by about k^2 h / 2 times the amplitude (0.15 1/s here).
  GridSpec spec = small_spec();
  spec.ny = 8;
  spec.boundary[2] = spec.boundary[3] = fw::fluid::BoundaryType::periodic;
  const double length = spec.ny * spec.h, k = 2.0 * std::acos(-1.0) / length;
  const auto wave = [&](double, double y, double) {
    return std::array<double, 3>{std::sin(k * (y - spec.origin[1])), 0.0, 0.0};
  };
  const auto frame = fw::io::make_wind_frame(spec, mac_from(spec, wave), {}, {}, {}, 0.0, 0);
  REQUIRE(frame.periodic == std::array<bool, 3>{false, true, false});
  const std::vector<float> w = fw::io::wind_vorticity(frame);
  for (int j = 0; j < spec.ny; ++j) {
    INFO("j = " << j);
    const double y = spec.h * (j + 0.5);
    const double expected = -std::cos(k * y) * std::sin(k * spec.h) / spec.h;
    // Tolerance: float32 velocities of order 1 m/s differenced over 2 h = 1 m.
    CHECK(w[3 * frame.cell_index(2, j, 3) + 2] == Approx(expected).margin(1e-6));
  }
}

TEST_CASE("wind_speed: the magnitude of the cell-centred velocity", "[output]") {
  fw::io::WindFrame frame;
  frame.dims = {2, 1, 1};
  frame.h = 1.0;
  frame.velocity = {3.0f, 4.0f, 0.0f, -1.0f, 2.0f, -2.0f};
  const std::vector<float> speed = fw::io::wind_speed(frame);
  REQUIRE(speed.size() == 2);
  CHECK(speed[0] == 5.0f);
  CHECK(speed[1] == 3.0f);
  frame.velocity.pop_back();
  CHECK_THROWS_AS(fw::io::wind_speed(frame), std::invalid_argument);
}

TEST_CASE("sample_velocity: reproduces a linear field exactly and clamps at the domain edges", "[output]") {
  const GridSpec spec = small_spec();
  const MacVelocity vel = mac_from(spec, linear);
  // Points inside every component's lattice: between half a cell from the walls (x, y, z).
  const std::vector<std::array<double, 3>> points = {
      {1.25, -1.75, 3.25}, {2.3, -0.9, 4.1}, {3.0, -0.3, 5.7}, {1.9, -1.2, 4.987}, {3.24, -0.26, 5.74}};
  for (const auto& p : points) {
    const auto got = fw::io::sample_velocity(spec, vel, p);
    const auto expected = linear(p[0], p[1], p[2]);
    for (int c = 0; c < 3; ++c) {
      // Tolerance: float32 face values (~1e-6 relative of ~10 m/s).
      CHECK(got[std::size_t(c)] == Approx(expected[std::size_t(c)]).margin(1e-5));
    }
  }

  // Far outside the domain: each component takes its value at the nearest lattice corner.
  const auto low = fw::io::sample_velocity(spec, vel, {-100.0, -100.0, -100.0});
  CHECK(low[0] == vel.u.front());
  CHECK(low[1] == vel.v.front());
  CHECK(low[2] == vel.w.front());
  const auto high = fw::io::sample_velocity(spec, vel, {100.0, 100.0, 100.0});
  CHECK(high[0] == vel.u.back());
  CHECK(high[1] == vel.v.back());
  CHECK(high[2] == vel.w.back());

  CHECK_THROWS_AS(fw::io::sample_velocity(spec, vel, {std::numeric_limits<double>::quiet_NaN(), 0.0, 0.0}),
                  std::invalid_argument);
}
