// The element tree models' kernels (host/stages/BranchStages, kernels/tree_branches.cl) against their CPU
// oracles (trees/RigidBranches, trees/SpringBranches, trees/BranchPose), on a smooth random MAC wind and a
// forest of three species: one moved by rigid bodies, one by springs, one modal, at various yaws and scales.
#include <catch2/catch.hpp>

#include <algorithm>
#include <cmath>
#include <cstring>
#include <random>

#include "host/stages/ForestStages.hpp"
#include "host/stages/SavedStateNames.hpp"
#include "tests/support/BranchModels.hpp"
#include "tests/support/Fields.hpp"
#include "tests/support/SmallSpecies.hpp"
#include "tests/support/TestDevice.hpp"
#include "trees/BranchPose.hpp"
#include "trees/ForestReference.hpp"
#include "trees/RigidBranches.hpp"
#include "trees/SpringBranches.hpp"

using namespace fw;

namespace {

// Tolerances (float32 kernels against the double oracles), relative to the largest value; the float
// rounding of the sampled wind (~1e-7) carries into every result, and each is measured near 1e-7 on PoCL:
// equilibrium angles, a 3 x 3 solve per joint of moments summed up the tree (a few dozen float terms);
constexpr double kEquilibriumTolerance = 1e-5;
// 40 implicit steps of the articulated-body recursion, whose rounding carries from step to step (3e-7);
constexpr double kStepTolerance = 1e-5;
// spring angles: float atan and sin of the same loads (1.3e-7);
constexpr double kSpringTolerance = 1e-5;
// the pose from the device's own angles: quaternion products along root-to-tip paths of a few dozen
// elements (2e-7).
constexpr double kPoseTolerance = 1e-5;

fluid::GridSpec forest_grid() {
  fluid::GridSpec spec;
  spec.nx = 28;
  spec.ny = 24;
  spec.nz = 12;
  spec.h = 1.0;
  spec.origin = {-2.0, 2.0, -1.0};
  return spec;
}

trees::Forest test_forest() {
  std::vector<trees::SpeciesBasis> species = {test::small_species("broadleaf", 6.0, 1, 5, 8, 3, 2.0),
                                              test::small_species("conifer", 5.0, 2, 4, 10, 2, 1.0),
                                              test::small_species("broadleaf", 5.0, 3, 4, 6, 2)};
  std::mt19937 rng(7);
  std::uniform_real_distribution<double> x(1.0, 22.0), y(5.0, 22.0), yaw(-M_PI, M_PI), scale(0.6, 1.5);
  std::vector<trees::TreeInstance> trees;
  for (int k = 0; k < 9; ++k) trees.push_back({k % 3, {x(rng), y(rng), 0.0}, yaw(rng), scale(rng)});
  return trees::Forest(std::move(species), std::move(trees));
}

// The CPU side of one element tree: its table and the loads of the wind at its element centres.
struct ElementTree {
  trees::BranchElements elements;
  std::vector<Eigen::Vector3d> loads;
};

ElementTree element_tree(const trees::Forest& forest, int k, const fluid::GridSpec& spec,
                         const fluid::MacVelocity& wind) {
  const trees::SpeciesBasis& basis = forest.species_of(k);
  ElementTree tree{
      trees::BranchElements::of(basis.skeleton(), basis.settings().material, basis.settings().wind), {}};
  const trees::TreeInstance& instance = forest.instances()[std::size_t(k)];
  const Eigen::Matrix3d R = forest.rotation(k);
  const double s = instance.scale;
  tree.loads.assign(std::size_t(tree.elements.size()), Eigen::Vector3d::Zero());
  for (int j = 1; j < tree.elements.size(); ++j) {
    const Eigen::Vector3d world = instance.position + s * R * tree.elements[j].centre;
    const Eigen::Vector3d v = R.transpose() * trees::sample_mac_velocity(spec, wind, world);
    tree.loads[std::size_t(j)] = s * s * tree.elements.load(j, v);
  }
  return tree;
}

// The largest |device - expected| over the largest |expected| of instance k's angles.
double angle_error(const std::vector<float>& joints, int offset, const std::vector<Eigen::Vector3d>& expected,
                   double& largest) {
  double diff = 0.0;
  for (std::size_t j = 0; j < expected.size(); ++j)
    for (int c = 0; c < 3; ++c) {
      diff = std::max(diff,
                      std::abs(double(joints[FW_JOINT_FLOATS * (std::size_t(offset) + j) + std::size_t(c)]) -
                               expected[j](c)));
      largest = std::max(largest, std::abs(expected[j](c)));
    }
  return diff;
}

// The largest |device - reference| over the largest |reference| of instance k's pose, from the device's own
// angles `joints` and its displacements `u` (world frame).
double pose_error(const trees::Forest& forest, const trees::BranchElements& elements,
                  const std::vector<float>& joints, int offset, const std::vector<float>& u, int k) {
  const int first_node = forest.node_offset(k), nodes = elements.size();
  std::vector<Eigen::Vector3d> angles(static_cast<std::size_t>(nodes));
  for (int j = 0; j < nodes; ++j)
    for (int c = 0; c < 3; ++c)
      angles[std::size_t(j)](c) = joints[FW_JOINT_FLOATS * std::size_t(offset + j) + std::size_t(c)];
  const double scale = forest.instances()[std::size_t(k)].scale;
  const Eigen::MatrixX3d expected =
      (trees::branch_displacements(elements, scale, angles) * forest.rotation(k).transpose()).eval();
  double diff = 0.0, largest = 0.0;
  for (int n = 0; n < nodes; ++n)
    for (int c = 0; c < 3; ++c) {
      diff = std::max(diff,
                      std::abs(double(u[3 * std::size_t(first_node + n) + std::size_t(c)]) - expected(n, c)));
      largest = std::max(largest, std::abs(expected(n, c)));
    }
  return diff / largest;
}

struct BranchFixture {
  host::ComputeContext& cc;
  fluid::GridSpec spec = forest_grid();
  trees::Forest forest = test_forest();
  std::vector<trees::SpeciesDynamics> dynamics = test::three_model_dynamics();
  // A mean flow of ~7 m/s with a long-wave ripple: every element feels its own wind.
  fluid::MacVelocity wind = test::smooth_velocity(spec, {6.0, -3.0, 0.5}, {2.0, 1.5, 1.0});
  host::ForestStages stages{cc, spec, forest, nullptr, dynamics};
  host::DeviceVelocity dwind;

  explicit BranchFixture(host::ComputeContext& c) : cc(c) { dwind = test::upload_velocity(cc, wind); }
  int species(int k) const { return forest.instances()[std::size_t(k)].species; }
  double scale(int k) const { return forest.instances()[std::size_t(k)].scale; }
  double damping(int k) const {
    return trees::rigid_damping(dynamics[test::kRigid].rigid_bodies.damping_ratio,
                                forest.species_of(k).modes().omega()(0) / scale(k));
  }
};

}  // namespace

TEST_CASE("tree_branches: the rigid trees' equilibrium and 40 implicit steps from rest match the reference",
          "[forest][branches]") {
  auto* cc = test::device_or_skip();
  if (!cc) return;
  BranchFixture f(*cc);
  REQUIRE(f.stages.branches() != nullptr);
  host::BranchStages& branches = *f.stages.branches();
  REQUIRE(branches.tree_count() == 6);
  f.stages.enqueue_wind_load(f.dwind);
  f.stages.enqueue_equilibrium();
  const std::vector<float> equilibrium = branches.download_joints();

  // From rest in the wind: each tree swings towards its equilibrium and past it.
  f.stages.reset_state();
  constexpr double dt = 0.01;
  constexpr int kSteps = 40;
  for (int n = 0; n < kSteps; ++n) {
    f.stages.enqueue_wind_load(f.dwind);
    f.stages.enqueue_modal_step(float(dt));
  }
  const std::vector<float> stepped = branches.download_joints();
  int rigid_trees = 0;
  for (int k = 0; k < f.forest.instance_count(); ++k) {
    if (f.species(k) != test::kRigid) continue;
    ++rigid_trees;
    const ElementTree tree = element_tree(f.forest, k, f.spec, f.wind);
    const trees::RigidBranches rigid(tree.elements, f.scale(k), f.damping(k));
    const trees::RigidBranchState at_rest = rigid.equilibrium(tree.loads);
    double largest = 0.0;
    const double equilibrium_error =
        angle_error(equilibrium, branches.entry_offset(k), at_rest.angle, largest) / largest;
    trees::RigidBranchState state{
        std::vector<Eigen::Vector3d>(at_rest.angle.size(), Eigen::Vector3d::Zero()),
        std::vector<Eigen::Vector3d>(at_rest.angle.size(), Eigen::Vector3d::Zero())};
    for (int n = 0; n < kSteps; ++n) rigid.step(tree.loads, double(float(dt)), state);
    largest = 0.0;
    const double step_error = angle_error(stepped, branches.entry_offset(k), state.angle, largest) / largest;
    // The steps did move the tree, and not simply to its equilibrium.
    double moved = 0.0, off_equilibrium = 0.0;
    for (std::size_t j = 0; j < state.angle.size(); ++j) {
      moved = std::max(moved, state.angle[j].norm());
      off_equilibrium = std::max(off_equilibrium, (state.angle[j] - at_rest.angle[j]).norm());
    }
    WARN("rigid tree " << k << ": equilibrium error " << equilibrium_error << ", after " << kSteps
                       << " steps " << step_error << " (largest angle " << moved << " rad, "
                       << off_equilibrium << " from equilibrium)");
    CHECK(equilibrium_error < kEquilibriumTolerance);
    CHECK(step_error < kStepTolerance);
    CHECK(off_equilibrium > 0.05 * moved);
  }
  CHECK(rigid_trees == 3);
}

TEST_CASE("tree_branches: the spring trees' angles and every element tree's pose match the reference",
          "[forest][branches]") {
  auto* cc = test::device_or_skip();
  if (!cc) return;
  BranchFixture f(*cc);
  host::BranchStages& branches = *f.stages.branches();
  // Steps of 0.37 s: the springs' sine at 1.85 s differs from its value at 0.
  constexpr double dt = 0.37;
  constexpr int kSteps = 5;
  for (int n = 0; n < kSteps; ++n) {
    f.stages.enqueue_wind_load(f.dwind);
    f.stages.enqueue_modal_step(float(dt));
  }
  // The springs' last bend was taken at the last step's start.
  const double time = double(float(dt)) * (kSteps - 1);
  const std::vector<float> joints = branches.download_joints();
  f.stages.enqueue_deform();
  const std::vector<float> u = f.stages.download_displacements();
  int spring_trees = 0;
  for (int k = 0; k < f.forest.instance_count(); ++k) {
    const int offset = branches.entry_offset(k);
    if (f.species(k) == test::kModal) {
      // The modal kernels' (tests/kernels/forest_stages_test.cpp); no element entries.
      REQUIRE(offset == -1);
      continue;
    }
    const ElementTree tree = element_tree(f.forest, k, f.spec, f.wind);
    if (f.species(k) == test::kSprings) {
      ++spring_trees;
      const std::vector<Eigen::Vector3d> angles =
          trees::spring_angles(tree.elements, f.dynamics[test::kSprings].springs, f.scale(k), tree.loads,
                               trees::spring_phases(f.forest.id(k), tree.elements.size()), time);
      double largest = 0.0;
      const double error = angle_error(joints, offset, angles, largest) / largest;
      WARN("spring tree " << k << ": angle error " << error << " (largest " << largest << " rad)");
      CHECK(error < kSpringTolerance);
      CHECK(largest > 1e-3);
    }
    // The pose from the device's own angles.
    const double error = pose_error(f.forest, tree.elements, joints, offset, u, k);
    WARN("tree " << k << ": pose error " << error);
    CHECK(error < kPoseTolerance);
  }
  CHECK(spring_trees == 3);
}

// Joints turned further than the pose's series reach (kernels/tree_branches.cl FW_SERIES_MAX_ANGLE, a right
// angle) take the library's sine and cosine, in the same walk as joints that stay on the series.
TEST_CASE("tree_branches: the pose of joints turned past the series' reach matches the reference",
          "[forest][branches]") {
  auto* cc = test::device_or_skip();
  if (!cc) return;
  BranchFixture f(*cc);
  host::BranchStages& branches = *f.stages.branches();
  host::StageState state;
  branches.save_state(state);
  std::vector<std::uint8_t>& bytes = state.buffers.at(host::saved::kJointState);
  std::vector<float> joints(bytes.size() / sizeof(float));
  std::mt19937 rng(13);
  // Every third entry turned 3.5 to 5 rad, the others below 1.6 rad.
  std::uniform_real_distribution<double> small(-0.9, 0.9), large(2.0, 2.9);
  int past_reach = 0;
  for (std::size_t entry = 0; entry < joints.size() / FW_JOINT_FLOATS; ++entry)
    for (int c = 0; c < 3; ++c)
      joints[FW_JOINT_FLOATS * entry + std::size_t(c)] = float(entry % 3 == 0 ? large(rng) : small(rng));
  for (std::size_t entry = 0; entry < joints.size() / FW_JOINT_FLOATS; entry += 3) ++past_reach;
  std::memcpy(bytes.data(), joints.data(), bytes.size());
  branches.restore_state(state);
  f.stages.enqueue_deform();
  const std::vector<float> u = f.stages.download_displacements();
  for (int k = 0; k < f.forest.instance_count(); ++k) {
    if (f.species(k) == test::kModal) continue;
    const trees::SpeciesBasis& basis = f.forest.species_of(k);
    const trees::BranchElements elements =
        trees::BranchElements::of(basis.skeleton(), basis.settings().material, basis.settings().wind);
    const double error = pose_error(f.forest, elements, joints, branches.entry_offset(k), u, k);
    INFO("tree " << k << ": pose error " << error);
    CHECK(error < kPoseTolerance);
  }
  CHECK(past_reach > 10);
}

// The springs take FW_LANES entries of a tree together, and every kernel walks several trees per work-item: a
// tree's frame must not depend on which trees stand beside it (over MPI ranks a rank holds only some of
// them), and nor may its steps. Interleaved species, and modal trees between them.
TEST_CASE("tree_branches: a tree's frame is the same to the bit alone and among its neighbours",
          "[forest][branches]") {
  auto* cc = test::device_or_skip();
  if (!cc) return;
  const fluid::GridSpec spec = forest_grid();
  std::mt19937 rng(29);
  std::uniform_real_distribution<double> x(1.0, 22.0), y(5.0, 22.0), yaw(-M_PI, M_PI), scale(0.6, 1.5);
  // Mostly element trees, more of each model than a work-item's lanes.
  std::discrete_distribution<int> kind({9.0, 9.0, 2.0});
  std::vector<trees::TreeInstance> placed;
  std::vector<int> per_species(3, 0);
  for (int k = 0; k < 3 * FW_LANES; ++k) {
    placed.push_back({kind(rng), {x(rng), y(rng), 0.0}, yaw(rng), scale(rng)});
    ++per_species[std::size_t(placed.back().species)];
  }
  REQUIRE(per_species[test::kRigid] > FW_LANES);
  REQUIRE(per_species[test::kSprings] > FW_LANES);
  const trees::Forest forest(test_forest().species(), std::move(placed));
  const std::vector<trees::SpeciesDynamics> dynamics = test::three_model_dynamics();
  const fluid::MacVelocity wind = test::smooth_velocity(spec, {6.0, -3.0, 0.5}, {2.0, 1.5, 1.0});
  host::DeviceVelocity dwind = test::upload_velocity(*cc, wind);
  // A few steps of 0.05 s from rest, then the frame.
  constexpr int kSteps = 3;
  const auto frame = [&](const trees::Forest& trees) {
    host::ForestStages stages(*cc, spec, trees, nullptr, dynamics);
    for (int n = 0; n < kSteps; ++n) {
      stages.enqueue_wind_load(dwind);
      stages.enqueue_modal_step(0.05f);
    }
    stages.enqueue_deform();
    return stages.download_displacements();
  };
  const std::vector<float> together = frame(forest);
  int checked = 0;
  for (int k = 0; k < forest.instance_count(); ++k) {
    if (forest.instances()[std::size_t(k)].species == test::kModal) continue;
    INFO("instance " << k);
    const std::vector<float> u = frame(forest.subset({k}));
    const auto from = together.begin() + 3 * std::ptrdiff_t(forest.node_offset(k));
    CHECK(std::equal(u.begin(), u.end(), from, from + std::ptrdiff_t(u.size())));
    CHECK(*std::max_element(u.begin(), u.end()) > 0.0f);
    ++checked;
  }
  CHECK(checked == per_species[test::kRigid] + per_species[test::kSprings]);
}

// The planner reports the estimate (host/app/plan/ForestPlan.cpp) and refuses a run that would not fit: it
// may count more work-items' scratch than a device uses (one per tree at most), never less.
TEST_CASE("tree_branches: the device memory estimate bounds what the element stages allocate",
          "[forest][branches]") {
  auto* cc = test::device_or_skip();
  if (!cc) return;
  const trees::Forest forest = test_forest();
  const std::vector<trees::SpeciesDynamics> dynamics = test::three_model_dynamics();
  const std::size_t before = cc->allocated_bytes();
  const host::ForestStages stages(*cc, forest_grid(), forest, nullptr, dynamics);
  const std::size_t allocated = cc->allocated_bytes() - before;
  const std::size_t estimate = host::ForestStages::estimate_device_bytes(forest, dynamics);
  INFO("allocated " << allocated << " bytes, estimated " << estimate);
  CHECK(allocated <= estimate);
  CHECK(allocated > host::ForestStages::estimate_device_bytes(forest));
}
