// The trees' kernels (host/ForestStages: kernels/tree_wind_load.cl, tree_modal_step.cl, tree_deform.cl)
// against the CPU oracle trees/ForestReference, on a smooth random MAC wind and a forest of two small
// species with various yaws and scales.
#include <catch2/catch.hpp>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <random>

#include "host/stages/ForestStages.hpp"
#include "tests/support/Fields.hpp"
#include "tests/support/SmallSpecies.hpp"
#include "tests/support/TestDevice.hpp"
#include "trees/ForestReference.hpp"
#include "trees/TreeGenerator.hpp"

using namespace fw;

namespace {

// Tolerances (float32 kernels against the double oracle):
// sampling: positions and 8-point interpolation in float, ~10 ulps of the wind speed;
constexpr double kSampleTolerance = 1e-5;
// forces: |v| v (two more roundings) and dot products of 3S terms;
constexpr double kForceTolerance = 1e-4;
// 50 steps of forces and state in float: errors of the forces carry into q linearly;
constexpr double kStateTolerance = 2e-4;
// deformation from the same q: a dot product of m terms and a rotation.
constexpr double kDeformTolerance = 1e-5;
// the strong-wind correction from the same q: float atan (a few ulps) and q~^2 w in the same sum, then the
// length-restoring walk, whose float rounding adds up along each root-to-tip path (a few dozen elements
// here) and which turns Diener's float error normal to each element into motion of the subtree; measured
// 1.8e-7 on PoCL (2.3e-7 when the walk read Diener's displacements back instead of summing each element's
// image), the linear path's margin kept.
constexpr double kStrongDeformTolerance = 1e-5;
// Element lengths of the device's corrected frames against their rest lengths: float rounding of the
// displacements (~1e-7 of the largest, a few m) over the shortest element; measured 1.9-2.1e-7 on PoCL.
constexpr double kDeviceLengthTolerance = 1e-5;

// 32 x 24 x 14 cells of 1 m; the origin off zero so that the kernels must use it.
fluid::GridSpec forest_grid() {
  fluid::GridSpec spec;
  spec.nx = 32;
  spec.ny = 24;
  spec.nz = 14;
  spec.h = 1.0;
  spec.origin = {-4.0, 3.0, -1.0};
  return spec;
}

// A smooth random wind: a mean flow plus three random Fourier modes per component, up to ~9 m/s.
fluid::MacVelocity smooth_wind(const fluid::GridSpec& spec, std::uint32_t seed) {
  std::mt19937 rng(seed);
  std::uniform_real_distribution<double> unit(-1.0, 1.0);
  struct Wave {
    double amplitude, phase, k[3];
  };
  Wave waves[3][3];
  for (auto& component : waves)
    for (auto& w : component)
      w = {2.0 * unit(rng), M_PI * unit(rng), {0.4 * unit(rng), 0.4 * unit(rng), 0.4 * unit(rng)}};
  const double mean[3] = {6.0, -2.0, 0.3};
  fluid::MacVelocity vel(spec);
  for (int c = 0; c < 3; ++c) {
    const int ex = spec.nx + (c == 0), ey = spec.ny + (c == 1), ez = spec.nz + (c == 2);
    for (int k = 0; k < ez; ++k)
      for (int j = 0; j < ey; ++j)
        for (int i = 0; i < ex; ++i) {
          const double x[3] = {spec.origin[0] + spec.h * (i + (c == 0 ? 0.0 : 0.5)),
                               spec.origin[1] + spec.h * (j + (c == 1 ? 0.0 : 0.5)),
                               spec.origin[2] + spec.h * (k + (c == 2 ? 0.0 : 0.5))};
          double value = mean[c];
          for (const Wave& w : waves[c])
            value += w.amplitude * std::sin(w.k[0] * x[0] + w.k[1] * x[1] + w.k[2] * x[2] + w.phase);
          vel.component(c)[std::size_t(i + ex * (j + ey * k))] = float(value);
        }
  }
  return vel;
}

// 20 instances of two species, yaws all round, scales 0.6 .. 1.5, roots inside the grid; the last one stands
// high enough that its crown leaves the domain (clamped sampling).
trees::Forest test_forest() {
  std::vector<trees::SpeciesBasis> species = {test::small_species("broadleaf", 6.0, 1, 5, 8, 3),
                                              test::small_species("conifer", 5.0, 2, 4, 10, 2)};
  std::mt19937 rng(5);
  std::uniform_real_distribution<double> x(-1.0, 26.0), y(5.0, 25.0), yaw(-M_PI, M_PI), scale(0.6, 1.5);
  std::vector<trees::TreeInstance> trees;
  for (int k = 0; k < 19; ++k) trees.push_back({k % 2, {x(rng), y(rng), 0.0}, yaw(rng), scale(rng)});
  trees.push_back({0, {10.0, 14.0, 9.0}, 1.0, 1.2});
  return trees::Forest(std::move(species), std::move(trees));
}

double relative(const std::vector<float>& device, const Eigen::MatrixXd& expected) {
  REQUIRE(device.size() == std::size_t(expected.size()));
  // Row-major flattening of expected (rows are samples or nodes, 3 columns; or a vector).
  double diff = 0.0, scale = 0.0;
  std::size_t n = 0;
  for (int r = 0; r < expected.rows(); ++r)
    for (int c = 0; c < expected.cols(); ++c, ++n) {
      diff = std::max(diff, std::abs(double(device[n]) - expected(r, c)));
      scale = std::max(scale, std::abs(expected(r, c)));
    }
  return diff / scale;
}

Eigen::VectorXd to_eigen(const std::vector<float>& v) {
  Eigen::VectorXd out(Eigen::Index(v.size()));
  for (std::size_t i = 0; i < v.size(); ++i) out(Eigen::Index(i)) = v[i];
  return out;
}

struct ForestFixture {
  host::ComputeContext& cc;
  fluid::GridSpec spec = forest_grid();
  trees::Forest forest = test_forest();
  trees::ForestReference ref{forest};
  fluid::MacVelocity wind = smooth_wind(spec, 17);
  host::ForestStages stages{cc, spec, forest};
  host::DeviceVelocity dwind;

  explicit ForestFixture(host::ComputeContext& c) : cc(c) { dwind = test::upload_velocity(cc, wind); }
};

}  // namespace

TEST_CASE("tree_wind_load: sampled wind and modal forces match the reference", "[forest]") {
  auto* cc = test::device_or_skip();
  if (!cc) return;
  ForestFixture f(*cc);
  REQUIRE(f.stages.instance_count() == 20);
  REQUIRE(f.stages.total_modes() == f.ref.total_modes());
  INFO("species nodes: " << f.forest.species()[0].skeleton().size() << ", "
                         << f.forest.species()[1].skeleton().size());
  CHECK(f.forest.species()[0].skeleton().size() >= 30);
  CHECK(f.forest.species()[1].skeleton().size() >= 30);
  f.stages.enqueue_wind_load(f.dwind);
  const double sample_error = relative(f.stages.download_sampled_wind(), f.ref.sample_wind(f.spec, f.wind));
  const double force_error = relative(f.stages.download_modal_forces(), f.ref.modal_forces(f.spec, f.wind));
  WARN("wind load: max relative error, sampled wind " << sample_error << ", modal forces " << force_error);
  CHECK(sample_error < kSampleTolerance);
  CHECK(force_error < kForceTolerance);
}

TEST_CASE("tree_wind_load: with a drag law the modal forces match the reference and scale by its factor",
          "[forest]") {
  auto* cc = test::device_or_skip();
  if (!cc) return;
  ForestFixture f(*cc);
  const fluid::DragLaw law{-0.8, 3.0};
  f.stages.set_drag_law(law);
  f.stages.enqueue_wind_load(f.dwind);
  const auto forces = f.stages.download_modal_forces();
  CHECK(relative(forces, f.ref.modal_forces(f.spec, f.wind, law)) < kForceTolerance);
  // The law does change them: the fixture's wind is not at the reference speed everywhere.
  CHECK(relative(forces, f.ref.modal_forces(f.spec, f.wind)) > 0.05);
}

TEST_CASE("tree_modal_step: 50 steps of both integrators match the reference", "[forest]") {
  auto* cc = test::device_or_skip();
  if (!cc) return;
  ForestFixture f(*cc);
  const double omega_max = f.ref.omega().maxCoeff();
  // exact: a step coarser than the highest modes' periods (it is stable at any dt); semi-implicit: within
  // its stability limit omega dt < 2.
  for (auto [integrator, dt, name] :
       {std::tuple{trees::ModalIntegrator::exact, 0.02, "exact"},
        std::tuple{trees::ModalIntegrator::semi_implicit, 0.5 / omega_max, "semi-implicit"}}) {
    f.stages.set_integrator(integrator);
    // Start from a random state, so that free oscillation and the forced response both show.
    std::mt19937 rng(3);
    std::uniform_real_distribution<float> unit(-1.0f, 1.0f);
    const Eigen::VectorXd q_static = f.ref.static_modal_response(f.spec, f.wind);
    const double amplitude = q_static.cwiseAbs().maxCoeff();
    host::ModalState start;
    for (int j = 0; j < f.stages.total_modes(); ++j) {
      start.q.push_back(float(amplitude) * unit(rng));
      start.qdot.push_back(float(amplitude * omega_max * 0.1) * unit(rng));
    }
    f.stages.upload_modal_state(start);
    Eigen::VectorXd q = to_eigen(start.q), qdot = to_eigen(start.qdot);
    for (int n = 0; n < 50; ++n) {
      f.stages.enqueue_wind_load(f.dwind);
      f.stages.enqueue_modal_step(float(dt));
      f.ref.step(q, qdot, f.ref.modal_forces(f.spec, f.wind), double(float(dt)), integrator);
    }
    const host::ModalState state = f.stages.download_modal_state();
    const double q_error = relative(state.q, q), qdot_error = relative(state.qdot, qdot);
    WARN(name << ", 50 steps of " << dt << " s: max relative error q " << q_error << ", qdot " << qdot_error);
    CHECK(q_error < kStateTolerance);
    CHECK(qdot_error < kStateTolerance);

    // The deformation, from the device's own q (the kernel alone) and against the oracle's whole chain.
    f.stages.enqueue_deform();
    const std::vector<float> u = f.stages.download_displacements();
    const double deform_error = relative(u, f.ref.displacements(to_eigen(state.q)));
    const double chain_error = relative(u, f.ref.displacements(q));
    WARN(name << ": displacements, max relative error " << deform_error << " (kernel), " << chain_error
              << " (whole chain)");
    CHECK(deform_error < kDeformTolerance);
    CHECK(chain_error < kStateTolerance);
  }
}

// A storm's modal state: every instance-mode at up to its fitted range q_max
// (trees/StrongWindCorrection.hpp), s^5/2 q_max in the instance's own coordinate, so that the arctan and the
// q~^2 w terms matter.
host::ModalState storm_state(const trees::Forest& forest, std::uint32_t seed) {
  std::mt19937 rng(seed);
  std::uniform_real_distribution<double> unit(-1.0, 1.0);
  host::ModalState state;
  for (int k = 0; k < forest.instance_count(); ++k) {
    const double grown = std::pow(forest.instances()[std::size_t(k)].scale, 2.5);
    for (const trees::StrongWindModeFit& fit : forest.species_of(k).strong_wind().fits()) {
      state.q.push_back(float(grown * fit.q_max * unit(rng)));
      state.qdot.push_back(0.0f);
    }
  }
  return state;
}

// Max over instances of (max |device - expected| over the instance's nodes) / (max |expected| there): each
// instance on its own, so that the small trees' errors do not hide behind the large ones' motion.
double worst_instance_error(const trees::Forest& forest, const std::vector<float>& device,
                            const Eigen::MatrixX3d& expected) {
  REQUIRE(device.size() == std::size_t(3 * expected.rows()));
  double worst = 0.0;
  for (int k = 0; k < forest.instance_count(); ++k) {
    double diff = 0.0, scale = 0.0;
    for (int n = forest.node_offset(k); n < forest.node_offset(k + 1); ++n)
      for (int a = 0; a < 3; ++a) {
        diff = std::max(diff, std::abs(double(device[std::size_t(3 * n + a)]) - expected(n, a)));
        scale = std::max(scale, std::abs(expected(n, a)));
      }
    worst = std::max(worst, diff / scale);
  }
  return worst;
}

// Max over every instance's elements of | |deformed| / |rest| - 1 |, the rest element s R (p_c - p_p) in
// double, the deformed one that plus the device's u_c - u_p: what the length-restoring pass makes exact.
double max_length_error(const trees::Forest& forest, const std::vector<float>& device) {
  REQUIRE(device.size() == std::size_t(3 * forest.total_nodes()));
  double worst = 0.0;
  for (int k = 0; k < forest.instance_count(); ++k) {
    const trees::Skeleton& skeleton = forest.species_of(k).skeleton();
    const Eigen::Matrix3d grow = forest.instances()[std::size_t(k)].scale * forest.rotation(k);
    auto u = [&](int node) {
      const std::size_t at = 3 * std::size_t(forest.node_offset(k) + node);
      return Eigen::Vector3d(device[at], device[at + 1], device[at + 2]);
    };
    for (const auto& [parent, child] : skeleton.elements()) {
      const Eigen::Vector3d rest = grow * (skeleton.node(child).position - skeleton.node(parent).position);
      worst = std::max(worst, std::abs((rest + u(child) - u(parent)).norm() / rest.norm() - 1.0));
    }
  }
  return worst;
}

double max_length_error(const trees::Forest& forest, const Eigen::MatrixX3d& u) {
  std::vector<float> flat;
  for (int n = 0; n < u.rows(); ++n)
    for (int a = 0; a < 3; ++a) flat.push_back(float(u(n, a)));
  return max_length_error(forest, flat);
}

TEST_CASE("tree_deform_strong: the strong-wind correction matches the reference at every scale and yaw",
          "[forest]") {
  auto* cc = test::device_or_skip();
  if (!cc) return;
  ForestFixture f(*cc);
  CHECK(f.stages.strong_wind_correction());  // on by default
  const host::ModalState state = storm_state(f.forest, 23);
  f.stages.upload_modal_state(state);
  f.stages.enqueue_deform();
  const std::vector<float> u = f.stages.download_displacements();
  const Eigen::VectorXd q = to_eigen(state.q);
  const Eigen::MatrixX3d expected = f.ref.displacements(q, true);
  const double error = worst_instance_error(f.forest, u, expected);
  const double correction =
      (f.ref.displacements(q, false) - expected).cwiseAbs().maxCoeff() / expected.cwiseAbs().maxCoeff();
  const double lengths = max_length_error(f.forest, u);
  WARN("strong-wind deformation of 20 instances (scales 0.6-1.5, all yaws): max relative error per instance "
       << error << "; the correction moves nodes by " << correction << " of the largest motion; element "
       << "lengths off by " << lengths
       << " (linear: " << max_length_error(f.forest, f.ref.displacements(q, false)) << ")");
  CHECK(correction > 0.05);  // the amplitudes are large enough for the correction to matter
  CHECK(error < kStrongDeformTolerance);
  CHECK(lengths < kDeviceLengthTolerance);

  // At rest every node stays exactly where it is: Diener's part is 0, and the pass's change has no term
  // without delta (its lengths are those of the rounded rest elements themselves).
  f.stages.reset_state();
  f.stages.enqueue_deform();
  const std::vector<float> rest = f.stages.download_displacements();
  CHECK(std::all_of(rest.begin(), rest.end(), [](float x) { return x == 0.0f; }));
}

// tree_deform_strong deforms a few consecutive instances of one species together (kernels/tree_deform.cl,
// FW_STRONG_TREES), and others one by one: a tree's frame must not depend on which trees stand beside it
// (over MPI ranks a rank holds only some of them). Groups of one species, of the other, mixed, and a short
// tail.
TEST_CASE("tree_deform_strong: a tree's frame is the same to the bit alone and among its neighbours",
          "[forest]") {
  auto* cc = test::device_or_skip();
  if (!cc) return;
  const std::vector<int> kinds = {0, 0, 0, 0, 1, 1, 1, 1, 0, 1, 0, 0, 1, 0, 0};
  std::mt19937 rng(41);
  std::uniform_real_distribution<double> x(1.0, 25.0), y(5.0, 25.0), yaw(-M_PI, M_PI), scale(0.6, 1.5);
  std::vector<trees::TreeInstance> placed;
  for (int kind : kinds) placed.push_back({kind, {x(rng), y(rng), 0.0}, yaw(rng), scale(rng)});
  const trees::Forest forest(test_forest().species(), std::move(placed));
  const fluid::GridSpec spec = forest_grid();
  host::ForestStages stages(*cc, spec, forest);
  const host::ModalState state = storm_state(forest, 37);
  stages.upload_modal_state(state);
  stages.enqueue_deform();
  const std::vector<float> together = stages.download_displacements();
  const trees::ForestReference ref(forest);
  CHECK(worst_instance_error(forest, together, ref.displacements(to_eigen(state.q), true)) <
        kStrongDeformTolerance);

  for (int k : {0, 5, 9, 14}) {  // in a group of species 0, of species 1, a mixed group, the tail
    INFO("instance " << k);
    const trees::Forest alone = forest.subset({k});
    host::ForestStages single(*cc, spec, alone);
    host::ModalState own;
    const auto modes = state.q.begin() + forest.mode_offset(k);
    own.q.assign(modes, modes + alone.total_modes());
    own.qdot.assign(own.q.size(), 0.0f);
    single.upload_modal_state(own);
    single.enqueue_deform();
    const std::vector<float> u = single.download_displacements();
    const auto from = together.begin() + 3 * std::ptrdiff_t(forest.node_offset(k));
    CHECK(std::equal(u.begin(), u.end(), from, from + std::ptrdiff_t(u.size())));
  }
}

TEST_CASE("tree_deform: with the strong-wind correction off, frames are the linear modal sum", "[forest]") {
  auto* cc = test::device_or_skip();
  if (!cc) return;
  ForestFixture f(*cc);
  const host::ModalState state = storm_state(f.forest, 29);
  f.stages.upload_modal_state(state);
  f.stages.set_strong_wind_correction(false);
  CHECK_FALSE(f.stages.strong_wind_correction());
  f.stages.enqueue_deform();
  const std::vector<float> off = f.stages.download_displacements();
  CHECK(worst_instance_error(f.forest, off, f.ref.displacements(to_eigen(state.q), false)) <
        kDeformTolerance);
  // On and off again: the flag picks the kernel and leaves nothing behind, bit for bit.
  f.stages.set_strong_wind_correction(true);
  f.stages.enqueue_deform();
  const std::vector<float> on = f.stages.download_displacements();
  CHECK(on != off);
  f.stages.set_strong_wind_correction(false);
  f.stages.enqueue_deform();
  CHECK(f.stages.download_displacements() == off);
}

TEST_CASE("tree_modal_step: a long exact run settles at the static response", "[forest]") {
  auto* cc = test::device_or_skip();
  if (!cc) return;
  ForestFixture f(*cc);
  f.stages.reset_state();
  f.stages.enqueue_wind_load(f.dwind);
  // zeta = 0.03: 1,000 steps of 0.5 s damp the slowest mode's transient below float rounding.
  for (int n = 0; n < 1000; ++n) f.stages.enqueue_modal_step(0.5f);
  const auto state = f.stages.download_modal_state();
  CHECK(relative(state.q, f.ref.static_modal_response(f.spec, f.wind)) < kForceTolerance);
}

TEST_CASE("ForestStages: reset, bad dt and bad state sizes", "[forest]") {
  auto* cc = test::device_or_skip();
  if (!cc) return;
  ForestFixture f(*cc);
  f.stages.enqueue_wind_load(f.dwind);
  f.stages.enqueue_modal_step(0.01f);
  f.stages.reset_state();
  const auto state = f.stages.download_modal_state();
  for (int j = 0; j < f.stages.total_modes(); ++j) {
    CHECK(state.q[std::size_t(j)] == 0.0f);
    CHECK(state.qdot[std::size_t(j)] == 0.0f);
  }
  CHECK_THROWS_WITH(f.stages.enqueue_modal_step(-1.0f), "ForestStages: dt must be finite and >= 0, got -1");
  CHECK_THROWS_AS(f.stages.enqueue_modal_step(std::nanf("")), std::invalid_argument);
  CHECK_THROWS_AS(f.stages.upload_modal_state(host::ModalState{{1.0f}, {1.0f}}), std::invalid_argument);
}

// Timing, not a check: `kernel_tests "[forest-bench]"`. 1,000 instances x 25 modes x 3 samples.
TEST_CASE("ForestStages: wind load + modal step timing", "[.][forest-bench]") {
  auto* cc = test::device_or_skip();
  if (!cc) return;
  fluid::GridSpec spec;
  spec.nx = 128;
  spec.ny = 128;
  spec.nz = 32;
  spec.h = 2.0;
  std::vector<trees::SpeciesBasis> species = {test::small_species("broadleaf", 12.0, 4, 5, 25, 3)};
  std::mt19937 rng(9);
  std::uniform_real_distribution<double> pos(10.0, 246.0), yaw(-M_PI, M_PI), scale(0.8, 1.2);
  std::vector<trees::TreeInstance> trees;
  for (int k = 0; k < 1000; ++k) trees.push_back({0, {pos(rng), pos(rng), 0.0}, yaw(rng), scale(rng)});
  const trees::Forest forest(std::move(species), std::move(trees));
  host::ForestStages stages(*cc, spec, forest);
  const auto wind = smooth_wind(spec, 2);
  host::DeviceVelocity dwind = test::upload_velocity(*cc, wind);
  auto run = [&](int steps) {
    const auto start = std::chrono::steady_clock::now();
    for (int n = 0; n < steps; ++n) {
      stages.enqueue_wind_load(dwind);
      stages.enqueue_modal_step(0.01f);
    }
    cc->finish();
    return std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - start).count() /
           steps;
  };
  auto time_each = [&](auto&& enqueue, int steps) {
    const auto start = std::chrono::steady_clock::now();
    for (int n = 0; n < steps; ++n) enqueue();
    cc->finish();
    return std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - start).count() /
           steps;
  };
  run(10);  // warm-up (kernel compilation for the work sizes)
  const double ms = run(200);
  const double load_ms = time_each([&] { stages.enqueue_wind_load(dwind); }, 200);
  const double step_ms = time_each([&] { stages.enqueue_modal_step(0.01f); }, 200);
  stages.set_integrator(trees::ModalIntegrator::semi_implicit);
  const double semi_ms = time_each([&] { stages.enqueue_modal_step(0.001f); }, 200);
  const auto t0 = std::chrono::steady_clock::now();
  for (int n = 0; n < 50; ++n) stages.enqueue_deform();
  cc->finish();
  const double deform_ms =
      std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - t0).count() / 50;
  WARN("1000 instances x 25 modes x 3 samples, "
       << forest.species()[0].skeleton().size() << " nodes: wind load + modal step " << ms << " ms ("
       << load_ms << " + " << step_ms << "), semi-implicit step " << semi_ms << " ms, deform " << deform_ms
       << " ms");
}

// Timing, not a check: `kernel_tests "[forest-bench]"`. The deformation of an output frame for 700 instances
// of the default broadleaf (905 nodes, 20 modes) at storm amplitudes: linear, and with the whole strong-wind
// correction (Diener's part and the length-restoring pass, one kernel).
TEST_CASE("ForestStages: deformation timing, linear and strong-wind corrected", "[.][forest-bench]") {
  auto* cc = test::device_or_skip();
  if (!cc) return;
  constexpr int kInstances = 700, kModes = 20, kFrames = 20;
  trees::GeneratorSettings g;
  g.preset = "broadleaf";
  trees::SpeciesSettings settings;
  settings.modal.mode_count = kModes;
  settings.wind.samples = 3;
  std::vector<trees::SpeciesBasis> species = {
      trees::SpeciesBasis::compute(trees::generate_tree(g), settings)};
  std::mt19937 rng(11);
  std::uniform_real_distribution<double> pos(10.0, 246.0), yaw(-M_PI, M_PI), scale(0.8, 1.2);
  std::vector<trees::TreeInstance> trees;
  for (int k = 0; k < kInstances; ++k) trees.push_back({0, {pos(rng), pos(rng), 0.0}, yaw(rng), scale(rng)});
  const trees::Forest forest(std::move(species), std::move(trees));
  fluid::GridSpec spec;
  spec.nx = spec.ny = 128;
  spec.nz = 16;
  spec.h = 2.0;
  host::ForestStages stages(*cc, spec, forest);
  stages.upload_modal_state(storm_state(forest, 31));

  auto time_each = [&](auto&& enqueue) {
    enqueue();  // warm-up (kernel compilation for the work sizes)
    cc->finish();
    const auto start = std::chrono::steady_clock::now();
    for (int n = 0; n < kFrames; ++n) enqueue();
    cc->finish();
    return std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - start).count() /
           kFrames;
  };
  stages.set_strong_wind_correction(false);
  const double linear_ms = time_each([&] { stages.enqueue_deform(); });
  stages.set_strong_wind_correction(true);
  const double corrected_ms = time_each([&] { stages.enqueue_deform(); });
  WARN(kInstances << " broadleaf instances x " << forest.species()[0].skeleton().size() << " nodes x "
                  << kModes << " modes (" << forest.total_nodes() << " nodes) on '"
                  << cc->device().device_name << "': deform linear " << linear_ms
                  << " ms, strong-wind corrected " << corrected_ms << " ms");
}

TEST_CASE("ForestStages: the device memory estimate is what the stage allocates", "[forest]") {
  auto* cc = test::device_or_skip();
  if (!cc) return;
  const trees::Forest forest = test_forest();
  // Exact: the planner reports this number (host/app/plan/ForestPlan.cpp), and the estimate counts the same
  // packed tables and state buffers the constructor uploads.
  const std::size_t before = cc->allocated_bytes();
  host::ForestStages stages(*cc, forest_grid(), forest);
  CHECK(cc->allocated_bytes() - before == host::ForestStages::estimate_device_bytes(forest));

  trees::UnresolvedTurbulenceSettings settings;
  settings.series_length = 1 << 10;
  const std::size_t before_series = cc->allocated_bytes();
  stages.set_unresolved_turbulence(trees::UnresolvedTurbulence(settings), 0.1);
  CHECK(cc->allocated_bytes() - before_series ==
        host::ForestStages::estimate_unresolved_bytes(settings, forest));
}
