// Each wind-grid kernel against the CPU reference (fluid/ReferenceStages), on random fields over a grid with
// every boundary type and a yawed solid box, and again over a ragged grid (test::ragged_spec) whose ranges
// leave items past the arrays in their last work-groups.
#include <catch2/catch.hpp>

#include <algorithm>
#include <cmath>
#include <memory>

#include "fluid/PressureLevels.hpp"
#include "fluid/ReferenceStages.hpp"
#include "fluid/TurbulenceBox.hpp"
#include "host/stages/FluidStages.hpp"
#include "tests/support/Fields.hpp"
#include "tests/support/TestDevice.hpp"

using namespace fw;
namespace ref = fw::fluid::reference;
using B = fluid::BoundaryType;

namespace {

// The kernels run in float, the reference in double with float storage: agreement to a few float ulps of
// the field's magnitude, accumulated over ~60 interpolation operations.
constexpr double kStageTolerance = 2e-5;

struct StageFixture {
  host::ComputeContext& cc;
  fluid::GridSpec spec = test::mixed_boundary_spec();
  std::vector<std::uint8_t> solid = test::box_solid(spec);
  fluid::PressureLevel fine = fluid::build_fine_pressure_level(spec, solid);
  fluid::InflowState inflow = test::test_inflow(spec);
  host::FluidStages stages{cc, spec};
  cl::Buffer mask = cc.buffer(fine.cell_count());

  explicit StageFixture(host::ComputeContext& c, fluid::GridSpec grid = test::mixed_boundary_spec())
      : cc(c), spec(grid) {
    stages.set_profile(test::upload_profile(cc, inflow, spec));
    cc.queue().enqueueWriteBuffer(mask, CL_TRUE, 0, fine.cell_count(), fine.mask.data());
    set_step(0.4f, 3.0f);
  }
  void set_step(float dt, float time) {
    FwStep s{};
    s.dt = dt;
    s.time = time;
    for (int a = 0; a < 3; ++a) s.ambient[a] = inflow.ambient[a];
    host::set_step_turbulence(s, inflow);
    stages.set_step(s);
  }
  /// The reference's ghost value at every index of component c's padded copy, in its storage order.
  std::vector<float> expected_padded(const fluid::MacVelocity& vel, int c) const {
    constexpr int pad = FW_PAD;
    const int ex = ref::extent(spec, c, 0), ey = ref::extent(spec, c, 1), ez = ref::extent(spec, c, 2);
    std::vector<float> expected;
    for (int k = -pad; k < ez + pad; ++k)
      for (int j = -pad; j < ey + pad; ++j)
        for (int i = -pad; i < ex + pad; ++i)
          expected.push_back(float(ref::fetch(spec, inflow, vel.component(c), c, i, j, k)));
    return expected;
  }
  struct MacCormackResult {
    fluid::MacVelocity forward, corrected;
  };
  /// WindGrid::advect's MacCormack sequence on the device over dt: the forward semi-Lagrangian step, the
  /// backward step from the forward's padded copy, and the correction in place.
  MacCormackResult maccormack(const fluid::MacVelocity& vel, float dt) {
    auto dvel = stages.allocate_velocity(), fwd = stages.allocate_velocity(),
         back = stages.allocate_velocity();
    auto padded = stages.allocate_padded_velocity(), padded_fwd = stages.allocate_padded_velocity();
    test::upload(cc, vel, dvel);
    stages.enqueue_pad(dvel, padded);
    for (int c = 0; c < 3; ++c) stages.enqueue_advect(c, dt, padded, padded.component(c), fwd.component(c));
    stages.enqueue_pad(fwd, padded_fwd);
    for (int c = 0; c < 3; ++c)
      stages.enqueue_advect(c, -dt, padded, padded_fwd.component(c), back.component(c));
    for (int c = 0; c < 3; ++c)
      stages.enqueue_maccormack_correct(c, padded, padded.component(c), fwd.component(c), back.component(c),
                                        back.component(c));
    return {test::download(cc, fwd, spec), test::download(cc, back, spec)};
  }
  /// WindGrid::advect_upwind's sequence on the device over dt: three upwind stages from vel, the first two
  /// with their prescribed faces imposed (no projection).
  fluid::MacVelocity upwind5(const fluid::MacVelocity& vel, float dt) {
    auto orders = stages.upload_upwind_orders(fluid::upwind_orders(spec, solid));
    auto base = stages.allocate_velocity(), first = stages.allocate_velocity(),
         second = stages.allocate_velocity();
    auto padded = stages.allocate_padded_velocity();
    test::upload(cc, vel, base);
    const float fractions[] = {1.0f / 3.0f, 0.5f, 1.0f};
    host::DeviceVelocity* stage = &base;
    for (int n = 0; n < 3; ++n) {
      stages.enqueue_pad(*stage, padded);
      host::DeviceVelocity& out = n == 1 ? second : first;
      for (int c = 0; c < 3; ++c)
        stages.enqueue_upwind_stage(c, fractions[n] * dt, padded, orders, base.component(c),
                                    out.component(c));
      if (n < 2)
        for (int c = 0; c < 3; ++c) stages.enqueue_enforce_boundaries(c, mask, out.component(c));
      stage = &out;
    }
    return test::download(cc, first, spec);
  }
  /// One upwind stage on the device: vel + coef_dt R(vel).
  fluid::MacVelocity upwind_stage(const fluid::MacVelocity& vel, float coef_dt) {
    auto orders = stages.upload_upwind_orders(fluid::upwind_orders(spec, solid));
    auto dvel = stages.allocate_velocity(), out = stages.allocate_velocity();
    auto padded = stages.allocate_padded_velocity();
    test::upload(cc, vel, dvel);
    stages.enqueue_pad(dvel, padded);
    for (int c = 0; c < 3; ++c)
      stages.enqueue_upwind_stage(c, coef_dt, padded, orders, dvel.component(c), out.component(c));
    return test::download(cc, out, spec);
  }
  /// Inflow turbulence through the inflow faces (test::add_small_turbulence).
  void make_turbulent() {
    test::add_small_turbulence(inflow);
    stages.set_profile(test::upload_profile(cc, inflow, spec));
    set_step(0.4f, 3.0f);
  }
};

}  // namespace

TEST_CASE("ghosts: the padded copy holds the reference's ghost value at every index") {
  auto* cc = test::device_or_skip();
  if (!cc) return;
  StageFixture f(*cc, GENERATE(test::mixed_boundary_spec(), test::ragged_spec()));
  CAPTURE(f.spec.nx, f.spec.ny, f.spec.nz);
  const auto vel = test::random_velocity(f.spec, 3.0, 1);
  auto dvel = f.stages.allocate_velocity();
  auto padded = f.stages.allocate_padded_velocity();
  test::upload(*cc, vel, dvel);
  f.stages.enqueue_pad(dvel, padded);
  for (int c = 0; c < 3; ++c) {
    const auto device = test::download(*cc, padded.component(c), f.stages.padded_count(c));
    CHECK(test::relative_error(device, f.expected_padded(vel, c)) < 1e-6);  // copies, one product (profile)
  }
}

TEST_CASE("ghosts: inflow turbulence in the ghost layers matches the reference") {
  auto* cc = test::device_or_skip();
  if (!cc) return;
  StageFixture f(*cc, GENERATE(test::mixed_boundary_spec(), test::ragged_spec()));
  CAPTURE(f.spec.nx, f.spec.ny, f.spec.nz);
  f.make_turbulent();
  const auto vel = test::random_velocity(f.spec, 3.0, 1);
  auto dvel = f.stages.allocate_velocity();
  auto padded = f.stages.allocate_padded_velocity();
  test::upload(*cc, vel, dvel);
  f.stages.enqueue_pad(dvel, padded);
  double largest_turbulence = 0.0;
  for (int c = 0; c < 3; ++c) {
    const auto device = test::download(*cc, padded.component(c), f.stages.padded_count(c));
    // Trilinear interpolation of the box in float against double: a few ulps of the largest value.
    CHECK(test::relative_error(device, f.expected_padded(vel, c)) < 1e-5);
    // West ghosts are inflow: how far they stand from the laminar profile is the turbulence they carry.
    for (int k = 0; k < ref::extent(f.spec, c, 2); ++k)
      for (int j = 0; j < ref::extent(f.spec, c, 1); ++j) {
        const double laminar = f.inflow.ambient[c] * f.inflow.profile[std::min(k, f.spec.nz - 1)];
        const double ghost = ref::fetch(f.spec, f.inflow, vel.component(c), c, -1, j, k);
        largest_turbulence = std::max(largest_turbulence, std::abs(ghost - laminar));
      }
  }
  CHECK(largest_turbulence > 0.5);  // the ghosts do carry turbulence (sigma 1.7 m/s)
}

TEST_CASE(
    "ghosts: the prescribed shell serves inflow on three faces, corners included, and follows the box") {
  // Inflow west, south and top: a ghost beyond two of them (a corner) lies in two faces' shells, and the
  // lookup must find it in one; each later step (a new box offset) must re-sample the shell.
  auto* cc = test::device_or_skip();
  if (!cc) return;
  auto spec = test::mixed_boundary_spec();
  spec.boundary[FW_FACE_SOUTH] = B::inflow;
  spec.boundary[FW_FACE_NORTH] = B::slip;
  spec.boundary[FW_FACE_TOP] = B::inflow;
  StageFixture f(*cc, spec);
  f.make_turbulent();
  const auto vel = test::random_velocity(f.spec, 3.0, 2);
  auto dvel = f.stages.allocate_velocity();
  auto padded = f.stages.allocate_padded_velocity();
  test::upload(*cc, vel, dvel);
  for (int step = 0; step < 2; ++step) {
    INFO("step " << step);
    if (step == 1) {  // the box travels on
      f.inflow.turbulence_offset = {17.9f, -2.2f, 0.7f};
      f.set_step(0.4f, 3.4f);
    }
    f.stages.enqueue_pad(dvel, padded);
    for (int c = 0; c < 3; ++c) {
      const auto device = test::download(*cc, padded.component(c), f.stages.padded_count(c));
      // As in the single-face test: a float trilinear sample of the box against double.
      CHECK(test::relative_error(device, f.expected_padded(vel, c)) < 1e-5);
    }
    for (int c = 0; c < 3; ++c) f.stages.enqueue_enforce_boundaries(c, f.mask, dvel.component(c));
    auto expected = vel;
    ref::enforce_boundaries(f.spec, f.fine, f.inflow, expected);
    CHECK(test::relative_error(test::download(*cc, dvel, f.spec), expected) < 1e-5);
    test::upload(*cc, vel, dvel);
  }
}

TEST_CASE("ghosts: an inflow buffer without room for the shell is refused with the class name") {
  auto* cc = test::device_or_skip();
  if (!cc) return;
  StageFixture f(*cc, GENERATE(test::mixed_boundary_spec(), test::ragged_spec()));
  CAPTURE(f.spec.nx, f.spec.ny, f.spec.nz);
  auto turbulent = f.inflow;
  test::add_small_turbulence(turbulent);
  FwStep s = f.stages.step();
  host::set_step_turbulence(s, turbulent);
  // The fixture's buffer holds the profile only: a step with the turbulence on cannot be served.
  CHECK_THROWS_WITH(f.stages.set_step(s), Catch::Contains("FluidStages") && Catch::Contains("inflow buffer"));
}

TEST_CASE("advect: semi-Lagrangian RK2 kernel matches the CPU reference on random fields") {
  auto* cc = test::device_or_skip();
  if (!cc) return;
  StageFixture f(*cc, GENERATE(test::mixed_boundary_spec(), test::ragged_spec()));
  CAPTURE(f.spec.nx, f.spec.ny, f.spec.nz);
  // |u| up to 8 m/s, dt 0.4 s, h 2 m: back-traces travel up to ~1.6 cells and cross every boundary.
  auto vel = test::random_velocity(f.spec, 8.0, 11);
  test::match_periodic_faces(f.spec, vel);
  auto dvel = f.stages.allocate_velocity(), out = f.stages.allocate_velocity();
  auto padded = f.stages.allocate_padded_velocity();
  test::upload(*cc, vel, dvel);
  f.stages.enqueue_pad(dvel, padded);
  for (int c = 0; c < 3; ++c) f.stages.enqueue_advect(c, 0.4f, padded, padded.component(c), out.component(c));
  const auto device = test::download(*cc, out, f.spec);
  const auto expected = ref::advect_semi_lagrangian(f.spec, f.inflow, vel, vel, 0.4);
  for (int c = 0; c < 3; ++c) {
    INFO("component " << c);
    CHECK(test::relative_error(device.component(c), expected.component(c)) < kStageTolerance);
  }
}

TEST_CASE("advect: clamped MacCormack kernels match the CPU reference on random fields") {
  auto* cc = test::device_or_skip();
  if (!cc) return;
  StageFixture f(*cc, GENERATE(test::mixed_boundary_spec(), test::ragged_spec()));
  CAPTURE(f.spec.nx, f.spec.ny, f.spec.nz);
  auto vel = test::random_velocity(f.spec, 8.0, 21);
  test::match_periodic_faces(f.spec, vel);
  const auto device = f.maccormack(vel, 0.4f).corrected;
  const auto expected = ref::advect_maccormack(f.spec, f.inflow, vel, vel, 0.4);
  // The clamp is a switch: where the corrected value sits within rounding of the limit, float and double
  // may pick different branches. Such faces must be rare, and every other face must agree closely.
  for (int c = 0; c < 3; ++c) {
    CHECK(test::mismatch_fraction(device.component(c), expected.component(c), kStageTolerance) < 2e-3);
  }
}

TEST_CASE("advect: semi-Lagrangian and MacCormack kernels match the CPU reference in a smooth wind") {
  // Random fields send most work-items down the gathers; in a smooth wind the back-traced cells of a
  // work-item's consecutive faces lie along one row, so most take the windowed loads (kernels/lanes.cl).
  // Over dt 0.4 s and h 2 m the mean (3.75, 1.25, -1.25) m/s moves (0.75, 0.25, -0.25) cells. The ripple
  // in u, up to 1.5 m/s, moves the x-displacement across 0.5 and 1 cells, so that a work-item's lanes
  // straddle two shifts; the 0.2 m/s ripples in v and w keep each item's lanes on one row.
  auto* cc = test::device_or_skip();
  if (!cc) return;
  StageFixture f(*cc, GENERATE(test::mixed_boundary_spec(), test::ragged_spec()));
  CAPTURE(f.spec.nx, f.spec.ny, f.spec.nz);
  auto vel = test::smooth_velocity(f.spec, {3.75, 1.25, -1.25}, {1.5, 0.2, 0.2});
  test::match_periodic_faces(f.spec, vel);
  const auto [forward, corrected] = f.maccormack(vel, 0.4f);
  const auto expected_forward = ref::advect_semi_lagrangian(f.spec, f.inflow, vel, vel, 0.4);
  const auto expected_corrected = ref::advect_maccormack(f.spec, f.inflow, vel, vel, 0.4);
  for (int c = 0; c < 3; ++c) {
    INFO("component " << c);
    CHECK(test::relative_error(forward.component(c), expected_forward.component(c)) < kStageTolerance);
    // As on random fields: the clamp may switch differently in float and double at a few faces.
    CHECK(test::mismatch_fraction(corrected.component(c), expected_corrected.component(c), kStageTolerance) <
          2e-3);
  }
}

TEST_CASE("advect: an upwind5 stage matches the CPU reference on random fields, short rows included") {
  // Random values make every flux's upwind side and order matter. The mixed grid has every boundary type
  // and a solid box (so all three orders occur); a 10-cell variant has rows shorter than the lanes.
  auto* cc = test::device_or_skip();
  if (!cc) return;
  auto short_rows = test::mixed_boundary_spec();
  short_rows.nx = 10;
  for (const auto& grid : {test::mixed_boundary_spec(), short_rows, test::ragged_spec()}) {
    StageFixture f(*cc, grid);
    auto vel = test::random_velocity(f.spec, 8.0, 31);
    test::match_periodic_faces(f.spec, vel);
    const auto device = f.upwind_stage(vel, 0.4f);
    const auto expected =
        ref::upwind_stage(f.spec, f.inflow, fluid::upwind_orders(f.spec, f.solid), vel, vel, 0.4);
    for (int c = 0; c < 3; ++c) {
      INFO("nx " << f.spec.nx << ", component " << c);
      CHECK(test::relative_error(device.component(c), expected.component(c)) < kStageTolerance);
    }
  }
}

TEST_CASE("advect: upwind5's three Runge-Kutta stages match the CPU reference in a smooth wind") {
  auto* cc = test::device_or_skip();
  if (!cc) return;
  StageFixture f(*cc, GENERATE(test::mixed_boundary_spec(), test::ragged_spec()));
  CAPTURE(f.spec.nx, f.spec.ny, f.spec.nz);
  f.make_turbulent();  // the inflow ghosts carry turbulence through every stage
  auto vel = test::smooth_velocity(f.spec, {3.75, 1.25, -1.25}, {1.5, 0.2, 0.2});
  test::match_periodic_faces(f.spec, vel);
  // dt 0.4 s, h 2 m and speeds up to about 5 m/s: a summed Courant number near 1, inside the limit.
  const auto device = f.upwind5(vel, 0.4f);
  const auto expected =
      ref::advect_upwind5(f.spec, f.fine, f.inflow, fluid::upwind_orders(f.spec, f.solid), vel, 0.4);
  for (int c = 0; c < 3; ++c) {
    INFO("component " << c);
    CHECK(test::relative_error(device.component(c), expected.component(c)) < kStageTolerance);
  }
}

TEST_CASE("forces: body force and travelling gusts match the CPU reference") {
  auto* cc = test::device_or_skip();
  if (!cc) return;
  StageFixture f(*cc, GENERATE(test::mixed_boundary_spec(), test::ragged_spec()));
  CAPTURE(f.spec.nx, f.spec.ny, f.spec.nz);
  f.set_step(0.25f, 4.0f);
  std::vector<FwGust> gusts(2);
  gusts[0] = FwGust{2.0f, 6.0f, 12.0f, 9.0f, {0.0f, 20.0f, 8.0f}, {5.0f, 1.0f, 0.0f}, {0.8f, 0.6f, 0.0f}};
  gusts[1] = FwGust{3.5f, 2.0f, -4.0f, 5.0f, {20.0f, 30.0f, 10.0f}, {0.0f, 0.0f, 1.0f}, {0.0f, 0.0f, 1.0f}};
  cl::Buffer dgusts = cc->buffer(gusts.size() * sizeof(FwGust));
  cc->queue().enqueueWriteBuffer(dgusts, CL_TRUE, 0, gusts.size() * sizeof(FwGust), gusts.data());
  auto vel = test::random_velocity(f.spec, 1.0, 31);
  auto dvel = f.stages.allocate_velocity();
  test::upload(*cc, vel, dvel);
  const std::array<double, 3> g{0.5, -0.25, 0.0};
  for (int c = 0; c < 3; ++c) f.stages.enqueue_apply_forces(c, float(g[c]), dgusts, 2, dvel.component(c));
  const auto device = test::download(*cc, dvel, f.spec);
  ref::add_body_force(vel, g, 0.25);
  ref::add_gusts(f.spec, vel, gusts, 4.0, 0.25);
  CHECK(test::relative_error(device, vel) < kStageTolerance);
  // The gusts did something: the field differs from body force alone by more than rounding.
  auto body_only = test::random_velocity(f.spec, 1.0, 31);
  ref::add_body_force(body_only, g, 0.25);
  CHECK(test::relative_error(body_only, vel) > 1e-2);
}

TEST_CASE("forces: vorticity and vorticity confinement match the CPU reference") {
  auto* cc = test::device_or_skip();
  if (!cc) return;
  StageFixture f(*cc, GENERATE(test::mixed_boundary_spec(), test::ragged_spec()));
  CAPTURE(f.spec.nx, f.spec.ny, f.spec.nz);
  auto vel = test::random_velocity(f.spec, 3.0, 41);
  auto dvel = f.stages.allocate_velocity();
  test::upload(*cc, vel, dvel);
  cl::Buffer vorticity = cc->buffer(f.spec.cell_count() * 4 * sizeof(float));
  f.stages.enqueue_vorticity(dvel, vorticity);
  const auto device_vorticity = test::download(*cc, vorticity, f.spec.cell_count() * 4);
  CHECK(test::relative_error(device_vorticity, ref::vorticity(f.spec, vel)) < kStageTolerance);
  for (int c = 0; c < 3; ++c) f.stages.enqueue_vorticity_confinement(c, 0.3f, vorticity, dvel.component(c));
  const auto device = test::download(*cc, dvel, f.spec);
  ref::add_vorticity_confinement(f.spec, vel, 0.3, 0.4);
  // N = grad|w| / |grad|w|| amplifies rounding where the gradient is tiny; 1e-4 covers it.
  CHECK(test::relative_error(device, vel) < 1e-4);
}

TEST_CASE("forces: explicit viscous diffusion matches the CPU reference, ghosts included") {
  auto* cc = test::device_or_skip();
  if (!cc) return;
  StageFixture f(*cc, GENERATE(test::mixed_boundary_spec(), test::ragged_spec()));
  CAPTURE(f.spec.nx, f.spec.ny, f.spec.nz);
  const auto vel = test::random_velocity(f.spec, 2.0, 51);
  auto dvel = f.stages.allocate_velocity(), out = f.stages.allocate_velocity();
  test::upload(*cc, vel, dvel);
  const double nu = 0.9, dt = 0.4;  // nu dt / h^2 = 0.09
  for (int c = 0; c < 3; ++c)
    f.stages.enqueue_diffuse(c, float(nu * dt / (f.spec.h * f.spec.h)), dvel.component(c), out.component(c));
  CHECK(test::relative_error(test::download(*cc, out, f.spec), ref::diffuse(f.spec, f.inflow, vel, nu, dt)) <
        kStageTolerance);
}

TEST_CASE("boundaries: prescribed faces match the CPU reference") {
  auto* cc = test::device_or_skip();
  if (!cc) return;
  StageFixture f(*cc, GENERATE(test::mixed_boundary_spec(), test::ragged_spec()));
  CAPTURE(f.spec.nx, f.spec.ny, f.spec.nz);
  auto vel = test::random_velocity(f.spec, 2.0, 61);
  auto dvel = f.stages.allocate_velocity();
  test::upload(*cc, vel, dvel);
  for (int c = 0; c < 3; ++c) f.stages.enqueue_enforce_boundaries(c, f.mask, dvel.component(c));
  const auto device = test::download(*cc, dvel, f.spec);
  ref::enforce_boundaries(f.spec, f.fine, f.inflow, vel);
  CHECK(test::relative_error(device, vel) == 0.0);  // pure copies and assignments: exact
  // West inflow faces carry the profile: u = 7 m/s * shape(z) beside fluid cells.
  const int k = 5;
  CHECK(device.u[ref::face_index(f.spec, 0, 0, 3, k)] == Approx(7.0 * f.inflow.profile[k]).epsilon(1e-6));
}

TEST_CASE("boundaries: inflow faces with turbulence match the CPU reference") {
  auto* cc = test::device_or_skip();
  if (!cc) return;
  StageFixture f(*cc, GENERATE(test::mixed_boundary_spec(), test::ragged_spec()));
  CAPTURE(f.spec.nx, f.spec.ny, f.spec.nz);
  f.make_turbulent();
  auto vel = test::random_velocity(f.spec, 2.0, 61);
  auto dvel = f.stages.allocate_velocity();
  test::upload(*cc, vel, dvel);
  for (int c = 0; c < 3; ++c) f.stages.enqueue_enforce_boundaries(c, f.mask, dvel.component(c));
  const auto device = test::download(*cc, dvel, f.spec);
  ref::enforce_boundaries(f.spec, f.fine, f.inflow, vel);
  CHECK(test::relative_error(device, vel) < 1e-5);  // float trilinear box sample against double
  // A west face above the reference height: the ambient wind plus sigma times the box's own value there.
  const int j = 3, k = 8;
  const double x = f.spec.origin[0] - f.inflow.turbulence_offset[0];
  const double y = f.spec.origin[1] + f.spec.h * (j + 0.5) - f.inflow.turbulence_offset[1];
  const double z = f.spec.origin[2] + f.spec.h * (k + 0.5) - f.inflow.turbulence_offset[2];
  const double taper = std::min(1.0, f.inflow.profile[k] / double(FW_TURBULENCE_FULL_SHAPE));
  const double expected = 7.0 * f.inflow.profile[k] + 1.7 * taper * f.inflow.turbulence->sample(x, y, z)[0];
  CHECK(device.u[ref::face_index(f.spec, 0, 0, j, k)] == Approx(expected).epsilon(1e-5));
}

TEST_CASE("project: divergence right-hand side and gradient subtraction match the CPU reference") {
  auto* cc = test::device_or_skip();
  if (!cc) return;
  StageFixture f(*cc, GENERATE(test::mixed_boundary_spec(), test::ragged_spec()));
  CAPTURE(f.spec.nx, f.spec.ny, f.spec.nz);
  auto vel = test::random_velocity(f.spec, 2.0, 71);
  ref::enforce_boundaries(f.spec, f.fine, f.inflow, vel);
  auto dvel = f.stages.allocate_velocity();
  test::upload(*cc, vel, dvel);
  cl::Buffer b = cc->buffer(f.spec.cell_count() * sizeof(float));
  f.stages.enqueue_divergence_rhs(f.mask, dvel, b);
  const auto expected_b = ref::divergence_rhs(f.spec, f.fine, vel);
  CHECK(test::relative_error(test::download(*cc, b, f.spec.cell_count()), expected_b) < kStageTolerance);
  CHECK(f.stages.max_divergence(f.mask, dvel) ==
        Approx(ref::max_divergence(f.spec, f.fine, vel)).epsilon(kStageTolerance));

  const auto phi = test::random_cells(f.spec.cell_count(), 5.0, 72);
  cl::Buffer dphi = cc->buffer(phi.size() * sizeof(float));
  test::upload(*cc, phi, dphi);
  for (int c = 0; c < 3; ++c) f.stages.enqueue_subtract_gradient(c, f.mask, dphi, dvel.component(c));
  ref::subtract_gradient(f.spec, f.fine, phi, vel);
  CHECK(test::relative_error(test::download(*cc, dvel, f.spec), vel) < kStageTolerance);
}

TEST_CASE("project: max speed reduction finds the largest component and reports NaN") {
  auto* cc = test::device_or_skip();
  if (!cc) return;
  StageFixture f(*cc, GENERATE(test::mixed_boundary_spec(), test::ragged_spec()));
  CAPTURE(f.spec.nx, f.spec.ny, f.spec.nz);
  auto vel = test::random_velocity(f.spec, 2.0, 81);
  vel.w[123] = -9.5f;
  auto dvel = f.stages.allocate_velocity();
  test::upload(*cc, vel, dvel);
  CHECK(f.stages.max_speed_component(dvel) == Approx(9.5));
  vel.v[77] = NAN;
  test::upload(*cc, vel, dvel);
  CHECK(std::isnan(f.stages.max_speed_component(dvel)));
}
