// kernels/tree_loads.cl (host/stages/DamageStages) against its CPU references trees/TreeDamage (modal trees)
// and trees/BranchStemLoads (element trees): every stem section's utilisation, the root's moment and the
// failure records of forests of small species with various yaws and scales, and what a failed tree does on
// the next step.
#include <catch2/catch.hpp>

#include <algorithm>
#include <cmath>
#include <random>

#include "host/stages/ForestStages.hpp"
#include "tests/support/BranchModels.hpp"
#include "tests/support/Fields.hpp"
#include "tests/support/SmallSpecies.hpp"
#include "tests/support/TestDevice.hpp"
#include "trees/BranchStemLoads.hpp"
#include "trees/TreeDamage.hpp"
#include "trees/TreeGenerator.hpp"

using namespace fw;

namespace {

// Float32 dot products of m terms with maps in float against the double reference: a few ulps of the
// largest term; q of both signs cancels, so the tolerance is relative to the largest utilisation.
constexpr double kUtilisationTolerance = 1e-5;

fluid::GridSpec loads_grid() {
  fluid::GridSpec spec;
  spec.nx = 32;
  spec.ny = 24;
  spec.nz = 14;
  spec.h = 1.0;
  return spec;
}

// The tests' wind: 8 m/s from the west-north-west with a long-wave ripple.
fluid::MacVelocity loads_wind(const fluid::GridSpec& spec) {
  return test::smooth_velocity(spec, {8.0, -2.0, 0.3}, {2.0, 1.0, 0.5});
}

// 16 instances of two species, yaws all round, scales 0.6 .. 1.5.
trees::Forest loads_forest() {
  std::vector<trees::SpeciesBasis> species = {test::small_species("broadleaf", 6.0, 1, 5, 8, 3),
                                              test::small_species("conifer", 5.0, 2, 4, 10, 2)};
  std::mt19937 rng(11);
  std::uniform_real_distribution<double> x(2.0, 28.0), y(2.0, 20.0), yaw(-M_PI, M_PI), scale(0.6, 1.5);
  std::vector<trees::TreeInstance> trees;
  for (int k = 0; k < 16; ++k) trees.push_back({k % 2, {x(rng), y(rng), 0.0}, yaw(rng), scale(rng)});
  return trees::Forest(std::move(species), std::move(trees));
}

// Every tree's loads by the reference, for the modal state `q` (flat, instance-major).
std::vector<trees::TreeLoad> reference_loads(const trees::Forest& forest,
                                             const trees::DamageSettings& settings,
                                             const std::vector<float>& q) {
  std::vector<trees::TreeLoad> loads;
  for (int k = 0; k < forest.instance_count(); ++k) {
    const trees::SpeciesBasis& species = forest.species_of(k);
    const int sp = forest.instances()[std::size_t(k)].species;
    Eigen::VectorXd qk(species.modes().mode_count());
    for (int i = 0; i < qk.size(); ++i) qk(i) = q[std::size_t(forest.mode_offset(k) + i)];
    const auto critical = trees::critical_moments(species.stem_loads(), settings.strengths[std::size_t(sp)]);
    loads.push_back(
        trees::tree_load(species.stem_loads(), critical, forest.instances()[std::size_t(k)].scale, qk));
  }
  return loads;
}

// A forest of the three models (docs/tree-models.md): rigid bodies, springs and modal, four trees each, yaws
// all round, scales 0.6 .. 1.5.
trees::Forest element_forest() {
  // The springs' wood is soft, as a user after a visible bend sets it (docs/tree-models.md): their joints
  // then turn by a few degrees and their pose's weight counts.
  trees::GeneratorSettings g;
  g.preset = "conifer";
  g.height = 5.0;
  g.seed = 2;
  g.iterations = 4;
  g.max_element_length = 5.0;
  trees::SpeciesSettings soft;
  soft.material = {2.0e7, 0.77e7, 900.0};
  soft.modal.mode_count = 6;
  soft.wind.samples = 2;
  soft.wind.leaf_area_index = 2.0;
  std::vector<trees::SpeciesBasis> species = {test::small_species("broadleaf", 6.0, 1, 5, 8, 3, 2.0),
                                              trees::SpeciesBasis::compute(trees::generate_tree(g), soft),
                                              test::small_species("broadleaf", 5.0, 3, 4, 6, 2)};
  std::mt19937 rng(5);
  std::uniform_real_distribution<double> x(2.0, 28.0), y(2.0, 20.0), yaw(-M_PI, M_PI), scale(0.6, 1.5);
  std::vector<trees::TreeInstance> trees;
  for (int k = 0; k < 12; ++k) trees.push_back({k % 3, {x(rng), y(rng), 0.0}, yaw(rng), scale(rng)});
  return trees::Forest(std::move(species), std::move(trees));
}

// The forest of element_forest() on the device, moved by a wind for a while: every joint turned, the rigid
// bodies off their equilibrium.
struct ElementFixture {
  host::ComputeContext& cc;
  fluid::GridSpec spec = loads_grid();
  trees::Forest forest = element_forest();
  std::vector<trees::SpeciesDynamics> dynamics = test::three_model_dynamics();
  host::ForestStages stages{cc, spec, forest, nullptr, dynamics};

  explicit ElementFixture(host::ComputeContext& c) : cc(c) {
    host::DeviceVelocity wind = test::upload_velocity(cc, loads_wind(spec));
    stages.enqueue_wind_load(wind);
    stages.enqueue_equilibrium();
    // A gust of twice the wind's drag on the rigid bodies' equilibrium: 0.3 s later they swing through it.
    test::upload(cc, test::smooth_velocity(spec, {11.0, -3.0, 0.4}, {2.5, 1.5, 0.6}), wind);
    for (int n = 0; n < 6; ++n) {
      stages.enqueue_wind_load(wind);
      stages.enqueue_modal_step(0.05f);
    }
  }
  int species(int k) const { return forest.instances()[std::size_t(k)].species; }
  double scale(int k) const { return forest.instances()[std::size_t(k)].scale; }
  // Tree k's loads by the references: trees/BranchStemLoads from the device's own joint angles, or tree_load
  // from the modal state.
  trees::TreeLoad reference(int k, const trees::DamageSettings& settings, const host::ModalState& modal) {
    const trees::SpeciesBasis& basis = forest.species_of(k);
    const auto critical =
        trees::critical_moments(basis.stem_loads(), settings.strengths[std::size_t(species(k))]);
    if (species(k) == test::kModal) {
      Eigen::VectorXd q(basis.modes().mode_count());
      for (int i = 0; i < q.size(); ++i) q(i) = modal.q[std::size_t(forest.mode_offset(k) + i)];
      return trees::tree_load(basis.stem_loads(), critical, scale(k), q);
    }
    const trees::BranchElements elements =
        trees::BranchElements::of(basis.skeleton(), basis.settings().material, basis.settings().wind);
    const std::vector<Eigen::Vector3d> angles = stages.branches()->download_angles(k, elements.size());
    const auto moments =
        trees::branch_stem_moments(basis.skeleton(), elements, trees::BranchStem::of(basis.skeleton()),
                                   dynamics[std::size_t(species(k))].model, scale(k), angles);
    return trees::branch_tree_load(moments, critical, scale(k));
  }
};

}  // namespace

TEST_CASE("tree_loads: utilisations, root moments and failures match the reference, once per tree",
          "[forest]") {
  auto* cc = test::device_or_skip();
  if (!cc) return;
  const fluid::GridSpec spec = loads_grid();
  const trees::Forest forest = loads_forest();
  host::ForestStages stages(*cc, spec, forest);
  host::DeviceVelocity wind = test::upload_velocity(*cc, loads_wind(spec));

  // A random modal state of the size a strong wind gives (its static response, times 3).
  stages.enqueue_wind_load(wind);
  stages.enqueue_equilibrium();
  const std::vector<float> q_static = stages.download_modal_state().q;
  const float amplitude = 3.0f * *std::max_element(q_static.begin(), q_static.end(), [](float a, float b) {
                            return std::abs(a) < std::abs(b);
                          });
  std::mt19937 rng(4);
  std::uniform_real_distribution<float> unit(-1.0f, 1.0f);
  host::ModalState state;
  for (int j = 0; j < stages.total_modes(); ++j) {
    state.q.push_back(std::abs(amplitude) * unit(rng));
    state.qdot.push_back(unit(rng));
  }

  // Strengths that fail about half the trees: the broadleaf (species 0) by overturning, its anchorage
  // brought to its trees' median overturning ratio and its wood a hundred times its largest breaking
  // ratio; the conifer (species 1) by breakage, the other way round.
  trees::DamageSettings settings;
  settings.enabled = true;
  settings.strengths = {trees::strength_preset(trees::StrengthPreset::birch),
                        trees::strength_preset(trees::StrengthPreset::norway_spruce)};
  std::vector<double> overturning[2], breaking[2];
  const std::vector<trees::TreeLoad> preset_loads = reference_loads(forest, settings, state.q);
  for (int k = 0; k < forest.instance_count(); ++k) {
    const int sp = forest.instances()[std::size_t(k)].species;
    overturning[sp].push_back(preset_loads[std::size_t(k)].overturning);
    breaking[sp].push_back(preset_loads[std::size_t(k)].utilisation.maxCoeff());
  }
  const auto median = [](std::vector<double> v) {
    std::nth_element(v.begin(), v.begin() + std::ptrdiff_t(v.size() / 2), v.end());
    return v[v.size() / 2];
  };
  const auto largest = [](const std::vector<double>& v) { return *std::max_element(v.begin(), v.end()); };
  settings.strengths[0].anchorage *= median(overturning[0]);
  settings.strengths[0].modulus_of_rupture *= 100.0 * largest(breaking[0]);
  settings.strengths[1].modulus_of_rupture *= median(breaking[1]);
  settings.strengths[1].anchorage *= 100.0 * largest(overturning[1]);
  const std::vector<trees::TreeLoad> expected = reference_loads(forest, settings, state.q);

  stages.set_damage(forest, settings);
  host::DamageStages& damage = *stages.damage();
  stages.upload_modal_state(state);
  stages.enqueue_damage_check(2.5f);
  const std::vector<float> utilisation = damage.download_utilisation();
  const std::vector<trees::TreeDamageRecord> records = damage.download_records();
  const std::vector<float> sampled = stages.download_sampled_wind();

  int failed = 0, broken = 0, overturned = 0;
  double worst_error = 0.0;
  for (int k = 0; k < forest.instance_count(); ++k) {
    INFO("tree " << k);
    const trees::TreeLoad& load = expected[std::size_t(k)];
    const double scale = load.largest();
    for (Eigen::Index j = 0; j < load.utilisation.size(); ++j)
      worst_error = std::max(
          worst_error,
          std::abs(utilisation[std::size_t(damage.section_offset(k) + j)] - load.utilisation(j)) / scale);
    const trees::TreeDamageRecord& r = records[std::size_t(k)];
    CHECK(r.utilisation == Approx(scale).epsilon(kUtilisationTolerance));
    CHECK(r.max_base_moment == Approx(load.root_moment).epsilon(kUtilisationTolerance));
    // Far enough from 1 that float rounding cannot decide (the reference's ratio is used to skip the rest).
    if (std::abs(scale - 1.0) < 10 * kUtilisationTolerance) continue;
    trees::TreeDamageRecord reference;
    const bool fails =
        trees::record_load(reference, load, 2.5, Eigen::Vector3d::Zero(),
                           forest.instances()[std::size_t(k)].scale, forest.species_of(k).stem_loads());
    CHECK((r.state != trees::TreeState::standing) == fails);
    CHECK(r.state == reference.state);
    CHECK(r.failed_section == reference.failed_section);
    CHECK(r.break_height == Approx(reference.break_height).epsilon(1e-6));
    if (!fails) continue;
    ++failed;
    broken += r.state == trees::TreeState::broken;
    overturned += r.state == trees::TreeState::overturned;
    CHECK(r.time == 2.5);
    const int top = forest.sample_offset(k) + forest.species_of(k).wind().sample_count() - 1;
    for (int a = 0; a < 3; ++a) CHECK(r.top_wind(a) == sampled[std::size_t(3 * top + a)]);
  }
  WARN("tree_loads: " << failed << " of 16 failed (" << broken << " broken, " << overturned
                      << " overturned); largest utilisation error " << worst_error);
  CHECK(worst_error < kUtilisationTolerance);
  CHECK(broken > 0);
  CHECK(overturned > 0);
  // The counter counts every tree that failed, those near 1 that the checks above skip included.
  const auto down = std::count_if(records.begin(), records.end(), [](const trees::TreeDamageRecord& r) {
    return r.state != trees::TreeState::standing;
  });
  CHECK(down >= failed);
  CHECK(damage.take_new_failures() == down);
  CHECK(damage.take_new_failures() == 0);

  // The next step: a failed tree is held at rest and carries nothing; a standing one goes on. Its record
  // keeps its time and maxima.
  stages.enqueue_damage_check(3.0f);
  const host::ModalState after = stages.download_modal_state();
  const std::vector<trees::TreeDamageRecord> later = damage.download_records();
  for (int k = 0; k < forest.instance_count(); ++k) {
    const bool down = later[std::size_t(k)].state != trees::TreeState::standing;
    for (int i = 0; i < forest.species_of(k).modes().mode_count(); ++i) {
      const std::size_t j = std::size_t(forest.mode_offset(k) + i);
      CHECK(after.q[j] == (down ? 0.0f : state.q[j]));
    }
    if (down) {
      CHECK(later[std::size_t(k)].utilisation == 0.0f);
      CHECK(later[std::size_t(k)].time == records[std::size_t(k)].time);
      CHECK(later[std::size_t(k)].max_utilisation == records[std::size_t(k)].max_utilisation);
    }
  }
  CHECK(damage.take_new_failures() == 0);
}

TEST_CASE("tree_loads: without consequences a failed tree keeps swaying and its record its first failure",
          "[forest]") {
  auto* cc = test::device_or_skip();
  if (!cc) return;
  const fluid::GridSpec spec = loads_grid();
  const trees::Forest forest = loads_forest();
  host::ForestStages stages(*cc, spec, forest);
  trees::DamageSettings settings;
  settings.enabled = true;
  settings.consequences = false;
  // Wood and roots of a thousandth of the preset's: any bend fails every tree.
  for (int sp = 0; sp < 2; ++sp) {
    trees::TreeStrength weak = trees::strength_preset(trees::StrengthPreset::scots_pine);
    weak.modulus_of_rupture *= 1e-3;
    weak.anchorage *= 1e-3;
    settings.strengths.push_back(weak);
  }
  stages.set_damage(forest, settings);
  host::ModalState state;
  for (int j = 0; j < stages.total_modes(); ++j) {
    state.q.push_back(j % 3 == 0 ? 0.05f : -0.02f);
    state.qdot.push_back(0.0f);
  }
  stages.upload_modal_state(state);
  stages.enqueue_damage_check(1.0f);
  CHECK(stages.damage()->take_new_failures() == forest.instance_count());
  stages.enqueue_damage_check(2.0f);
  CHECK(stages.damage()->take_new_failures() == 0);
  CHECK(stages.download_modal_state().q == state.q);
  for (const trees::TreeDamageRecord& r : stages.damage()->download_records()) {
    CHECK(r.state != trees::TreeState::standing);
    CHECK(r.time == 1.0);
    CHECK(r.utilisation > 1.0);  // still loaded
  }
}

TEST_CASE("tree_fall: a failed tree's nodes on a frame are the reference's fall, its stump at rest",
          "[forest]") {
  auto* cc = test::device_or_skip();
  if (!cc) return;
  const fluid::GridSpec spec = loads_grid();
  const trees::Forest forest = loads_forest();
  host::ForestStages stages(*cc, spec, forest);
  host::DeviceVelocity wind = test::upload_velocity(*cc, loads_wind(spec));
  stages.enqueue_wind_load(wind);
  stages.enqueue_equilibrium();
  // Strengths that fail about half the trees in the wind's static bend: both presets brought to the
  // median tree's largest ratio.
  trees::DamageSettings settings;
  settings.enabled = true;
  settings.strengths = {trees::strength_preset(trees::StrengthPreset::birch),
                        trees::strength_preset(trees::StrengthPreset::scots_pine)};
  std::vector<double> largest;
  for (const trees::TreeLoad& load : reference_loads(forest, settings, stages.download_modal_state().q))
    largest.push_back(load.largest());
  std::nth_element(largest.begin(), largest.begin() + 8, largest.end());
  for (trees::TreeStrength& s : settings.strengths) {
    s.modulus_of_rupture *= 0.999 * largest[8];
    s.anchorage *= 0.999 * largest[8];
  }
  stages.set_damage(forest, settings);
  stages.enqueue_damage_check(4.0f);
  const std::vector<trees::TreeDamageRecord> records = stages.damage()->download_records();
  stages.enqueue_damage_check(4.5f);  // the failed trees' modes now at rest
  constexpr double kFrameTime = 6.0;  // 2 s into the falls: part way down
  stages.enqueue_deform();
  stages.enqueue_falls(kFrameTime);
  const std::vector<float> u = stages.download_displacements();
  int falling = 0;
  double worst = 0.0;
  for (int k = 0; k < forest.instance_count(); ++k) {
    const trees::TreeDamageRecord& r = records[std::size_t(k)];
    if (r.state == trees::TreeState::standing) continue;
    ++falling;
    const trees::FallPose pose = trees::fall_pose(r, trees::FallGeometry::of(forest.species_of(k)),
                                                  forest.instances()[std::size_t(k)].scale, kFrameTime);
    const Eigen::MatrixX3d expected = trees::fall_displacements(forest, k, pose);
    for (Eigen::Index n = 0; n < expected.rows(); ++n)
      for (int a = 0; a < 3; ++a)
        worst =
            std::max(worst, std::abs(u[std::size_t(3 * (forest.node_offset(k) + n) + a)] - expected(n, a)));
  }
  WARN("tree_fall: " << falling << " trees falling, largest difference " << worst << " m");
  CHECK(falling >= 4);
  // Float positions of a few metres and a float rotation: 1e-5 m.
  CHECK(worst < 1e-5);
}

TEST_CASE("DamageStages: the estimate is what the constructor allocates", "[forest]") {
  auto* cc = test::device_or_skip();
  if (!cc) return;
  const trees::Forest forest = loads_forest();
  trees::DamageSettings settings;
  settings.enabled = true;
  settings.strengths.assign(2, trees::strength_preset(trees::StrengthPreset::scots_pine));
  const std::size_t before = cc->allocated_bytes();
  host::DamageStages damage(*cc, forest, settings);
  CHECK(cc->allocated_bytes() - before == host::DamageStages::estimate_device_bytes(forest, settings));
}

TEST_CASE(
    "tree_loads: the element trees' utilisations, root moments and failures match their reference, and a "
    "failed tree's joints are held at rest",
    "[forest][branches]") {
  auto* cc = test::device_or_skip();
  if (!cc) return;
  ElementFixture f(*cc);
  host::BranchStages& branches = *f.stages.branches();
  const std::vector<float> joints = branches.download_joints();
  const host::ModalState modal = f.stages.download_modal_state();

  // Strengths that fail half the element trees: the rigid bodies by overturning (their anchorage brought to
  // 0.95 of their trees' median overturning ratio, their wood a hundred times its largest breaking ratio),
  // the springs by breakage, the other way round; the modal trees stand (a hundred times both).
  trees::DamageSettings settings;
  settings.enabled = true;
  settings.strengths.assign(3, trees::strength_preset(trees::StrengthPreset::norway_spruce));
  std::vector<double> overturning[3], breaking[3];
  double largest_angle = 0.0;
  for (int k = 0; k < f.forest.instance_count(); ++k) {
    const trees::TreeLoad load = f.reference(k, settings, modal);
    overturning[f.species(k)].push_back(load.overturning);
    breaking[f.species(k)].push_back(load.utilisation.maxCoeff());
    if (f.species(k) == test::kSprings)
      for (const Eigen::Vector3d& theta :
           branches.download_angles(k, f.forest.species_of(k).skeleton().size()))
        largest_angle = std::max(largest_angle, theta.norm());
  }
  // The soft springs bend: their pose and its weight count.
  CHECK(largest_angle > 0.03);
  const auto median = [](std::vector<double> v) {
    std::nth_element(v.begin(), v.begin() + std::ptrdiff_t(v.size() / 2), v.end());
    return v[v.size() / 2];
  };
  const auto largest = [](const std::vector<double>& v) { return *std::max_element(v.begin(), v.end()); };
  settings.strengths[test::kRigid].anchorage *= 0.95 * median(overturning[test::kRigid]);
  settings.strengths[test::kRigid].modulus_of_rupture *= 100.0 * largest(breaking[test::kRigid]);
  settings.strengths[test::kSprings].modulus_of_rupture *= 0.95 * median(breaking[test::kSprings]);
  settings.strengths[test::kSprings].anchorage *= 100.0 * largest(overturning[test::kSprings]);
  settings.strengths[test::kModal].modulus_of_rupture *= 100.0 * largest(breaking[test::kModal]);
  settings.strengths[test::kModal].anchorage *= 100.0 * largest(overturning[test::kModal]);
  std::vector<trees::TreeLoad> expected;
  for (int k = 0; k < f.forest.instance_count(); ++k) expected.push_back(f.reference(k, settings, modal));

  const std::size_t before = cc->allocated_bytes();
  f.stages.set_damage(f.forest, settings);
  const std::size_t allocated = cc->allocated_bytes() - before;
  // What the plan reports (host/app/plan/DamagePlan.cpp): a slice of scratch a tree, as many as a device
  // uses.
  CHECK(allocated == host::DamageStages::estimate_device_bytes(f.forest, settings, f.dynamics));
  CHECK(allocated > host::DamageStages::estimate_device_bytes(f.forest, settings));
  host::DamageStages& damage = *f.stages.damage();
  f.stages.enqueue_damage_check(2.5f);
  const std::vector<float> utilisation = damage.download_utilisation();
  const std::vector<trees::TreeDamageRecord> records = damage.download_records();
  const std::vector<float> sampled = f.stages.download_sampled_wind();

  int failed[3] = {}, broken = 0, overturned = 0;
  double worst_error[3] = {};
  for (int k = 0; k < f.forest.instance_count(); ++k) {
    INFO("tree " << k << ", species " << f.species(k));
    const trees::TreeLoad& load = expected[std::size_t(k)];
    const double scale = load.largest();
    // Relative to the tree's largest section utilisation (a hundredth of its largest where it overturns).
    for (Eigen::Index j = 0; j < load.utilisation.size(); ++j)
      worst_error[f.species(k)] =
          std::max(worst_error[f.species(k)],
                   std::abs(utilisation[std::size_t(damage.section_offset(k) + j)] - load.utilisation(j)) /
                       load.utilisation.maxCoeff());
    const trees::TreeDamageRecord& r = records[std::size_t(k)];
    CHECK(r.utilisation == Approx(scale).epsilon(kUtilisationTolerance));
    CHECK(r.max_base_moment == Approx(load.root_moment).epsilon(kUtilisationTolerance));
    if (std::abs(scale - 1.0) < 10 * kUtilisationTolerance) continue;
    trees::TreeDamageRecord reference;
    const bool fails = trees::record_load(reference, load, 2.5, Eigen::Vector3d::Zero(), f.scale(k),
                                          f.forest.species_of(k).stem_loads());
    CHECK((r.state != trees::TreeState::standing) == fails);
    CHECK(r.state == reference.state);
    CHECK(r.failed_section == reference.failed_section);
    CHECK(r.break_height == Approx(reference.break_height).epsilon(1e-6));
    if (!fails) continue;
    ++failed[f.species(k)];
    broken += r.state == trees::TreeState::broken;
    overturned += r.state == trees::TreeState::overturned;
    CHECK(r.time == 2.5);
    const int top = f.forest.sample_offset(k) + f.forest.species_of(k).wind().sample_count() - 1;
    for (int a = 0; a < 3; ++a) CHECK(r.top_wind(a) == sampled[std::size_t(3 * top + a)]);
  }
  WARN("tree_loads, element trees: failed "
       << failed[test::kRigid] << " rigid (of 4), " << failed[test::kSprings] << " springs (of 4), "
       << failed[test::kModal] << " modal; largest utilisation error: rigid " << worst_error[test::kRigid]
       << ", springs " << worst_error[test::kSprings] << ", modal " << worst_error[test::kModal]);
  for (const double error : worst_error) CHECK(error < kUtilisationTolerance);
  CHECK(failed[test::kRigid] == 2);
  CHECK(failed[test::kSprings] == 2);
  CHECK(failed[test::kModal] == 0);
  CHECK(broken > 0);
  CHECK(overturned > 0);
  const auto down = std::count_if(records.begin(), records.end(), [](const trees::TreeDamageRecord& r) {
    return r.state != trees::TreeState::standing;
  });
  CHECK(damage.take_new_failures() == down);

  // The next check: a failed element tree's joints are zeroed (angles and rates) and its sections carry
  // nothing; a standing tree's joints are as they were.
  f.stages.enqueue_damage_check(3.0f);
  const std::vector<float> after = branches.download_joints();
  const std::vector<trees::TreeDamageRecord> later = damage.download_records();
  const std::vector<float> later_utilisation = damage.download_utilisation();
  int held = 0;
  for (int k = 0; k < f.forest.instance_count(); ++k) {
    if (f.species(k) == test::kModal) continue;
    INFO("tree " << k);
    const bool is_down = later[std::size_t(k)].state != trees::TreeState::standing;
    held += is_down;
    const int entries = f.forest.species_of(k).skeleton().size();
    for (int i = 0; i < FW_JOINT_FLOATS * entries; ++i) {
      const std::size_t j = std::size_t(FW_JOINT_FLOATS * branches.entry_offset(k) + i);
      CHECK(after[j] == (is_down ? 0.0f : joints[j]));
    }
    if (!is_down) continue;
    CHECK(later[std::size_t(k)].utilisation == 0.0f);
    CHECK(later[std::size_t(k)].time == records[std::size_t(k)].time);
    CHECK(later[std::size_t(k)].max_utilisation == records[std::size_t(k)].max_utilisation);
    for (int j = 0; j < f.forest.species_of(k).stem_loads().section_count(); ++j)
      CHECK(later_utilisation[std::size_t(damage.section_offset(k) + j)] == 0.0f);
  }
  CHECK(held == down);
  CHECK(damage.take_new_failures() == 0);

  // Stepped on, a held tree moves for one step and is zeroed again (after the step): the pose of a frame
  // shows it at rest.
  f.stages.enqueue_modal_step(0.05f);
  f.stages.enqueue_damage_check(3.05f);
  const std::vector<float> stepped = branches.download_joints();
  for (int k = 0; k < f.forest.instance_count(); ++k) {
    if (f.species(k) == test::kModal || later[std::size_t(k)].state == trees::TreeState::standing) continue;
    const int entries = f.forest.species_of(k).skeleton().size();
    for (int i = 0; i < FW_JOINT_FLOATS * entries; ++i)
      CHECK(stepped[std::size_t(FW_JOINT_FLOATS * branches.entry_offset(k) + i)] == 0.0f);
  }
}

TEST_CASE("tree_loads: without consequences a failed element tree keeps its joints and fails once",
          "[forest][branches]") {
  auto* cc = test::device_or_skip();
  if (!cc) return;
  ElementFixture f(*cc);
  trees::DamageSettings settings;
  settings.enabled = true;
  settings.consequences = false;
  // Wood and roots of a millionth of the preset's: any bend fails every element tree; the modal trees'
  // a thousand times the preset's stand.
  for (int sp = 0; sp < 3; ++sp) {
    trees::TreeStrength strength = trees::strength_preset(trees::StrengthPreset::scots_pine);
    const double factor = sp == test::kModal ? 1e3 : 1e-6;
    strength.modulus_of_rupture *= factor;
    strength.anchorage *= factor;
    settings.strengths.push_back(strength);
  }
  f.stages.set_damage(f.forest, settings);
  const std::vector<float> joints = f.stages.branches()->download_joints();
  f.stages.enqueue_damage_check(1.0f);
  CHECK(f.stages.damage()->take_new_failures() == 8);
  f.stages.enqueue_damage_check(2.0f);
  CHECK(f.stages.damage()->take_new_failures() == 0);
  CHECK(f.stages.branches()->download_joints() == joints);
  const std::vector<trees::TreeDamageRecord> records = f.stages.damage()->download_records();
  for (int k = 0; k < f.forest.instance_count(); ++k) {
    const trees::TreeDamageRecord& r = records[std::size_t(k)];
    if (f.species(k) == test::kModal) {
      CHECK(r.state == trees::TreeState::standing);
      continue;
    }
    CHECK(r.state != trees::TreeState::standing);
    CHECK(r.time == 1.0);
    CHECK(r.utilisation > 1.0);  // still loaded
  }
}
