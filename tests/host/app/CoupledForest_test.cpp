// Trees driven by the device wind grid: the physics of the coupled step (WindGrid + ForestStages) against
// results computed on the host.
#include <catch2/catch.hpp>

#include <Eigen/Geometry>

#include <cmath>
#include <vector>

#include "host/app/CoupledStep.hpp"
#include "tests/support/TestDevice.hpp"
#include "trees/Forest.hpp"
#include "trees/SpeciesBasis.hpp"

using fw::trees::Skeleton;
using fw::trees::SkeletonNode;

namespace {

// An asymmetric small tree (no mirror plane), 3.5 m tall.
std::vector<SkeletonNode> asymmetric_nodes() {
  return {{-1, {0.0, 0.0, 0.0}, 0.10},  {0, {0.05, 0.0, 0.8}, 0.09}, {1, {0.1, 0.05, 1.6}, 0.08},
          {2, {0.12, 0.1, 2.4}, 0.06},  {3, {0.1, 0.12, 3.0}, 0.04}, {4, {0.08, 0.1, 3.5}, 0.03},
          {2, {0.7, 0.3, 2.0}, 0.04},   {6, {1.2, 0.6, 2.3}, 0.03},  {3, {-0.5, 0.4, 2.8}, 0.035},
          {8, {-0.9, 0.9, 3.0}, 0.025}, {1, {0.3, -0.6, 1.3}, 0.03}, {10, {0.5, -1.1, 1.5}, 0.02}};
}

fw::trees::SpeciesBasis species_from(std::vector<SkeletonNode> nodes) {
  fw::trees::SpeciesSettings settings;
  settings.modal.mode_count = 8;
  settings.wind.samples = 2;
  return fw::trees::SpeciesBasis::compute(Skeleton::from_nodes(std::move(nodes)), settings);
}

// A channel of 24 x 12 x 10 cells of 1 m with uniform flow along x: inflow on the upwind face, outflow on the
// other, slip elsewhere. Uniform flow stays uniform, so every tree sees exactly the ambient wind.
fw::host::WindGridSetup channel(double wind_x) {
  fw::host::WindGridSetup setup;
  setup.spec.nx = 24;
  setup.spec.ny = 12;
  setup.spec.nz = 10;
  setup.spec.h = 1.0;
  using fw::fluid::BoundaryType;
  const BoundaryType upwind = BoundaryType::inflow, downwind = BoundaryType::outflow;
  setup.spec.boundary = {wind_x > 0 ? upwind : downwind,
                         wind_x > 0 ? downwind : upwind,
                         BoundaryType::slip,
                         BoundaryType::slip,
                         BoundaryType::slip,
                         BoundaryType::slip};
  setup.settings.dt = 0.05;
  setup.ambient = {wind_x, 0.0, 0.0};
  return setup;
}

}  // namespace

TEST_CASE("CoupledForest: one tree in steady uniform wind settles at the static modal solution",
          "[simulation]") {
  auto* cc = fw::test::device_or_skip();
  if (!cc) return;
  const fw::trees::SpeciesBasis species = species_from(asymmetric_nodes());
  const double yaw = 0.7, scale = 1.2;
  const fw::trees::Forest forest({species}, {{0, {12.0, 6.0, 0.0}, yaw, scale}});
  fw::host::CoupledStep coupled(*cc, channel(8.0), forest, {});
  coupled.start({8.0, 0.0, 0.0});
  for (int step = 0; step < 600; ++step) coupled.step();  // 30 s: over 10 damping times of the slowest mode
  const fw::host::ModalState state = coupled.trees().download_modal_state();

  // On the host, from the species alone: f_i = |v| v . (s^1/2 R p_i^s) summed over the samples, for the
  // uniform wind v = (8, 0, 0); q_i = f_i / (omega_i / s)^2.
  const Eigen::Matrix3d rotation = Eigen::AngleAxisd(yaw, Eigen::Vector3d::UnitZ()).toRotationMatrix();
  const Eigen::Vector3d v(8.0, 0.0, 0.0);
  for (int i = 0; i < 8; ++i) {
    double f = 0.0;
    for (int s = 0; s < species.wind().sample_count(); ++s) {
      f += v.norm() * v.dot(std::sqrt(scale) * rotation * species.wind().projection(s, i));
    }
    const double omega = species.modes().omega()(i) / scale;
    const double expected = f / (omega * omega);
    INFO("mode " << i << ": device q " << state.q[std::size_t(i)] << ", host f/omega^2 " << expected);
    // Tolerance: 1e-3 of the largest static coordinate (float32 state, the grid's 1e-5 uniformity).
    CHECK(std::abs(state.q[std::size_t(i)] - expected) <
          1e-3 * std::abs(f / std::pow(species.modes().omega()(0) / scale, 2)) + 1e-9);
    CHECK(std::abs(state.qdot[std::size_t(i)]) < 1e-3 * std::abs(expected) * omega + 1e-7);
  }
}

TEST_CASE("CoupledForest: wind from the east gives the mirror image of the response to wind from the west",
          "[simulation]") {
  auto* cc = fw::test::device_or_skip();
  if (!cc) return;
  std::vector<SkeletonNode> mirrored = asymmetric_nodes();
  for (auto& node : mirrored) node.position.x() = -node.position.x();
  const fw::trees::Forest west_forest({species_from(asymmetric_nodes())}, {{0, {12.0, 6.0, 0.0}, 0.0, 1.0}});
  const fw::trees::Forest east_forest({species_from(mirrored)}, {{0, {12.0, 6.0, 0.0}, 0.0, 1.0}});

  auto run = [&](const fw::trees::Forest& forest, double wind_x) {
    fw::host::CoupledStep coupled(*cc, channel(wind_x), forest, {});
    coupled.start({wind_x, 0.0, 0.0});
    for (int step = 0; step < 40; ++step) coupled.step();  // 2 s: still swinging, not yet static
    coupled.trees().enqueue_deform();
    return coupled.trees().download_displacements();
  };
  const std::vector<float> west = run(west_forest, 8.0);   // wind from the west blows toward +x
  const std::vector<float> east = run(east_forest, -8.0);  // the mirrored tree, wind from the east
  REQUIRE(west.size() == east.size());
  float largest = 0.0f;
  for (float u : west) largest = std::max(largest, std::abs(u));
  REQUIRE(largest > 1e-4f);
  for (std::size_t node = 0; node < west.size() / 3; ++node) {
    INFO("node " << node);
    // Tolerance: 1e-3 of the largest displacement (two independent modal solves, float32 integration).
    CHECK(std::abs(east[3 * node] + west[3 * node]) < 1e-3f * largest);
    CHECK(std::abs(east[3 * node + 1] - west[3 * node + 1]) < 1e-3f * largest);
    CHECK(std::abs(east[3 * node + 2] - west[3 * node + 2]) < 1e-3f * largest);
  }
}
