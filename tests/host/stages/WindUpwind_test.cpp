// The wind grid with upwind5 advection on the device: order of accuracy in space and time, momentum
// conservation, its time step and its stability limit.
#include <catch2/catch.hpp>

#include <cmath>
#include <numbers>

#include "fluid/ReferenceStages.hpp"
#include "fluid/SolidMap.hpp"
#include "host/stages/WindGrid.hpp"
#include "tests/support/TestDevice.hpp"

using namespace fw;
namespace ref = fw::fluid::reference;
using B = fluid::BoundaryType;

namespace {

host::WindGridSetup periodic_box(int nx, int ny, int nz, double h) {
  host::WindGridSetup setup;
  setup.spec.nx = nx;
  setup.spec.ny = ny;
  setup.spec.nz = nz;
  setup.spec.h = h;
  setup.spec.boundary = {B::periodic, B::periodic, B::periodic, B::periodic, B::periodic, B::periodic};
  setup.settings.advection = fluid::AdvectionScheme::upwind5;
  setup.settings.pressure.tolerance = 1e-5;
  return setup;
}

// A 16 m periodic square of n x n x 2 cells in the uniform wind (U, V) = (2, 1) m/s, with w(x, y) = sin(2 pi
// (x + y) / L): the momentum equation then advects w as a passive scalar (u and v stay uniform and the field
// stays divergence-free), whose exact solution is the start shifted by (U, V) t.
struct PassiveWave {
  static constexpr double kLength = 16.0, kU = 2.0, kV = 1.0;
  static double exact(double x, double y, double t) {
    return std::sin(2.0 * std::numbers::pi * ((x - kU * t) + (y - kV * t)) / kLength);
  }
  // Max |w - exact| after `duration` seconds at fixed steps of summed Courant number `courant`.
  static double error(host::ComputeContext& cc, int n, double courant, double duration) {
    const double h = kLength / n;
    auto setup = periodic_box(n, n, 2, h);
    const double dt_wanted = courant * h / (kU + kV);
    const int steps = int(std::ceil(duration / dt_wanted - 1e-9));
    setup.settings.dt = duration / steps;
    host::WindGrid wind(cc, setup);
    fluid::MacVelocity vel(setup.spec);
    for (float& u : vel.u) u = float(kU);
    for (float& v : vel.v) v = float(kV);
    for (int k = 0; k <= 2; ++k)
      for (int j = 0; j < n; ++j)
        for (int i = 0; i < n; ++i)
          vel.w[ref::face_index(setup.spec, 2, i, j, k)] = float(exact((i + 0.5) * h, (j + 0.5) * h, 0.0));
    wind.upload_velocity(vel);
    for (int s = 0; s < steps; ++s) wind.step();
    const auto out = wind.download_velocity();
    double worst = 0.0;
    for (int j = 0; j < n; ++j)
      for (int i = 0; i < n; ++i)
        worst = std::max(worst, std::abs(double(out.w[ref::face_index(setup.spec, 2, i, j, 1)]) -
                                         exact((i + 0.5) * h, (j + 0.5) * h, duration)));
    return worst;
  }
};

// Sum of component c over the distinct faces (a periodic axis' high twin left out), in double.
double total(const fluid::GridSpec& spec, const fluid::MacVelocity& vel, int c) {
  double sum = 0.0;
  for (int k = 0; k < spec.nz; ++k)
    for (int j = 0; j < spec.ny; ++j)
      for (int i = 0; i < spec.nx; ++i) sum += vel.component(c)[ref::face_index(spec, c, i, j, k)];
  return sum;
}

}  // namespace

TEST_CASE("WindGrid upwind5: halving h cuts the error of an advected wave at least 25 times") {
  auto* cc = test::device_or_skip();
  if (!cc) return;
  // Fifth order gives 32x. A summed Courant number of 0.05 keeps RK3's error (third order in dt, about
  // 1/30 of the spatial one on the coarse grid) out of the ratio; the wave travels 8 s, half its period
  // along y and a whole one along x.
  const double coarse = PassiveWave::error(*cc, 16, 0.05, 8.0);
  const double fine = PassiveWave::error(*cc, 32, 0.05, 8.0);
  INFO("max error: " << coarse << " on 16 cells, " << fine << " on 32 cells, ratio " << coarse / fine);
  CHECK(coarse < 0.05);  // the scheme does carry the wave (a diffusive one would lose it)
  CHECK(coarse / fine >= 25.0);
}

TEST_CASE("WindGrid upwind5: halving dt cuts the error of an advected wave at least 6 times") {
  auto* cc = test::device_or_skip();
  if (!cc) return;
  // Third-order Runge-Kutta gives 8x. On 64 cells the spatial error is about 1/100 of the time error at a
  // summed Courant number of 1.
  const double large = PassiveWave::error(*cc, 64, 1.0, 8.0);
  const double small = PassiveWave::error(*cc, 64, 0.5, 8.0);
  INFO("max error: " << large << " at Courant 1, " << small << " at 0.5, ratio " << large / small);
  CHECK(large / small >= 6.0);
}

TEST_CASE("WindGrid upwind5: total momentum in a periodic box is conserved to 1e-6 over 100 steps") {
  auto* cc = test::device_or_skip();
  if (!cc) return;
  auto setup = periodic_box(16, 16, 16, 1.0);
  setup.settings.cfl = 0.8;
  setup.settings.smagorinsky_constant = 0.16;  // the subgrid stress is in flux form too
  host::WindGrid wind(*cc, setup);
  // A mean wind with eddies: ripples of a few wavelengths in every component, projected.
  fluid::MacVelocity vel(setup.spec);
  const double mean[3] = {4.0, 2.0, 1.0};
  for (int c = 0; c < 3; ++c) {
    const int ex = ref::extent(setup.spec, c, 0), ey = ref::extent(setup.spec, c, 1);
    for (std::size_t id = 0; id < vel.component(c).size(); ++id) {
      const double i = double(id % ex), j = double((id / ex) % ey), k = double(id / (std::size_t(ex) * ey));
      vel.component(c)[id] =
          float(mean[c] + 1.5 * std::sin(0.39 * i + 0.79 * j + c) * std::cos(0.39 * k - c));
    }
  }
  wind.upload_velocity(vel);
  wind.project();
  const auto start = wind.download_velocity();
  double moved = 0.0;
  for (int n = 0; n < 100; ++n) wind.step();
  const auto end = wind.download_velocity();
  for (int c = 0; c < 3; ++c) {
    const double before = total(setup.spec, start, c), after = total(setup.spec, end, c);
    INFO("component " << c << ": " << before << " -> " << after);
    // Float storage of 4096 faces a stage: about 1e-9 of the total a stage, as a random walk.
    CHECK(std::abs(after - before) <= 1e-6 * std::abs(before));
    for (std::size_t id = 0; id < end.component(c).size(); ++id)
      moved = std::max(moved, double(std::abs(end.component(c)[id] - start.component(c)[id])));
  }
  CHECK(moved > 0.5);  // the eddies did move
}

TEST_CASE(
    "WindGrid upwind5: dt auto keeps the summed Courant number at 1.2, and caps it with the CFL number") {
  auto* cc = test::device_or_skip();
  if (!cc) return;
  auto setup = periodic_box(16, 8, 8, 2.0);
  setup.settings.cfl = 5.0;  // asks more than the scheme allows
  setup.settings.max_dt = 10.0;
  host::WindGrid wind(*cc, setup);
  fluid::MacVelocity vel(setup.spec);
  for (float& u : vel.u) u = 4.0f;
  for (float& v : vel.v) v = -2.0f;
  wind.upload_velocity(vel);
  const double dt = wind.step().dt;
  CHECK(dt == Approx(fluid::kUpwind5CourantLimit * 2.0 / 6.0).epsilon(1e-6));
  CHECK(wind.courant_number({4.0, 2.0, 0.0}, dt) == Approx(fluid::kUpwind5CourantLimit).epsilon(1e-6));
  // A smaller CFL number on the largest component wins.
  setup.settings.cfl = 0.5;
  host::WindGrid calm(*cc, setup);
  calm.upload_velocity(vel);
  CHECK(calm.step().dt == Approx(0.5 * 2.0 / 4.0).epsilon(1e-6));
}

TEST_CASE("WindGrid upwind5: the same setup run twice gives bit-identical fields, per-stage projection too") {
  auto* cc = test::device_or_skip();
  if (!cc) return;
  for (auto projection : {fluid::StageProjection::final_stage, fluid::StageProjection::every_stage}) {
    host::WindGridSetup setup;
    setup.spec.nx = 24;
    setup.spec.ny = 16;
    setup.spec.nz = 8;
    setup.spec.h = 1.0;
    setup.spec.boundary = {B::inflow, B::outflow, B::slip, B::slip, B::no_slip, B::slip};
    setup.settings.advection = fluid::AdvectionScheme::upwind5;
    setup.settings.stage_projection = projection;
    setup.settings.cfl = 0.8;
    setup.ambient = {5.0, 0.0, 0.0};
    setup.gusts.push_back(
        FwGust{0.2f, 2.0f, 3.0f, 4.0f, {6.0f, 8.0f, 4.0f}, {5.0f, 0.0f, 0.0f}, {0.0f, 1.0f, 0.0f}});
    fluid::SolidMap solids(setup.spec);  // a post: the scheme drops its order around it
    solids.add(fluid::SolidCylinder{"post", {10.0, 8.0, 0.0}, 2.5, 6.0});
    setup.solid = solids.cells();
    auto run = [&] {
      host::WindGrid wind(*cc, setup);
      wind.initialise_ambient();
      for (int n = 0; n < 20; ++n) wind.step();
      return wind.download_velocity();
    };
    const auto a = run(), b = run();
    for (int c = 0; c < 3; ++c) CHECK(a.component(c) == b.component(c));
    double vmax = 0.0;  // the gust and the post made the field non-trivial, and it stayed finite
    for (float v : a.v) vmax = std::max(vmax, double(std::abs(v)));
    CHECK(vmax > 0.5);
    CHECK(std::isfinite(vmax));
  }
}
