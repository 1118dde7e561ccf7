// Upwind advection's interpolation and flux orders (fluid/UpwindStencil) and its CPU reference
// (fluid::reference::upwind_stage, advect_upwind5), without a device.
#include <catch2/catch.hpp>

#include <cmath>
#include <vector>

#include "fluid/PressureLevels.hpp"
#include "fluid/ReferenceStages.hpp"
#include "fluid/UpwindStencil.hpp"
#include "fluid/WindSettings.hpp"

using namespace fw;
namespace ref = fw::fluid::reference;
using B = fluid::BoundaryType;

namespace {

fluid::GridSpec grid(int nx, int ny, int nz, std::array<B, 6> boundary) {
  fluid::GridSpec spec;
  spec.nx = nx;
  spec.ny = ny;
  spec.nz = nz;
  spec.h = 1.0;
  spec.boundary = boundary;
  return spec;
}

int order_at(const fluid::GridSpec& spec, const fluid::UpwindOrders& orders, int c, int i, int j, int k,
             int axis, fluid::FluxSide side) {
  return fluid::flux_order(orders[std::size_t(c)][ref::face_index(spec, c, i, j, k)], axis, side);
}

}  // namespace

// The mean over the unit cell [n - 3, n - 2] of x^degree + 1: the flux point at x = 0 lies between the
// cells of values 2 and 3.
std::array<double, 6> cell_means(int degree) {
  std::array<double, 6> q{};
  for (int n = 0; n < 6; ++n)
    q[std::size_t(n)] = (std::pow(n - 2.0, degree + 1) - std::pow(n - 3.0, degree + 1)) / (degree + 1) + 1.0;
  return q;
}

TEST_CASE("upwind stencil: each order reconstructs the polynomials of its degree from cell means") {
  // The flux form differences the fluxes, so its interpolation reconstructs the value at the flux point from
  // the means of the cells around it (Wicker & Skamarock 2002): an upwind-biased stencil of order p uses p
  // cells and is exact up to degree p - 1, from either side.
  const int degree_of[] = {0, 2, 4};  // FW_UPWIND_FIRST, _THIRD, _FIFTH
  for (int code : {FW_UPWIND_FIRST, FW_UPWIND_THIRD, FW_UPWIND_FIFTH})
    for (double U : {2.0, -3.0})
      for (int degree = 0; degree <= degree_of[code]; ++degree) {
        const double exact = degree == 0 ? 2.0 : 1.0;
        INFO("order code " << code << ", U " << U << ", degree " << degree);
        CHECK(fluid::upwind_interpolation(code, U, cell_means(degree)) ==
              Approx(exact).margin(1e-12));  // double rounding
      }
}

TEST_CASE("upwind stencil: the next degree is not exact, and the bias follows the flow") {
  CHECK(std::abs(fluid::upwind_interpolation(FW_UPWIND_FIFTH, 1.0, cell_means(5)) - 1.0) > 1e-3);
  CHECK(std::abs(fluid::upwind_interpolation(FW_UPWIND_THIRD, 1.0, cell_means(3)) - 1.0) > 1e-3);
  // A step in the last cell moves the value for one sign of U only: the fifth-order stencil for U > 0
  // ignores the last cell, the one for U < 0 the first.
  std::array<double, 6> q{0, 0, 0, 0, 0, 1};
  CHECK(fluid::upwind_interpolation(FW_UPWIND_FIFTH, 1.0, q) == Approx(0.0).margin(1e-15));
  CHECK(fluid::upwind_interpolation(FW_UPWIND_FIFTH, -1.0, q) == Approx(2.0 / 60.0));
  std::array<double, 6> step{0, 0, 0, 1, 1, 1};
  CHECK(fluid::upwind_interpolation(FW_UPWIND_FIRST, 1.0, step) == 0.0);   // the upwind value q_m
  CHECK(fluid::upwind_interpolation(FW_UPWIND_FIRST, -1.0, step) == 1.0);  // q_m+1
}

TEST_CASE(
    "upwind stencil: orders drop to third then first before an outflow face, and stay fifth at an inflow") {
  // 12 cells along x between an inflow and an outflow face, periodic y, slip z.
  const auto spec = grid(12, 4, 4, {B::inflow, B::outflow, B::periodic, B::periodic, B::slip, B::slip});
  const auto orders = fluid::upwind_orders(spec, {});
  using S = fluid::FluxSide;
  // u along x: faces 0 .. 12; the lower flux of face p uses faces p - 3 .. p + 2 at fifth order. Beyond the
  // inflow face the ghosts hold the prescribed inflow, so even face 0's lower flux (faces -3 .. 2) is fifth.
  for (int p = 0; p <= 3; ++p) CHECK(order_at(spec, orders, 0, p, 1, 1, 0, S::lower) == FW_UPWIND_FIFTH);
  CHECK(order_at(spec, orders, 0, 9, 1, 1, 0, S::upper) == FW_UPWIND_FIFTH);  // uses faces 7 .. 12
  CHECK(order_at(spec, orders, 0, 10, 1, 1, 0, S::upper) == FW_UPWIND_THIRD);
  CHECK(order_at(spec, orders, 0, 11, 1, 1, 0, S::upper) == FW_UPWIND_FIRST);
  // v along x (12 faces 0 .. 11 per x-row, all tangential): fifth at the inflow, the same drop one face in
  // at the outflow.
  CHECK(order_at(spec, orders, 1, 0, 1, 1, 0, S::lower) == FW_UPWIND_FIFTH);
  CHECK(order_at(spec, orders, 1, 8, 1, 1, 0, S::upper) == FW_UPWIND_FIFTH);  // faces 6 .. 11
  CHECK(order_at(spec, orders, 1, 9, 1, 1, 0, S::upper) == FW_UPWIND_THIRD);
  CHECK(order_at(spec, orders, 1, 10, 1, 1, 0, S::upper) == FW_UPWIND_FIRST);
  // Across the periodic y axis every flux keeps fifth order, the wrap included.
  for (int c = 0; c < 3; ++c)
    for (int j = 0; j < ref::extent(spec, c, 1); ++j) {
      CHECK(order_at(spec, orders, c, 5, j, 1, 1, S::lower) == FW_UPWIND_FIFTH);
      CHECK(order_at(spec, orders, c, 5, j, 1, 1, S::upper) == FW_UPWIND_FIFTH);
    }
  // Four cells between slip walls are too few for fifth order anywhere along z.
  CHECK(order_at(spec, orders, 0, 5, 1, 2, 2, S::lower) == FW_UPWIND_THIRD);  // u rows 0 .. 3 usable
}

TEST_CASE("upwind stencil: a solid cuts the stencils that reach into it, and fluxes agree from both sides") {
  const auto spec =
      grid(16, 4, 4, {B::periodic, B::periodic, B::periodic, B::periodic, B::periodic, B::periodic});
  std::vector<std::uint8_t> solid(spec.cell_count(), 0);
  for (int k = 0; k < 4; ++k)
    for (int j = 0; j < 4; ++j)
      solid[std::size_t(8) + 16 * (std::size_t(j) + 4 * std::size_t(k))] = 1;  // x = 8
  const auto orders = fluid::upwind_orders(spec, solid);
  using S = fluid::FluxSide;
  // u faces 8 and 9 bound the solid cell 8 (each has a fluid side): usable. No u face lies inside it, so
  // the stencils along x stay at fifth order; v along x has its face 8 inside the solid.
  CHECK(order_at(spec, orders, 0, 8, 1, 1, 0, S::upper) == FW_UPWIND_FIFTH);
  CHECK(order_at(spec, orders, 1, 5, 1, 1, 0, S::upper) == FW_UPWIND_THIRD);  // v faces 3 .. 8 -> 4 .. 7
  CHECK(order_at(spec, orders, 1, 4, 1, 1, 0, S::upper) == FW_UPWIND_FIFTH);  // faces 2 .. 7
  CHECK(order_at(spec, orders, 1, 7, 1, 1, 0, S::upper) == FW_UPWIND_FIRST);  // faces 7, 8: first order
  // A face's upper flux along each axis is its upper neighbour's lower flux: the same order, wrap included.
  for (int c = 0; c < 3; ++c)
    for (int k = 0; k < ref::extent(spec, c, 2); ++k)
      for (int j = 0; j < ref::extent(spec, c, 1); ++j)
        for (int i = 0; i < ref::extent(spec, c, 0); ++i)
          for (int a = 0; a < 3; ++a) {
            int p[3] = {i, j, k};
            const int n = a == 0 ? spec.nx : (a == 1 ? spec.ny : spec.nz);
            p[a] = (p[a] + 1) % n;
            REQUIRE(order_at(spec, orders, c, i, j, k, a, S::upper) ==
                    order_at(spec, orders, c, p[0], p[1], p[2], a, S::lower));
          }
}

TEST_CASE("upwind reference: a stage conserves momentum in a periodic box") {
  // Every flux enters one face's tendency with + and its neighbour's with -: the sums telescope.
  const auto spec =
      grid(8, 8, 4, {B::periodic, B::periodic, B::periodic, B::periodic, B::periodic, B::periodic});
  const auto orders = fluid::upwind_orders(spec, {});
  const fluid::InflowState inflow;
  fluid::MacVelocity vel(spec);
  for (int c = 0; c < 3; ++c) {
    auto& q = vel.component(c);
    for (std::size_t n = 0; n < q.size(); ++n)
      q[n] = float(2.0 * std::sin(0.7 * double(n) + c) + (c == 0 ? 5 : 0));
  }
  // The high twins of periodic faces repeat the low ones, as the solver keeps them.
  for (int k = 0; k < spec.nz; ++k)
    for (int j = 0; j < spec.ny; ++j)
      vel.u[ref::face_index(spec, 0, spec.nx, j, k)] = vel.u[ref::face_index(spec, 0, 0, j, k)];
  for (int k = 0; k < spec.nz; ++k)
    for (int i = 0; i < spec.nx; ++i)
      vel.v[ref::face_index(spec, 1, i, spec.ny, k)] = vel.v[ref::face_index(spec, 1, i, 0, k)];
  for (int j = 0; j < spec.ny; ++j)
    for (int i = 0; i < spec.nx; ++i)
      vel.w[ref::face_index(spec, 2, i, j, spec.nz)] = vel.w[ref::face_index(spec, 2, i, j, 0)];
  const auto out = ref::upwind_stage(spec, inflow, orders, vel, vel, 0.1);
  for (int c = 0; c < 3; ++c) {
    double before = 0.0, after = 0.0, change = 0.0;
    for (int k = 0; k < spec.nz; ++k)
      for (int j = 0; j < spec.ny; ++j)
        for (int i = 0; i < spec.nx; ++i) {  // the distinct faces: a periodic axis' twin left out
          const auto id = ref::face_index(spec, c, i, j, k);
          before += vel.component(c)[id];
          after += out.component(c)[id];
          change += std::abs(double(out.component(c)[id]) - vel.component(c)[id]);
        }
    INFO("component " << c);
    CHECK(change > 1.0);                                    // the stage does move momentum around
    CHECK(std::abs(after - before) < 1e-5 * (change + 1));  // float storage of 256 faces' changes
  }
}
