// Canopy drag: the canopy_drag_{u,v,w} kernels against fluid::reference::canopy_drag, and its effect in a
// channel flow on the device (WindGrid::set_canopy).
#include <catch2/catch.hpp>

#include <chrono>
#include <cmath>
#include <cstring>
#include <random>
#include <vector>

#include "fluid/CanopyField.hpp"
#include "fluid/PressureLevels.hpp"
#include "fluid/ReferenceStages.hpp"
#include "host/stages/FluidStages.hpp"
#include "host/stages/WindGrid.hpp"
#include "tests/support/Fields.hpp"
#include "tests/support/TestDevice.hpp"

using namespace fw;
namespace ref = fw::fluid::reference;
using B = fluid::BoundaryType;

namespace {

// Float kernel against the double reference: one square root, a few sums and one division per face, so a
// few float ulps of each face's own value.
constexpr double kDragTolerance = 2e-6;

// Drag density in [0, 0.5] 1/m, zero in about a third of the cells (the kernel's copy path).
std::vector<float> random_drag(std::size_t n, std::uint32_t seed) {
  std::mt19937 rng(seed);
  std::uniform_real_distribution<float> k(0.0f, 0.5f);
  std::uniform_int_distribution<int> empty(0, 2);
  std::vector<float> out(n);
  for (auto& x : out) x = empty(rng) == 0 ? 0.0f : k(rng);
  return out;
}

// The kernels' drag of `vel` by the density `drag` on the faces next to its non-zero cells, read back.
fluid::MacVelocity drag_on_device(host::ComputeContext& cc, host::FluidStages& stages,
                                  const fluid::GridSpec& spec, const fluid::MacVelocity& vel,
                                  const std::vector<float>& drag, const fluid::DragLaw& law = {}) {
  auto dvel = stages.allocate_velocity(), scratch = stages.allocate_velocity();
  test::upload(cc, vel, dvel);
  cl::Buffer ddrag = cc.buffer(drag.size() * sizeof(float));
  test::upload(cc, drag, ddrag);
  stages.enqueue_canopy_drag(ddrag, host::nonzero_cell_box(spec, drag), dvel, scratch, law);
  return test::download(cc, dvel, spec);
}

// Largest |a - b| / |b| over faces (faces with b = 0 compared absolutely).
double face_relative_error(const std::vector<float>& a, const std::vector<float>& b) {
  double worst = 0.0;
  for (std::size_t i = 0; i < a.size(); ++i)
    worst = std::max(worst, std::abs(double(a[i]) - b[i]) / std::max(std::abs(double(b[i])), 1e-30));
  return worst;
}

}  // namespace

TEST_CASE(
    "canopy drag: with a drag law the kernel matches the reference, and a uniform wind slows by its factor",
    "[canopy]") {
  auto* cc = test::device_or_skip();
  if (!cc) return;
  const auto spec = test::mixed_boundary_spec();
  host::FluidStages stages(*cc, spec);
  FwStep s{};
  s.dt = 0.4f;
  stages.set_step(s);
  const fluid::DragLaw law{-0.8, 3.0};
  const auto drag = random_drag(spec.cell_count(), 7);
  auto run = [&](const fluid::MacVelocity& vel, const fluid::DragLaw& l) {
    return drag_on_device(*cc, stages, spec, vel, drag, l);
  };
  const auto random = test::random_velocity(spec, 8.0, 31);
  const auto device = run(random, law);
  const auto expected = ref::canopy_drag(spec, random, drag, 0.4, law);
  for (int c = 0; c < 3; ++c)
    CHECK(face_relative_error(device.component(c), expected.component(c)) < kDragTolerance);
  // In a uniform 6 m/s wind every face's implicit deceleration rate k f |u| carries the factor f(6) =
  // 2^-0.8: (q / out - 1) over the constant law's is f, to float rounding of the two quotients.
  fluid::MacVelocity uniform(spec);
  for (float& u : uniform.u) u = 6.0f;
  const auto with_law = run(uniform, law), constant = run(uniform, {});
  const double factor = law.factor(6.0);
  REQUIRE(factor == Approx(std::pow(2.0, -0.8)));
  double worst = 0.0;
  for (std::size_t f = 0; f < uniform.u.size(); ++f) {
    const double rate_law = 6.0 / with_law.u[f] - 1.0, rate_constant = 6.0 / constant.u[f] - 1.0;
    if (rate_constant > 1e-2) worst = std::max(worst, std::abs(rate_law / rate_constant / factor - 1.0));
  }
  CHECK(worst < 1e-4);  // float quotients near 1: a few ulps (6e-8) over rates of 0.01 and more
}

TEST_CASE("canopy drag: the kernel matches the CPU reference on a random field", "[canopy]") {
  auto* cc = test::device_or_skip();
  if (!cc) return;
  const auto spec = test::mixed_boundary_spec();
  host::FluidStages stages(*cc, spec);
  FwStep s{};
  s.dt = 0.4f;
  s.time = 2.0f;
  stages.set_step(s);
  const auto vel = test::random_velocity(spec, 8.0, 31);
  const auto drag = random_drag(spec.cell_count(), 7);
  const auto device = drag_on_device(*cc, stages, spec, vel, drag);
  const auto expected = ref::canopy_drag(spec, vel, drag, 0.4);
  for (int c = 0; c < 3; ++c) {
    INFO("component " << c);
    CHECK(face_relative_error(device.component(c), expected.component(c)) < kDragTolerance);
    // Implicit: every face slows down or keeps its value, and none changes sign.
    std::size_t slowed = 0;
    for (std::size_t f = 0; f < expected.component(c).size(); ++f) {
      const float before = vel.component(c)[f], after = device.component(c)[f];
      CHECK(std::abs(after) <= std::abs(before));
      CHECK(after * before >= 0.0f);
      slowed += std::abs(after) < std::abs(before);
    }
    CHECK(slowed > expected.component(c).size() / 2);
  }
}

TEST_CASE("canopy drag: only the faces of the drag's box change, and they match the reference", "[canopy]") {
  auto* cc = test::device_or_skip();
  if (!cc) return;
  // The ragged grid's box of faces ends in part-filled work-groups (test::ragged_spec).
  const auto spec = GENERATE(test::mixed_boundary_spec(), test::ragged_spec());
  CAPTURE(spec.nx, spec.ny, spec.nz);
  host::FluidStages stages(*cc, spec);
  FwStep s{};
  s.dt = 0.3f;
  stages.set_step(s);
  const auto vel = test::random_velocity(spec, 6.0, 5);
  // Drag in a block of cells away from every wall, and in one cell on the east wall's far corner.
  std::vector<float> drag(spec.cell_count(), 0.0f);
  for (int k = 1; k < 3; ++k)
    for (int j = 2; j < 4; ++j)
      for (int i = 1; i < 3; ++i) drag[std::size_t(i + spec.nx * (j + spec.ny * k))] = 0.4f;
  const host::CellBox block = host::nonzero_cell_box(spec, drag);
  CHECK(block.first == std::array<int, 3>{1, 2, 1});
  CHECK(block.count == std::array<int, 3>{2, 2, 2});
  drag[spec.cell_count() - 1] = 0.2f;
  const host::CellBox box = host::nonzero_cell_box(spec, drag);
  CHECK(box.first == std::array<int, 3>{1, 2, 1});
  CHECK(box.count == std::array<int, 3>{spec.nx - 1, spec.ny - 2, spec.nz - 1});
  CHECK(host::nonzero_cell_box(spec, std::vector<float>(spec.cell_count(), 0.0f)).empty());

  const auto device = drag_on_device(*cc, stages, spec, vel, drag);  // over `box`
  const auto expected = ref::canopy_drag(spec, vel, drag, 0.3);
  std::size_t changed = 0;
  for (int c = 0; c < 3; ++c) {
    INFO("component " << c);
    CHECK(face_relative_error(device.component(c), expected.component(c)) < kDragTolerance);
    for (std::size_t f = 0; f < vel.component(c).size(); ++f)
      changed += device.component(c)[f] != vel.component(c)[f];
  }
  // The block's 8 cells touch 3 x 12 faces, the corner cell 3 x 2 more (some of them are wall faces), and
  // the corner's north v face is the periodic seam's, which is the v face 0 below it too.
  CHECK(changed >= 30);
  CHECK(changed <= 43);
}

TEST_CASE(
    "canopy drag: a periodic seam's face takes the cells on both sides, as face 0 and as face n, on the "
    "device too",
    "[canopy]") {
  auto* cc = test::device_or_skip();
  if (!cc) return;
  // Periodic along x and y; drag 0.4 / m in the last column of cells along x only. Uniform wind (3, 0, 0)
  // m/s, dt = 0.5 s: the seam's u faces (face 0 and face nx, the same face) see k = (0 + 0.4) / 2, as the
  // column's west face does, so u = 3 / (1 + 0.5 * 0.2 * 3) on both sides of the column.
  fluid::GridSpec spec = test::mixed_boundary_spec();
  spec.boundary[FW_FACE_WEST] = B::periodic;
  spec.boundary[FW_FACE_EAST] = B::periodic;
  host::FluidStages stages(*cc, spec);
  FwStep s{};
  s.dt = 0.5f;
  stages.set_step(s);
  fluid::MacVelocity vel(spec);
  std::fill(vel.u.begin(), vel.u.end(), 3.0f);
  std::vector<float> drag(spec.cell_count(), 0.0f);
  for (int k = 0; k < spec.nz; ++k)
    for (int j = 0; j < spec.ny; ++j) drag[std::size_t(spec.nx - 1 + spec.nx * (j + spec.ny * k))] = 0.4f;
  const auto device = drag_on_device(*cc, stages, spec, vel, drag);
  const auto expected = ref::canopy_drag(spec, vel, drag, 0.5);
  const double seam = 3.0 / (1.0 + 0.5 * 0.2 * 3.0);
  const std::size_t ex = std::size_t(spec.nx) + 1;
  for (int k = 0; k < spec.nz; ++k)
    for (int j = 0; j < spec.ny; ++j) {
      const std::size_t row = ex * (j + std::size_t(spec.ny) * k);
      CHECK(expected.u[row] == Approx(seam).epsilon(1e-7));                // face 0
      CHECK(expected.u[row + spec.nx] == Approx(seam).epsilon(1e-7));      // face n, the same face
      CHECK(expected.u[row + spec.nx - 1] == Approx(seam).epsilon(1e-7));  // the column's west face
      CHECK(device.u[row] == Approx(seam).epsilon(kDragTolerance));
      CHECK(device.u[row + spec.nx] == device.u[row]);
    }
  CHECK(face_relative_error(device.u, expected.u) < kDragTolerance);
}

TEST_CASE("canopy drag: the reference is u / (1 + dt k |u|) in a uniform field", "[canopy]") {
  // Uniform wind (3, 4, 0) m/s, |u| = 5, uniform k = 0.2 1/m, dt = 0.5 s: every face scales by 1/1.5.
  fluid::GridSpec spec;
  spec.nx = 5;
  spec.ny = 4;
  spec.nz = 3;
  spec.h = 2.0;
  fluid::MacVelocity vel(spec);
  std::fill(vel.u.begin(), vel.u.end(), 3.0f);
  std::fill(vel.v.begin(), vel.v.end(), 4.0f);
  const auto out = ref::canopy_drag(spec, vel, std::vector<float>(spec.cell_count(), 0.2f), 0.5);
  for (float x : out.u) CHECK(x == Approx(2.0).epsilon(1e-7));
  for (float x : out.v) CHECK(x == Approx(4.0 / 1.5).epsilon(1e-7));
  for (float x : out.w) CHECK(x == 0.0f);
  CHECK_THROWS_AS(ref::canopy_drag(spec, vel, std::vector<float>(3, 0.2f), 0.5), std::invalid_argument);
}

namespace {

// A 48 x 16 x 16 m channel: uniform 3 m/s inflow from the west, outflow east, slip walls.
host::WindGridSetup channel_setup() {
  host::WindGridSetup setup;
  auto& spec = setup.spec;
  spec.nx = 48;
  spec.ny = 16;
  spec.nz = 16;
  spec.h = 1.0;
  spec.boundary = {B::inflow, B::outflow, B::slip, B::slip, B::slip, B::slip};
  setup.settings.dt = 0.2;  // CFL 0.6 at the inflow speed
  setup.settings.pressure.tolerance = 1e-5;
  setup.ambient = {3.0, 0.0, 0.0};
  return setup;
}

// Dense canopy block x 16-24, y 4-12, z 0-10 m of foliage with leaf area density 1.5 1/m and C_D 0.4,
// rasterised by fluid::CanopyField (one vertical element of length h through each cell's centre): under
// the drag convention F = 1/2 rho C_D A |u| u, k = 1/2 C_D a = 0.3 1/m.
constexpr double kBlockLeafAreaDensity = 1.5;  // 1/m
constexpr double kBlockDragCoefficient = 0.4;  // trees::WindBasisSettings::kFoliageDragCoefficient
constexpr double kBlockDragDensity = 0.5 * kBlockDragCoefficient * kBlockLeafAreaDensity;  // 0.3 1/m

std::vector<float> block_canopy(const fluid::GridSpec& spec) {
  fluid::CanopyField canopy(spec);
  const double h = spec.h;
  const double per_metre = kBlockLeafAreaDensity * h * h;  // a = alpha h / h^3
  std::vector<fluid::CanopyElement> elements;
  for (int kk = 0; kk < 10; ++kk)
    for (int j = 4; j < 12; ++j)
      for (int i = 16; i < 24; ++i) {
        const double x = spec.origin[0] + (i + 0.5) * h, y = spec.origin[1] + (j + 0.5) * h;
        const double z = spec.origin[2] + kk * h;
        elements.push_back({{x, y, z}, {x, y, z + h}, per_metre, kBlockDragCoefficient * per_metre});
      }
  canopy.add_elements(elements);
  return canopy.drag_density();
}

// Mean cell-centred speed over cells [i0, i1) x [4, 12) x [0, 10).
double mean_speed(const fluid::GridSpec& spec, const fluid::MacVelocity& vel, int i0, int i1) {
  double sum = 0.0;
  int n = 0;
  for (int k = 0; k < 10; ++k)
    for (int j = 4; j < 12; ++j)
      for (int i = i0; i < i1; ++i) {
        const double u =
            0.5 * (vel.u[ref::face_index(spec, 0, i, j, k)] + vel.u[ref::face_index(spec, 0, i + 1, j, k)]);
        const double v =
            0.5 * (vel.v[ref::face_index(spec, 1, i, j, k)] + vel.v[ref::face_index(spec, 1, i, j + 1, k)]);
        const double w =
            0.5 * (vel.w[ref::face_index(spec, 2, i, j, k)] + vel.w[ref::face_index(spec, 2, i, j, k + 1)]);
        sum += std::sqrt(u * u + v * v + w * w);
        ++n;
      }
  return sum / n;
}

bool identical(const fluid::MacVelocity& a, const fluid::MacVelocity& b) {
  for (int c = 0; c < 3; ++c)
    if (a.component(c).size() != b.component(c).size() ||
        std::memcmp(a.component(c).data(), b.component(c).data(), a.component(c).size() * sizeof(float)) != 0)
      return false;
  return true;
}

}  // namespace

TEST_CASE("canopy drag: a dense canopy block slows the channel flow inside and behind it", "[canopy]") {
  auto* cc = test::device_or_skip();
  if (!cc) return;
  const auto setup = channel_setup();
  const auto& spec = setup.spec;
  constexpr int kSteps = 120;  // 24 s, 1.5 flow-through times

  auto run = [&](auto&& configure) {
    host::WindGrid wind(*cc, setup);
    configure(wind);
    wind.initialise_ambient();
    for (int n = 0; n < kSteps; ++n) wind.step();
    return wind.download_velocity();
  };
  // The rasterised block holds k = 1/2 C_D a in its cells and nothing elsewhere.
  const auto k = block_canopy(spec);
  double block_sum = 0.0;
  for (float x : k) block_sum += x;
  CHECK(k[std::size_t(20 + spec.nx * (8 + spec.ny * 5))] == Approx(kBlockDragDensity).epsilon(1e-6));
  CHECK(block_sum == Approx(8 * 8 * 10 * kBlockDragDensity).epsilon(1e-6));

  const auto open = run([](host::WindGrid&) {});
  const auto forest = run([&](host::WindGrid& w) {
    w.set_canopy(k);
    CHECK(w.canopy_enabled());
  });

  for (int c = 0; c < 3; ++c)
    for (float x : forest.component(c)) REQUIRE(std::isfinite(x));
  const double inside_open = mean_speed(spec, open, 16, 24), inside = mean_speed(spec, forest, 16, 24);
  const double lee_open = mean_speed(spec, open, 24, 32), lee = mean_speed(spec, forest, 24, 32);
  const double inside_drop = 1.0 - inside / inside_open, lee_drop = 1.0 - lee / lee_open;
  WARN("canopy block (k = " << kBlockDragDensity << " 1/m): mean speed inside " << inside << " m/s vs "
                            << inside_open << " open (" << 100 * inside_drop << "% lower); in the lee " << lee
                            << " vs " << lee_open << " (" << 100 * lee_drop << "% lower)");
  CHECK(inside_drop > 0.2);
  CHECK(lee_drop > 0.2);

  // The projection still conserves mass: every cross-section carries the inflow flux, the air the canopy
  // holds back goes around and over it.
  auto flux_at = [&](const fluid::MacVelocity& vel, int i) {
    double sum = 0.0;
    for (int k = 0; k < spec.nz; ++k)
      for (int j = 0; j < spec.ny; ++j) sum += vel.u[ref::face_index(spec, 0, i, j, k)];
    return sum * spec.h * spec.h;
  };
  const double inflow = flux_at(forest, 0);
  CHECK(inflow == Approx(3.0 * 16 * 16).epsilon(1e-6));
  double worst = 0.0;
  for (int i : {8, 16, 20, 24, 28, 40, 48})
    worst = std::max(worst, std::abs(flux_at(forest, i) - inflow) / inflow);
  WARN("canopy block: largest relative flux error over cross-sections " << worst);
  CHECK(worst < 1e-4);
  // Beside and above the block the wind speeds up.
  CHECK(forest.u[ref::face_index(spec, 0, 20, 1, 5)] > open.u[ref::face_index(spec, 0, 20, 1, 5)]);
  CHECK(forest.u[ref::face_index(spec, 0, 20, 8, 13)] > open.u[ref::face_index(spec, 0, 20, 8, 13)]);
  const auto levels = fluid::build_fine_pressure_level(spec, {});
  CHECK(ref::max_divergence(spec, levels, forest) < 1e-3);

  SECTION("switched off, the run is bit-identical to one that never set a canopy") {
    const auto cleared = run([&](host::WindGrid& w) {
      w.set_canopy(block_canopy(spec));
      w.set_canopy({});
      CHECK_FALSE(w.canopy_enabled());
    });
    CHECK(identical(cleared, open));
    const auto zero =
        run([&](host::WindGrid& w) { w.set_canopy(std::vector<float>(spec.cell_count(), 0.0f)); });
    CHECK(identical(zero, open));
  }
}

TEST_CASE("canopy drag: WindGrid::set_canopy rejects bad fields", "[canopy]") {
  auto* cc = test::device_or_skip();
  if (!cc) return;
  host::WindGrid wind(*cc, channel_setup());
  using Catch::Matchers::Contains;
  CHECK_THROWS_WITH(wind.set_canopy(std::vector<float>(7, 0.1f)), Contains("WindGrid") && Contains("cells"));
  auto k = block_canopy(wind.spec());
  k[5] = -0.1f;
  CHECK_THROWS_WITH(wind.set_canopy(k), Contains("WindGrid"));
  k[5] = NAN;
  CHECK_THROWS_AS(wind.set_canopy(k), std::invalid_argument);
  CHECK_FALSE(wind.canopy_enabled());
}

TEST_CASE("canopy drag: stage cost on a 128 x 128 x 64 grid", "[.][bench]") {
  auto* cc = test::device_or_skip();
  if (!cc) return;
  host::WindGridSetup setup;
  auto& spec = setup.spec;
  spec.nx = 128;
  spec.ny = 128;
  spec.nz = 64;
  spec.h = 2.0;
  spec.boundary = {B::inflow, B::outflow, B::periodic, B::periodic, B::no_slip, B::slip};
  setup.settings.dt = 0.2;
  setup.ambient = {8.0, 0.0, 0.0};
  host::WindGrid wind(*cc, setup);
  // A forest over the middle half of the ground, 20 m (10 cells) tall.
  std::vector<float> k(spec.cell_count(), 0.0f);
  for (int kk = 0; kk < 10; ++kk)
    for (int j = 0; j < spec.ny; ++j)
      for (int i = 32; i < 96; ++i)
        k[std::size_t(i) + std::size_t(spec.nx) * (j + std::size_t(spec.ny) * kk)] = 0.2f;
  wind.set_canopy(k);
  wind.initialise_ambient();
  wind.step();  // warm-up: kernel builds
  wind.set_stage_timing(true);
  wind.reset_stage_ms();
  constexpr int kSteps = 5;
  for (int n = 0; n < kSteps; ++n) wind.step();
  double total = 0.0;
  for (const auto& [name, ms] : wind.stage_ms()) total += ms;
  for (const auto& [name, ms] : wind.stage_ms()) WARN(name << ": " << ms / kSteps << " ms/step");
  WARN("canopy: " << wind.stage_ms().at("canopy") / kSteps << " ms/step of " << total / kSteps << " ms/step");
  CHECK(wind.stage_ms().count("canopy") == 1);
}
