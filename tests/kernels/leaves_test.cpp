// The leaves' kernels (host/stages/LeafStages: kernels/leaves.cl) against the CPU oracle trees/LeafReference:
// a small forest in a strong, sheared wind over a ground with a solid block, so that leaves flutter, are
// shed, fly, land on the block and the ground, and leave through the outflow side.
#include <catch2/catch.hpp>

#include <algorithm>
#include <cmath>
#include <vector>

#include "fluid/PressureLevels.hpp"
#include "fluid/SolidMap.hpp"
#include "host/stages/LeafStages.hpp"
#include "tests/support/Fields.hpp"
#include "tests/support/SmallSpecies.hpp"
#include "tests/support/TestDevice.hpp"
#include "trees/Foliage.hpp"
#include "trees/LeafReference.hpp"

using namespace fw;
using B = fluid::BoundaryType;

namespace {

// 40 x 20 x 16 cells of 1 m, outflow east, periodic north-south, a ground.
fluid::GridSpec leaf_grid() {
  fluid::GridSpec spec;
  spec.nx = 40;
  spec.ny = 20;
  spec.nz = 16;
  spec.h = 1.0;
  spec.origin = {-2.0, 1.0, 0.0};
  spec.boundary = {B::inflow, B::outflow, B::periodic, B::periodic, B::no_slip, B::slip};
  return spec;
}

// A log-like shear: u = U (z / 10 m)^(1/7), a sideways and a sinking part, so leaves drift and come down.
fluid::MacVelocity shear_wind(const fluid::GridSpec& spec, double speed) {
  fluid::MacVelocity vel(spec);
  for (int c = 0; c < 3; ++c) {
    const int ex = spec.nx + (c == 0), ey = spec.ny + (c == 1), ez = spec.nz + (c == 2);
    for (int k = 0; k < ez; ++k)
      for (int j = 0; j < ey; ++j)
        for (int i = 0; i < ex; ++i) {
          const double z = spec.origin[2] + spec.h * (k + (c == 2 ? 0.0 : 0.5));
          const double profile = std::pow(std::max(z, 0.1) / 10.0, 1.0 / 7.0);
          const double value = c == 0 ? speed * profile : (c == 1 ? 0.1 * speed : -0.05 * speed);
          vel.component(c)[std::size_t(i + ex * (j + ey * k))] = float(value);
        }
  }
  return vel;
}

constexpr double kLeafAreaIndex = 3.0;

trees::SpeciesLeaves leaves_of(const trees::SpeciesBasis& species, trees::FlutterModel model,
                               std::uint64_t seed) {
  trees::LeafSettings settings;
  settings.model = model;
  settings.area = 0.01;             // big leaves: a few hundred per small tree
  settings.petiole_strength = 0.5;  // N: about half of them go in this wind
  settings.seed = seed;
  return trees::SpeciesLeaves::generate(species.skeleton(),
                                        trees::Foliage::of(species.skeleton(), kLeafAreaIndex), settings);
}

// Tolerances, float32 kernels against the double oracle:
// attached leaves: positions are rest geometry turned by theta, a few float ulps of ~20 m (measured 1.3e-6);
constexpr double kAttachedTolerance = 1e-4;  // m
// flying leaves after tens of steps of implicit drag: the float error of the wind and the drag relaxes
// instead of growing (the drag pulls every leaf towards the wind), so it stays at the level of a few steps'
// rounding (measured 1.1e-5 m after 4 s); leaves whose state differs (a load within rounding of its
// strength, a landing decided by a rounding of the height) are left out and counted instead, and so are
// leaves a sub-step apart (a sub-step count or a wall contact decided by a rounding: at most half a cell
// off). Measured: no leaf in another state; one leaf (stochastic model) a sub-step apart, 8.8e-4 m, stopped
// at a wall one sub-step earlier.
constexpr double kFlyingTolerance = 1e-4;  // m
constexpr double kMaxSubStep = 0.5;        // cells: FW_MAX_SUB_STEP_CELLS
constexpr double kDifferentStateShare = 0.01;

}  // namespace

TEST_CASE("leaves: the device step matches the CPU reference through shedding, flight and landing",
          "[leaves_device]") {
  auto* cc = test::device_or_skip();
  if (!cc) return;
  const fluid::GridSpec spec = leaf_grid();
  fluid::SolidMap solids(spec);
  solids.add(fluid::SolidBox{"wall", {16.0, 11.0, 2.5}, {4.0, 20.0, 5.0}});  // across the domain, 5 m high
  const auto& solid = solids.cells();

  const trees::SpeciesBasis species = test::small_species("broadleaf", 8.0, 3, 5, 6, 2, kLeafAreaIndex);
  std::vector<trees::TreeInstance> instances = {
      {0, {2.0, 6.0, 0.0}, 0.3, 1.0}, {0, {6.0, 14.0, 0.0}, 2.1, 1.3}, {0, {24.0, 10.0, 0.0}, -1.2, 0.8}};
  const trees::Forest forest({species}, instances);
  for (const auto model : {trees::FlutterModel::pseudo_branch, trees::FlutterModel::stochastic}) {
    INFO("flutter model " << trees::to_string(model));
    const std::vector<trees::SpeciesLeaves> leaves = {leaves_of(species, model, 11)};
    REQUIRE(leaves[0].count() > 100);

    trees::LeafReference ref(forest, leaves);
    host::LeafStages stages(*cc, spec, forest, leaves);
    REQUIRE(stages.own_count() == ref.count());

    const auto wind = shear_wind(spec, 18.0);
    host::DeviceVelocity dwind = test::upload_velocity(*cc, wind);
    const auto fine = fluid::build_fine_pressure_level(spec, solid);
    cl::Buffer mask = cc->upload(fine.mask, CL_MEM_READ_ONLY);

    const double dt = 0.05;
    const int steps = 80;  // 4 s: leaves shed at the first step have landed or left by then
    for (int n = 0; n < steps; ++n) {
      FwStep s{};
      s.dt = float(dt);
      s.time = float(n * dt);
      stages.enqueue_step(s, mask, dwind);
      ref.step(spec, solid, wind, n * dt, dt);
    }
    const host::LeafSnapshot snap = stages.download();
    const trees::LeafCounts device = stages.counts(), expected = ref.counts();
    INFO("shed " << device.shed << " / " << expected.shed << ", landed " << device.landed << " / "
                 << expected.landed << ", exited " << device.exited << " / " << expected.exited);
    CHECK(expected.shed > ref.count() / 10);  // the case exercises shedding ...
    CHECK(expected.landed > 0);               // ... landing ...
    CHECK(expected.exited > 0);               // ... and exits
    int different = 0, decided_apart = 0;
    double attached_error = 0.0, flying_error = 0.0;
    for (int j = 0; j < ref.count(); ++j) {
      const trees::WorldLeaf& leaf = ref.leaf(j);
      if (snap.state[std::size_t(j)] != std::uint8_t(leaf.state)) {
        ++different;
        continue;
      }
      if (leaf.state == trees::LeafState::exited) continue;
      double error = 0.0;
      for (int a = 0; a < 3; ++a)
        error = std::max(error, std::abs(snap.position[3 * std::size_t(j) + a] - leaf.position[a]));
      if (leaf.state == trees::LeafState::attached) {
        attached_error = std::max(attached_error, error);
      } else if (error > kFlyingTolerance) {
        // A sub-step count (or a wall contact) decided by a rounding: the leaf moves by at most a sub-step.
        ++decided_apart;
        CHECK(error <= kMaxSubStep * spec.h);
      } else {
        flying_error = std::max(flying_error, error);
      }
      // No leaf inside a solid cell, on either side.
      const int i = int(std::floor((leaf.position[0] - spec.origin[0]) / spec.h));
      const int jj = int(std::floor((leaf.position[1] - spec.origin[1]) / spec.h));
      const int k = int(std::floor((leaf.position[2] - spec.origin[2]) / spec.h + 1e-6));
      if (i >= 0 && i < spec.nx && jj >= 0 && jj < spec.ny && k >= 0 && k < spec.nz)
        CHECK(solid[std::size_t(i + spec.nx * (jj + spec.ny * k))] == 0);
    }
    INFO("attached error " << attached_error << " m, flying and landed " << flying_error << " m, "
                           << different << " leaves in another state, " << decided_apart
                           << " a sub-step apart");
    CHECK(attached_error < kAttachedTolerance);
    CHECK(flying_error < kFlyingTolerance);
    CHECK(different + decided_apart <= int(kDifferentStateShare * ref.count()) + 1);
    CHECK(std::abs(device.shed - expected.shed) <= long(kDifferentStateShare * ref.count()) + 1);
  }
}

TEST_CASE("leaves: a frame moves attached leaves with their element's displacement", "[leaves_device]") {
  auto* cc = test::device_or_skip();
  if (!cc) return;
  const fluid::GridSpec spec = leaf_grid();
  const trees::SpeciesBasis species = test::small_species("broadleaf", 8.0, 3, 5, 6, 2, kLeafAreaIndex);
  const trees::Forest forest({species}, {{0, {8.0, 10.0, 0.0}, 0.7, 1.1}});
  const std::vector<trees::SpeciesLeaves> leaves = {
      leaves_of(species, trees::FlutterModel::pseudo_branch, 5)};
  host::LeafStages stages(*cc, spec, forest, leaves);
  const host::LeafSnapshot rest = stages.download();
  // A rigid shift of every node: every attached leaf moves by it.
  const Eigen::Vector3d shift(0.3, -0.2, 0.05);
  std::vector<float> displacement(3 * std::size_t(forest.total_nodes()));
  for (std::size_t n = 0; n < displacement.size(); ++n) displacement[n] = float(shift[int(n % 3)]);
  cl::Buffer d = cc->upload(displacement, CL_MEM_READ_ONLY);
  stages.enqueue_frame(d);
  const host::LeafSnapshot moved = stages.download();
  REQUIRE(moved.position.size() == rest.position.size());
  double error = 0.0;
  for (std::size_t n = 0; n < rest.position.size(); ++n)
    error = std::max(error, std::abs(double(moved.position[n]) - rest.position[n] - shift[int(n % 3)]));
  CHECK(error < 1e-5);  // float sums of ~10 m and 0.3 m
  CHECK(moved.state == rest.state);
}

TEST_CASE("LeafStages: the device memory estimate bounds what the stage allocates by the sites alone",
          "[leaves_device]") {
  auto* cc = test::device_or_skip();
  if (!cc) return;
  const trees::SpeciesBasis species = test::small_species("broadleaf", 8.0, 3, 5, 6, 2, kLeafAreaIndex);
  const trees::Forest forest({species}, {{0, {2.0, 6.0, 0.0}, 0.3, 1.0}, {0, {24.0, 10.0, 0.0}, -1.2, 0.8}});
  const std::vector<trees::SpeciesLeaves> leaves = {leaves_of(species, trees::FlutterModel::stochastic, 11)};
  const std::size_t before = cc->allocated_bytes();
  host::LeafStages stages(*cc, leaf_grid(), forest, leaves);
  const std::size_t allocated = cc->allocated_bytes() - before;
  const std::size_t estimate = host::LeafStages::estimate_device_bytes(forest, leaves);
  // The estimate takes one site (its centre and its wind, 24 bytes) per leaf, the most there can be; the
  // stage allocates one per cell that holds a leaf. Everything else is counted exactly.
  const std::size_t leaf_total = std::size_t(stages.own_count());
  constexpr std::size_t kSiteBytes = 6 * sizeof(float);
  CHECK(allocated <= estimate);
  CHECK(allocated + leaf_total * kSiteBytes >= estimate);
}
