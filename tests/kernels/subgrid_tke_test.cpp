// Deardorff's subgrid energy (kernels/subgrid_tke.cl): the four kernels against fluid::reference
// tke_equilibrium, tke_viscosity, tke_advect and tke_update, and the model through host::WindGrid's
// "subgrid" stage (solver.subgrid: tke).
#include <catch2/catch.hpp>

#include <cmath>
#include <cstring>
#include <map>
#include <string>
#include <vector>

#include "fluid/PressureLevels.hpp"
#include "fluid/ReferenceStages.hpp"
#include "fluid/SubgridStress.hpp"
#include "fluid/SubgridTke.hpp"
#include "host/stages/FluidStages.hpp"
#include "host/stages/WindGrid.hpp"
#include "tests/support/Fields.hpp"
#include "tests/support/TestDevice.hpp"

using namespace fw;
namespace ref = fw::fluid::reference;
using B = fluid::BoundaryType;

namespace {

// Float kernels against the double reference, relative to the field's largest value: the strain's nine
// differences and a square root (a few float ulps of the velocities over |S|, as the Smagorinsky test's
// 1e-5), and for the advection the back-traced position's float rounding times the gradient of e.
constexpr double kTkeTolerance = 1e-5;

// Three grids between them give every boundary type on every axis: mixed_boundary_spec (inflow west,
// outflow east, periodic south and north, then the given ground, slip top), and one periodic along x with
// slip walls south and north, an inflow ground and an outflow top.
fluid::GridSpec tke_spec(int variant) {
  if (variant == 3) return test::ragged_spec();  // ranges that end in part-filled work-groups
  auto spec = test::mixed_boundary_spec();
  if (variant == 0) return spec;  // no-slip ground
  if (variant == 1) {
    spec.boundary[FW_FACE_GROUND] = B::slip;
    return spec;
  }
  spec.boundary = {B::periodic, B::periodic, B::slip, B::slip, B::inflow, B::outflow};
  return spec;
}

// The test box and a terrain step one cell high under i >= 15 (its top cells are wall cells).
std::vector<std::uint8_t> box_and_step(const fluid::GridSpec& spec) {
  auto solid = test::box_solid(spec);
  for (int j = 0; j < spec.ny; ++j)
    for (int i = 15; i < spec.nx; ++i) solid[std::size_t(i) + std::size_t(spec.nx) * j] = 1;
  return solid;
}

// A wind of (5, 2, 0) m/s with random perturbations of 4 m/s: at dt = 0.4 s and h = 2 m the back-traces
// reach up to 1.8 cells, across every ghost.
fluid::MacVelocity gusty_wind(const fluid::GridSpec& spec, std::uint32_t seed) {
  auto vel = test::random_velocity(spec, 4.0, seed);
  for (float& u : vel.u) u += 5.0f;
  for (float& v : vel.v) v += 2.0f;
  return vel;
}

std::vector<float> random_energy(std::size_t n, std::uint32_t seed) {
  auto e = test::random_cells(n, 3.0, seed);  // m^2/s^2
  for (float& x : e) x = std::abs(x);
  return e;
}

std::vector<float> random_drag(std::size_t n, std::uint32_t seed) {
  auto k = test::random_cells(n, 0.4, seed);  // 1/m
  for (float& x : k) x = std::max(x, 0.0f);   // about half the cells without leaves
  return k;
}

bool identical(const fluid::MacVelocity& a, const fluid::MacVelocity& b) {
  for (int c = 0; c < 3; ++c)
    if (a.component(c).size() != b.component(c).size() ||
        std::memcmp(a.component(c).data(), b.component(c).data(), a.component(c).size() * sizeof(float)) != 0)
      return false;
  return true;
}

struct TkeFixture {
  host::ComputeContext& cc;
  fluid::GridSpec spec;
  std::vector<std::uint8_t> solid = box_and_step(spec);
  fluid::PressureLevel fine = fluid::build_fine_pressure_level(spec, solid);
  host::FluidStages stages{cc, spec};
  cl::Buffer mask = cc.buffer(fine.cell_count());

  TkeFixture(host::ComputeContext& c, const fluid::GridSpec& s) : cc(c), spec(s) {
    cc.queue().enqueueWriteBuffer(mask, CL_TRUE, 0, fine.cell_count(), fine.mask.data());
  }
  void set_dt(float dt) {
    FwStep s{};
    s.dt = dt;
    stages.set_step(s);
  }
  cl::Buffer cells(const std::vector<float>& values) {
    cl::Buffer b = cc.buffer(spec.cell_count() * sizeof(float));
    test::upload(cc, values, b);
    return b;
  }
};

}  // namespace

TEST_CASE(
    "subgrid tke: the four kernels match the CPU reference with every boundary type, solids and a canopy",
    "[subgrid]") {
  auto* cc = test::device_or_skip();
  if (!cc) return;
  for (int variant = 0; variant < 4; ++variant)
    for (bool canopy : {false, true})
      for (double dt : {0.4, 8.0}) {  // 8 s: the cap (0.075 m^2/s) binds in most cells
        INFO("grid " << variant << ", canopy " << canopy << ", dt " << dt << " s");
        TkeFixture f(*cc, tke_spec(variant));
        f.set_dt(float(dt));
        const auto vel = gusty_wind(f.spec, 41 + variant);
        const auto energy = random_energy(f.spec.cell_count(), 43);
        const auto drag = canopy ? random_drag(f.spec.cell_count(), 47) : std::vector<float>{};
        auto dvel = f.stages.allocate_velocity();
        test::upload(*cc, vel, dvel);
        const std::size_t n = f.spec.cell_count();
        cl::Buffer e = f.cells(energy), nu = f.cells(std::vector<float>(n, 0.0f));
        cl::Buffer advected = f.cells(std::vector<float>(n, 0.0f)),
                   start = f.cells(std::vector<float>(n, 0.0f));
        cl::Buffer k = f.cells(canopy ? drag : std::vector<float>(n, 0.0f));
        const double cap = fluid::eddy_viscosity_cap(f.spec.h, dt);

        f.stages.enqueue_tke_equilibrium(f.mask, dvel, start);
        const auto expected_start = ref::tke_equilibrium(f.spec, f.solid, vel);
        CHECK(test::relative_error(test::download(*cc, start, n), expected_start) < kTkeTolerance);

        f.stages.enqueue_tke_viscosity(float(cap), f.mask, e, nu);
        const auto expected_nu = ref::tke_viscosity(f.spec, f.solid, energy, cap);
        CHECK(test::relative_error(test::download(*cc, nu, n), expected_nu) < kTkeTolerance);

        f.stages.enqueue_tke_advect(f.mask, dvel, e, advected);
        const auto device_advected = test::download(*cc, advected, n);
        const auto expected_advected = ref::tke_advect(f.spec, f.solid, vel, energy, dt);
        CHECK(test::relative_error(device_advected, expected_advected) < kTkeTolerance);

        // The update from the reference's own inputs, so that each stage is compared alone.
        test::upload(*cc, expected_nu, nu);
        test::upload(*cc, expected_advected, advected);
        f.stages.enqueue_tke_update(float(cap), f.mask, dvel, nu, canopy ? &k : nullptr, advected, e);
        const auto device_e = test::download(*cc, e, n);
        const auto expected_e =
            ref::tke_update(f.spec, f.solid, vel, expected_nu, drag, expected_advected, dt, cap);
        CHECK(test::relative_error(device_e, expected_e) < kTkeTolerance);
        for (std::size_t c = 0; c < n; ++c)
          if (f.solid[c]) {
            CHECK(device_e[c] == 0.0f);
            CHECK(device_advected[c] == 0.0f);
          }
        // The canopy changes the result, and the cap binds where asked.
        if (canopy)
          CHECK(test::relative_error(
                    ref::tke_update(f.spec, f.solid, vel, expected_nu, {}, expected_advected, dt, cap),
                    expected_e) > 1e-2);
        std::size_t capped = 0;
        for (float x : expected_nu) capped += x == float(cap);
        CHECK((dt > 1.0) == (capped > n / 2));
      }
}

TEST_CASE(
    "subgrid tke: through WindGrid e decays in a uniform wind as the closed form of de/dt = -C_eps e^1.5 / l",
    "[subgrid]") {
  // A fully periodic box and a uniform wind: no strain, so the velocity stays exactly uniform and every cell
  // takes e / (1 + dt C_eps sqrt(e) / h) a step. The closed form e0 / (1 + C_eps sqrt(e0) t / 2h)^2 is met
  // to the scheme's first-order error, 0.106 dt relative at t = 20 s (fluid/SubgridTke_test): 0.53% here.
  auto* cc = test::device_or_skip();
  if (!cc) return;
  host::WindGridSetup setup;
  setup.spec.nx = 8;
  setup.spec.ny = 6;
  setup.spec.nz = 4;
  setup.spec.h = 1.0;
  setup.spec.boundary = {B::periodic, B::periodic, B::periodic, B::periodic, B::periodic, B::periodic};
  setup.settings.subgrid = fluid::SubgridModel::tke;
  setup.settings.dt = 0.05;
  host::WindGrid wind(*cc, setup);
  fluid::MacVelocity vel(setup.spec);
  std::fill(vel.u.begin(), vel.u.end(), 2.0f);
  std::fill(vel.v.begin(), vel.v.end(), -1.0f);
  wind.upload_velocity(vel);
  constexpr double e0 = 1.0;
  wind.upload_subgrid_energy(std::vector<float>(setup.spec.cell_count(), float(e0)));
  for (int n = 0; n < 400; ++n) wind.step();
  const auto e = wind.download_subgrid_energy();
  const double exact = fluid::tke_decay(e0, 1.0, 1.0, wind.time());
  double recursion = e0;
  for (int n = 0; n < 400; ++n) recursion /= 1.0 + 0.05 * 0.93 * std::sqrt(recursion);
  WARN("WindGrid decay: e(" << wind.time() << " s) = " << e[0] << ", closed form " << exact << ", recursion "
                            << recursion);
  for (float x : e) {
    CHECK(x == Approx(recursion).epsilon(1e-4));  // float steps against the double recursion
    CHECK(std::abs(x - exact) / exact < 0.01);
  }
  // The wind stays uniform (to the float rounding of the advection's interpolation weights).
  const auto out = wind.download_velocity();
  for (int c = 0; c < 3; ++c)
    for (std::size_t f = 0; f < out.component(c).size(); ++f)
      CHECK(out.component(c)[f] == Approx(vel.component(c)[f]).margin(1e-5));
}

TEST_CASE(
    "subgrid tke: a WindGrid run is bit-identical twice, and subgrid smagorinsky is the default exactly",
    "[subgrid]") {
  auto* cc = test::device_or_skip();
  if (!cc) return;
  host::WindGridSetup setup;
  setup.spec = tke_spec(1);
  setup.solid = box_and_step(setup.spec);
  setup.settings.dt = 0.3;
  setup.settings.wall_roughness_length = 0.1;
  setup.profile.type = fluid::InflowProfile::Type::log;
  setup.profile.reference_height = 10.0;
  setup.profile.roughness_length = 0.5;
  setup.ambient = {7.0, 3.0, 0.0};
  constexpr int kSteps = 8;
  const auto drag = random_drag(setup.spec.cell_count(), 53);
  auto run = [&](const host::WindGridSetup& s, std::vector<float>* energy,
                 std::map<std::string, double>* ms) {
    host::WindGrid wind(*cc, s);
    wind.set_canopy(drag);
    wind.set_stage_timing(ms != nullptr);
    wind.initialise_ambient();
    for (int n = 0; n < kSteps; ++n) wind.step();
    if (energy) *energy = wind.download_subgrid_energy();
    if (ms) *ms = wind.stage_ms();
    return wind.download_velocity();
  };
  auto tke = setup;
  tke.settings.subgrid = fluid::SubgridModel::tke;
  std::vector<float> first_e, second_e;
  std::map<std::string, double> stages;
  const auto first = run(tke, &first_e, &stages);
  const auto second = run(tke, &second_e, nullptr);
  CHECK(identical(first, second));
  CHECK(first_e == second_e);
  CHECK(stages.count("subgrid") == 1);
  for (int c = 0; c < 3; ++c)
    for (float x : first.component(c)) REQUIRE(std::isfinite(x));
  double most = 0.0;
  for (float x : first_e) most = std::max(most, double(x));
  CHECK(most > 0.01);  // the shear of the log profile and the canopy made some

  // The Smagorinsky model named explicitly is the default, bit for bit; the tke run is another flow.
  auto smagorinsky = setup;
  smagorinsky.settings.smagorinsky_constant = 0.17;
  auto named = smagorinsky;
  named.settings.subgrid = fluid::SubgridModel::smagorinsky;
  const auto plain = run(smagorinsky, nullptr, nullptr);
  CHECK(identical(run(named, nullptr, nullptr), plain));
  CHECK_FALSE(identical(first, plain));

  // e and the advected e are two floats a cell more than nu_t alone.
  CHECK(host::WindGrid::estimate_device_bytes(tke) ==
        host::WindGrid::estimate_device_bytes(smagorinsky) + 2 * tke.spec.cell_count() * sizeof(float));
}

TEST_CASE("subgrid tke: WindGrid refuses subgrid energy of a wrong size or value, and without the model",
          "[subgrid]") {
  auto* cc = test::device_or_skip();
  if (!cc) return;
  host::WindGridSetup setup;
  setup.spec = tke_spec(2);
  host::WindGrid smagorinsky(*cc, setup);
  CHECK_FALSE(smagorinsky.subgrid_tke_enabled());
  CHECK_FALSE(smagorinsky.subgrid_enabled());
  CHECK_THROWS_AS(smagorinsky.download_subgrid_energy(), std::logic_error);
  setup.settings.subgrid = fluid::SubgridModel::tke;
  host::WindGrid wind(*cc, setup);
  CHECK(wind.subgrid_enabled());
  using Catch::Matchers::Contains;
  CHECK_THROWS_WITH(wind.upload_subgrid_energy({1.0f}), Contains("subgrid energy"));
  std::vector<float> bad(setup.spec.cell_count(), 0.5f);
  bad[7] = -0.1f;
  CHECK_THROWS_WITH(wind.upload_subgrid_energy(bad), Contains(">= 0"));
  bad[7] = NAN;
  CHECK_THROWS_AS(wind.upload_subgrid_energy(bad), std::invalid_argument);
  setup.settings.smagorinsky_constant = 0.1;
  CHECK_THROWS_WITH(host::WindGrid(*cc, setup), Contains("smagorinsky_constant"));
}
