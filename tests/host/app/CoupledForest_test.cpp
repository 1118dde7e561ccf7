// Trees driven by the device wind grid: the physics of the coupled step (WindGrid + ForestStages) against
// results computed on the host.
#include <catch2/catch.hpp>

#include <Eigen/Geometry>

#include <cmath>
#include <memory>
#include <vector>

#include "fluid/FlowStatistics.hpp"
#include "fluid/TurbulenceBox.hpp"
#include "host/app/CoupledStep.hpp"
#include "host/app/ProbeRecorder.hpp"
#include "tests/support/TestDevice.hpp"
#include "trees/Forest.hpp"
#include "trees/SpeciesBasis.hpp"
#include "trees/TreeGenerator.hpp"

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
  fw::host::CoupledStep coupled(*cc, channel(8.0), forest, {}, fw::host::TimeInputs::steady({8.0, 0.0, 0.0}));
  coupled.start();
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
    fw::host::CoupledStep coupled(*cc, channel(wind_x), forest, {},
                                  fw::host::TimeInputs::steady({wind_x, 0.0, 0.0}));
    coupled.start();
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

TEST_CASE("CoupledForest: a tree in turbulent wind sways at its first modal frequency", "[simulation]") {
  auto* cc = fw::test::device_or_skip();
  if (!cc) return;
  // An 8 m broadleaf (first mode 1.05 Hz along x) in a turbulent 8 m/s wind (intensity 20%, L_u = 6 m)
  // through a tunnel of 1 m cells. The tip responds to the broad turbulent load through its modal filter:
  // below f1 the turbulence spectrum falls as f^-5/3, at f1 the lightly damped first mode (zeta 0.05 by
  // default) amplifies it by 1 / (2 zeta)^2 = 100, so the tip spectrum must peak there.
  fw::host::WindGridSetup setup = channel(8.0);
  setup.spec.nx = 48;
  setup.spec.ny = 16;
  setup.spec.nz = 16;
  setup.spec.boundary[FW_FACE_SOUTH] = setup.spec.boundary[FW_FACE_NORTH] = fw::fluid::BoundaryType::periodic;
  fw::fluid::TurbulenceBoxSpec box;
  // Points every h/2, 16 m across (the tunnel's y period) and high, and 1024 m long: the frozen turbulence
  // repeats every 1024 m / 8 m/s = 128 s, so its spectrum is a line spectrum with lines 1/128 Hz apart,
  // far closer than the resonance's half-power width (2 zeta f1 = 0.1 Hz). A box of 128 m put lines
  // 1/16 Hz apart, and the tip spectrum peaked on the strongest line near f1, not at f1.
  box.cells = {2048, 32, 32};
  box.spacing = 0.5;
  box.spectrum = {1.0, 6.0};
  box.seed = 5;
  setup.turbulence = std::make_shared<const fw::fluid::TurbulenceBox>(box);
  // Clamped MacCormack keeps the resolved eddies of a few cells that semi-Lagrangian advection damps
  // within the six cells between the inflow and the tree (WindTurbulence_test prints both).
  setup.settings.advection = fw::fluid::AdvectionScheme::maccormack;
  fw::trees::GeneratorSettings tree;
  tree.preset = "broadleaf";
  tree.height = 8.0;
  fw::trees::SpeciesSettings settings;
  settings.modal.mode_count = 8;
  settings.wind.samples = 3;
  fw::trees::Forest forest({fw::trees::SpeciesBasis::compute(fw::trees::generate_tree(tree), settings)},
                           {{0, {6.0, 8.0, 0.0}, 0.0, 1.0}});
  const double f1 = forest.species()[0].modes().frequencies_hz()(0);
  fw::host::TimeInputs inputs = fw::host::TimeInputs::steady({8.0, 0.0, 0.0});
  inputs.turbulence_sigma = [](double) { return 0.2 * 8.0; };
  fw::host::CoupledStep coupled(*cc, setup, forest, {}, inputs);
  coupled.start();
  fw::host::ProbeRecorder tips(*cc, coupled, {}, forest.instance_count(), 1, true);
  // 2 s to set up, then one box period (128 s, 134 first-mode periods) for the spectrum's averages.
  while (coupled.time() < 2.0 - 1e-9) coupled.step();
  std::vector<double> along;
  while (coupled.time() < 130.0 - 1e-9) {
    coupled.step();
    along.push_back(tips.sample(coupled).tips[0][0]);
  }
  const double dt = setup.settings.dt;
  // Segments of 512 samples (25.6 s): df = 0.04 Hz, under the 10% window around f1, and 9 overlapping
  // segments to average: the peak of a single periodogram wanders within the resonance's half-power width
  // (2 zeta f1 = 0.1 Hz).
  const fw::fluid::Spectrum spectrum = fw::fluid::power_spectrum(along, dt, 512);
  const double peak =
      fw::fluid::peak_frequency(spectrum, spectrum.frequency.front(), spectrum.frequency.back());
  const double mean = fw::fluid::mean(along), sigma = fw::fluid::standard_deviation(along);
  INFO("f1 " << f1 << " Hz, tip spectrum peak " << peak << " Hz, mean bend " << mean << " m, sigma " << sigma
             << " m");
  CHECK(peak == Approx(f1).epsilon(0.10));  // the 10%
  CHECK(mean > 0.0);                        // bent downwind
  CHECK(sigma > 0.1 * mean);                // swaying about it, not a steady pose
}
