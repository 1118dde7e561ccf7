// The leaves (docs/leaves.md): LeafSettings' validation, SpeciesLeaves' generation on the foliage, and the
// CPU oracle LeafReference: flight to the terminal speed and with the wind, landing and exits, shedding and
// the flutter of both models.
#include <catch2/catch.hpp>

#include <Eigen/Geometry>
#include <algorithm>
#include <cmath>
#include <functional>
#include <numbers>
#include <stdexcept>

#include "tests/support/SmallSpecies.hpp"
#include "trees/Foliage.hpp"
#include "trees/ForestReference.hpp"
#include "trees/LeafReference.hpp"
#include "trees/LeafSettings.hpp"
#include "trees/SpeciesLeaves.hpp"
#include "trees/TreeGenerator.hpp"

using namespace fw;

namespace {

constexpr double kLai = 3.0;  // leaf area index of the test trees
// m or unit-vector components: the round-off of a few operations on values of order 1.
constexpr double kGeometry = 1e-12;
constexpr double kDt = 0.05;  // s, the step of the coupled simulation's typical wind grid

trees::SpeciesBasis small_species() {
  trees::SpeciesSettings settings;
  settings.modal.mode_count = 4;
  settings.wind.samples = 3;
  settings.wind.leaf_area_index = kLai;
  return trees::SpeciesBasis::compute(test::asymmetric_skeleton(), settings);
}

trees::SpeciesLeaves leaves_of(const trees::Skeleton& skeleton, const trees::LeafSettings& settings) {
  return trees::SpeciesLeaves::generate(skeleton, trees::Foliage::of(skeleton, kLai), settings);
}

// One small tree at the origin with the given leaves.
trees::LeafReference small_forest(const trees::LeafSettings& settings) {
  const trees::Forest forest({small_species()}, {{0, Eigen::Vector3d::Zero(), 0.0, 1.0}});
  return trees::LeafReference(forest, {leaves_of(test::asymmetric_skeleton(), settings)});
}

fluid::GridSpec grid(int nx, int ny, int nz, const std::array<double, 3>& origin) {
  fluid::GridSpec spec;
  spec.nx = nx;
  spec.ny = ny;
  spec.nz = nz;
  spec.h = 1.0;
  spec.origin = origin;
  spec.validate();
  return spec;
}

fluid::MacVelocity uniform_wind(const fluid::GridSpec& spec, const Eigen::Vector3d& v) {
  fluid::MacVelocity wind(spec);
  for (int c = 0; c < 3; ++c) std::fill(wind.component(c).begin(), wind.component(c).end(), float(v(c)));
  return wind;
}

// Every leaf flying from rest at where(j).
void launch(trees::LeafReference& ref, const std::function<Eigen::Vector3d(int)>& where) {
  for (int j = 0; j < ref.count(); ++j) {
    ref.leaf(j).state = trees::LeafState::flying;
    ref.leaf(j).position = where(j);
    ref.leaf(j).velocity.setZero();
  }
}

void run(trees::LeafReference& ref, const fluid::GridSpec& spec, const std::vector<std::uint8_t>& solid,
         const fluid::MacVelocity& wind, int steps, double dt = kDt) {
  for (int n = 0; n < steps; ++n) ref.step(spec, solid, wind, n * dt, dt);
}

double distance_to_segment(const Eigen::Vector3d& p, const Eigen::Vector3d& a, const Eigen::Vector3d& b) {
  const double t = std::clamp((p - a).dot(b - a) / (b - a).squaredNorm(), 0.0, 1.0);
  return (p - (a + t * (b - a))).norm();
}

}  // namespace

TEST_CASE("leaves: generation follows the foliage", "[leaves]") {
  const trees::Skeleton tree = test::small_broadleaf();
  const trees::Foliage foliage = trees::Foliage::of(tree, kLai);
  const trees::LeafSettings settings;
  const trees::SpeciesLeaves leaves = trees::SpeciesLeaves::generate(tree, foliage, settings);

  REQUIRE(foliage.leaf_area > 0.0);
  CHECK(leaves.count() == std::llround(settings.fraction * foliage.leaf_area / settings.area));
  CHECK(leaves.foliage_leaf_count() == Approx(foliage.leaf_area / settings.area));
  CHECK(leaves.side() == Approx(std::sqrt(settings.area)));
  CHECK(leaves.lever() == Approx(std::sqrt(settings.area)));  // l_p + l / 2 = 0.5 l + 0.5 l
  CHECK(leaves.mass() == Approx(settings.mass_per_area * settings.area));

  std::vector<double> strengths;
  for (const trees::RestLeaf& leaf : leaves.leaves()) {
    REQUIRE(foliage.leaf_bearing.at(std::size_t(leaf.element)));
    const auto [parent, child] = tree.elements()[std::size_t(leaf.element)];
    const Eigen::Vector3d a = tree.node(parent).position, b = tree.node(child).position;
    CHECK(distance_to_segment(leaf.anchor, a, b) < kGeometry);
    CHECK((leaf.anchor - (a + leaf.along * (b - a))).norm() < kGeometry);
    CHECK(std::abs(leaf.petiole.dot((b - a).normalized())) < kGeometry);
    CHECK(std::abs(leaf.petiole.norm() - 1.0) < kGeometry);
    CHECK(std::abs(leaf.hinge.norm() - 1.0) < kGeometry);
    CHECK(std::abs(leaf.normal.norm() - 1.0) < kGeometry);
    CHECK(std::abs(leaf.hinge.dot(leaf.petiole)) < kGeometry);
    CHECK(std::abs(leaf.normal.dot(leaf.petiole)) < kGeometry);  // the twist turns it about the petiole
    CHECK(leaf.normal.z() >= 0.0);
    CHECK(std::abs(leaf.tumble_axis.norm() - 1.0) < kGeometry);
    CHECK(leaf.tumble_axis.z() == 0.0);
    CHECK(leaf.strength > 0.0);
    for (const double f : leaf.frequency) {
      CHECK(f >= 0.8 * settings.frequency);  // +-20% jitter
      CHECK(f <= 1.2 * settings.frequency);
    }
    strengths.push_back(leaf.strength);
  }
  // The log-normal's median: the sample median of N draws has a relative standard error of about
  // 1.25 sigma / sqrt(N) (~1% here), so 5% is five of them.
  std::nth_element(strengths.begin(), strengths.begin() + strengths.size() / 2, strengths.end());
  CHECK(strengths[strengths.size() / 2] == Approx(settings.petiole_strength).epsilon(0.05));
}

TEST_CASE("leaves: generation is deterministic from the seed", "[leaves]") {
  const trees::Skeleton tree = test::small_broadleaf();
  trees::LeafSettings settings;
  settings.seed = 42;
  const trees::SpeciesLeaves a = leaves_of(tree, settings), b = leaves_of(tree, settings);
  settings.seed = 43;
  const trees::SpeciesLeaves c = leaves_of(tree, settings);
  REQUIRE(a.count() == b.count());
  REQUIRE(a.count() == c.count());  // the count depends on the foliage only
  int differing = 0;
  for (int k = 0; k < a.count(); ++k) {
    const trees::RestLeaf &x = a.leaf(k), &y = b.leaf(k);
    CHECK(x.element == y.element);
    CHECK(x.along == y.along);  // bit-identical: the same draws in the same order
    CHECK(x.anchor == y.anchor);
    CHECK(x.petiole == y.petiole);
    CHECK(x.normal == y.normal);
    CHECK(x.strength == y.strength);
    CHECK(x.phase == y.phase);
    CHECK(x.tumble_axis == y.tumble_axis);
    differing += c.leaf(k).anchor != x.anchor;
  }
  CHECK(differing == a.count());
}

TEST_CASE("leaves: a winter tree or a bare crown has no leaves", "[leaves]") {
  const trees::Skeleton tree = test::small_broadleaf();
  trees::LeafSettings settings;
  settings.model = trees::FlutterModel::none;
  CHECK(leaves_of(tree, settings).count() == 0);
  const trees::LeafSettings defaults;
  CHECK(trees::SpeciesLeaves::generate(tree, trees::Foliage::of(tree, 0.0), defaults).count() == 0);
  CHECK(trees::SpeciesLeaves().count() == 0);
}

TEST_CASE("leaves: a fraction thins the leaves", "[leaves]") {
  const trees::Skeleton tree = test::small_broadleaf();
  trees::LeafSettings settings;
  const int all = leaves_of(tree, settings).count();
  settings.fraction = 0.5;
  const trees::SpeciesLeaves half = leaves_of(tree, settings);
  CHECK(half.count() == std::llround(0.5 * half.foliage_leaf_count()));
  CHECK(std::abs(half.count() - 0.5 * all) <= 1.0);  // two roundings of the same count
}

TEST_CASE("leaves: a leaf area past the int count is refused before a leaf is made", "[leaves]") {
  const trees::Skeleton tree = test::small_broadleaf();
  const trees::LeafSettings defaults;
  // 1e30 m^2/m^2 of leaves: a count past long long, which rounded to a size once asked for 2^63 leaves.
  const trees::Foliage foliage = trees::Foliage::of(tree, 1e30);
  CHECK(trees::SpeciesLeaves::planned_count(foliage, defaults) > trees::SpeciesLeaves::kMaxCount);
  CHECK_THROWS_AS(trees::SpeciesLeaves::generate(tree, foliage, defaults), std::invalid_argument);
  const trees::Foliage usual = trees::Foliage::of(tree, 3.0);
  CHECK(trees::SpeciesLeaves::generate(tree, usual, defaults).count() ==
        std::llround(trees::SpeciesLeaves::planned_count(usual, defaults)));
}

TEST_CASE("leaves: validate names the key", "[leaves]") {
  using Edit = std::function<void(trees::LeafSettings&)>;
  const std::vector<std::pair<std::string, Edit>> cases = {
      {"area", [](auto& s) { s.area = 0.0; }},
      {"fraction", [](auto& s) { s.fraction = 1.5; }},
      {"fraction", [](auto& s) { s.fraction = 0.0; }},
      {"mass_per_area", [](auto& s) { s.mass_per_area = -0.1; }},
      {"frequency", [](auto& s) { s.frequency = NAN; }},
      {"damping_ratio", [](auto& s) { s.damping_ratio = 1.0; }},
      {"petiole_strength", [](auto& s) { s.petiole_strength = 0.0; }},
      {"strength_spread", [](auto& s) { s.strength_spread = -1.0; }},
      {"flight_drag_coefficient", [](auto& s) { s.flight_drag_coefficient = 0.0; }},
      {"amplitudes", [](auto& s) { s.amplitudes_deg[1] = -5.0; }},
      {"roll_coupling", [](auto& s) { s.roll_coupling = INFINITY; }},
      {"reference_speed", [](auto& s) { s.reference_speed = 0.0; }},
  };
  for (const auto& [key, edit] : cases) {
    INFO(key);
    trees::LeafSettings settings;
    edit(settings);
    CHECK_THROWS_WITH(settings.validate(), Catch::Contains("LeafSettings: " + key + " must"));
    CHECK_THROWS_WITH(leaves_of(test::small_broadleaf(), settings),
                      Catch::Contains("SpeciesLeaves: LeafSettings: " + key));
  }
  CHECK_NOTHROW(trees::LeafSettings{}.validate());

  CHECK(trees::to_string(trees::FlutterModel::none) == "none");
  CHECK(trees::to_string(trees::FlutterModel::pseudo_branch) == "pseudo_branch");
  CHECK(trees::to_string(trees::FlutterModel::stochastic) == "stochastic");

  const trees::Skeleton tree = test::small_broadleaf();
  CHECK_THROWS_WITH(
      trees::SpeciesLeaves::generate(tree, trees::Foliage::of(test::asymmetric_skeleton(), kLai), {}),
      Catch::Contains("SpeciesLeaves: the foliage"));
  const trees::Forest forest({small_species()}, {{0, Eigen::Vector3d::Zero(), 0.0, 1.0}});
  CHECK_THROWS_WITH(trees::LeafReference(forest, {}), Catch::Contains("LeafReference: 0 species leaves"));
}

TEST_CASE("leaves: instances scale and turn the species leaves", "[leaves]") {
  trees::LeafSettings settings;
  settings.fraction = 0.1;
  const trees::SpeciesLeaves species = leaves_of(test::asymmetric_skeleton(), settings);
  const double yaw = 0.7, scale = 1.3;
  const Eigen::Vector3d at(5.0, 3.0, 0.5);
  const trees::Forest forest({small_species()},
                             {{0, Eigen::Vector3d::Zero(), 0.0, 1.0}, {0, at, yaw, scale}});
  const trees::LeafReference ref(forest, {species});
  const int n = species.count();
  REQUIRE(n > 0);
  REQUIRE(ref.count() == 2 * n);
  const Eigen::Matrix3d turn = Eigen::AngleAxisd(yaw, Eigen::Vector3d::UnitZ()).toRotationMatrix();
  for (int k = 0; k < n; ++k) {
    const trees::RestLeaf& rest = species.leaf(k);
    const trees::WorldLeaf& leaf = ref.leaf(n + k);
    CHECK(ref.leaf(k).tree == 0);
    CHECK(leaf.tree == 1);
    CHECK(leaf.state == trees::LeafState::attached);
    CHECK((leaf.anchor - (at + scale * turn * rest.anchor)).norm() < kGeometry);
    CHECK((leaf.petiole - turn * rest.petiole).norm() < kGeometry);
    CHECK((leaf.rest_normal - turn * rest.normal).norm() < kGeometry);
    CHECK(leaf.lever == Approx(scale * species.lever()));
    CHECK(leaf.area == Approx(scale * scale * settings.area));
    CHECK(leaf.mass == Approx(scale * scale * species.mass()));
    CHECK((leaf.position - (leaf.anchor + leaf.lever * leaf.petiole)).norm() < kGeometry);
  }
  CHECK(ref.counts().attached == 2 * n);
  CHECK(ref.counts().shed == 0);
}

TEST_CASE("leaves: in still air a leaf falls at the terminal speed", "[leaves]") {
  trees::LeafSettings settings;
  settings.fraction = 0.05;
  trees::LeafReference ref = small_forest(settings);
  REQUIRE(ref.count() > 0);
  const fluid::GridSpec spec = grid(10, 10, 40, {-5.0, -5.0, 0.0});
  launch(ref, [](int) { return Eigen::Vector3d(0.0, 0.0, 35.0); });
  const fluid::MacVelocity still = uniform_wind(spec, Eigen::Vector3d::Zero());
  // 3 s: about 20 relaxation times v_t / g = 0.13 s, so only the step's fixed point is left.
  const int steps = 60;
  run(ref, spec, {}, still, steps);
  const double v_t = trees::terminal_speed(settings);
  CHECK(v_t == Approx(1.28).epsilon(0.01));  // docs/leaves.md's value at the defaults, to its two decimals
  for (int j = 0; j < ref.count(); ++j) {
    const trees::WorldLeaf& leaf = ref.leaf(j);
    REQUIRE(leaf.state == trees::LeafState::flying);
    const double error = std::abs(-leaf.velocity.z() - v_t) / v_t;
    INFO("terminal speed error " << error);
    // The implicit drag's fixed point is v_t exactly; 1e-6 leaves room for the transient's e^-20 remainder.
    CHECK(error < 1e-6);
    CHECK(leaf.velocity.head<2>().norm() < kGeometry);
  }
}

TEST_CASE("leaves: flying leaves take up the wind", "[leaves]") {
  trees::LeafSettings settings;
  settings.fraction = 0.05;
  trees::LeafReference ref = small_forest(settings);
  fluid::GridSpec spec = grid(16, 16, 40, {-8.0, -8.0, 0.0});
  for (int face : {FW_FACE_WEST, FW_FACE_EAST, FW_FACE_SOUTH, FW_FACE_NORTH})
    spec.boundary[std::size_t(face)] = fluid::BoundaryType::periodic;
  const double speed = 8.0;
  const fluid::MacVelocity wind = uniform_wind(spec, {speed, 0.0, 0.0});
  launch(ref, [](int j) { return Eigen::Vector3d(0.1 * (j % 10), 0.1 * (j / 10 % 10), 30.0); });
  run(ref, spec, {}, wind, 40);  // 2 s, a hundred of the drag's relaxation times 1 / (k |u - v|)
  double mean = 0.0;
  for (int j = 0; j < ref.count(); ++j) {
    REQUIRE(ref.leaf(j).state == trees::LeafState::flying);  // periodic sides: no exits
    mean += ref.leaf(j).velocity.head<2>().norm() / ref.count();
  }
  INFO("mean horizontal speed " << mean << " m/s in a wind of " << speed);
  CHECK(std::abs(mean - speed) < 0.2 * speed);
  // The horizontal slip decays by 1 / (1 + dt k |u - v|) a step, at least 0.72 once only the fall is left.
  CHECK(std::abs(mean - speed) < 1e-4 * speed);
}

namespace {

// 16^3 cells of 1 m with a block of cells [4, 8) x [4, 8) x [0, 3): its top at z = 3 m, its west wall at
// x = 4 m.
constexpr int kBlockLo = 4, kBlockHi = 8, kBlockTop = 3;

struct BlockScene {
  fluid::GridSpec spec = grid(16, 16, 16, {0.0, 0.0, 0.0});
  std::vector<std::uint8_t> solid = std::vector<std::uint8_t>(spec.cell_count(), 0);

  BlockScene() {
    for (int k = 0; k < kBlockTop; ++k)
      for (int j = kBlockLo; j < kBlockHi; ++j)
        for (int i = kBlockLo; i < kBlockHi; ++i) solid[std::size_t(i + spec.nx * (j + spec.ny * k))] = 1;
  }
  bool inside_solid(const Eigen::Vector3d& x) const {
    const int i = int(std::floor(x.x())), j = int(std::floor(x.y())), k = int(std::floor(x.z()));
    return x.z() < 0.0 || solid[std::size_t(i + spec.nx * (j + spec.ny * k))] != 0;
  }
};

}  // namespace

TEST_CASE("leaves: flying leaves land on top faces and never inside solids", "[leaves]") {
  const BlockScene scene;
  const double half_cell = 0.5 * scene.spec.h;  // docs/leaves.md: a landed leaf lies on a top face
  trees::LeafSettings settings;
  settings.fraction = 0.05;

  SECTION("dropped in still air over the block and over open ground") {
    trees::LeafReference ref = small_forest(settings);
    const int n = ref.count();
    REQUIRE(n >= 10);
    auto over_block = [](int j) { return j % 2 == 0; };
    launch(ref, [&](int j) {
      const double a = 0.37 * (j % 7), b = 0.41 * (j / 7 % 7);  // spread over 2.2 m x 2.5 m
      return over_block(j) ? Eigen::Vector3d(4.4 + a, 4.4 + b, 10.0)
                           : Eigen::Vector3d(10.5 + a, 10.5 + b, 10.0);
    });
    const fluid::MacVelocity still = uniform_wind(scene.spec, Eigen::Vector3d::Zero());
    run(ref, scene.spec, scene.solid, still, 200);  // 10 s: a fall of 10 m at 1.28 m/s takes 8 s at most
    for (int j = 0; j < n; ++j) {
      const trees::WorldLeaf& leaf = ref.leaf(j);
      INFO("leaf " << j << " at " << leaf.position.transpose());
      REQUIRE(leaf.state == trees::LeafState::landed);
      CHECK(std::abs(leaf.position.z() - (over_block(j) ? kBlockTop : 0.0)) < half_cell);
      CHECK_FALSE(scene.inside_solid(leaf.position));
    }
    CHECK(ref.counts().landed == n);
    CHECK(ref.counts().shed == n);
  }

  SECTION("blown into the block's wall, they slide down it to the ground and stay") {
    trees::LeafReference ref = small_forest(settings);
    const int n = ref.count();
    launch(ref, [](int j) { return Eigen::Vector3d(2.5 + 0.2 * (j % 7), 4.5 + 0.4 * (j / 7 % 7), 2.5); });
    const fluid::MacVelocity breeze = uniform_wind(scene.spec, {3.0, 0.0, 0.0});
    run(ref, scene.spec, scene.solid, breeze, 100);
    std::vector<Eigen::Vector3d> landed_at;
    for (int j = 0; j < n; ++j) {
      const trees::WorldLeaf& leaf = ref.leaf(j);
      INFO("leaf " << j << " at " << leaf.position.transpose());
      REQUIRE(leaf.state == trees::LeafState::landed);
      CHECK(std::abs(leaf.position.z()) < half_cell);   // on the ground by the wall
      CHECK(leaf.position.x() <= kBlockLo);             // never through the wall
      CHECK(leaf.position.x() > kBlockLo - half_cell);  // it stopped at the wall, within one sub-step
      CHECK_FALSE(scene.inside_solid(leaf.position));
      landed_at.push_back(leaf.position);
    }
    // Landed leaves never move again, whatever the wind.
    const fluid::MacVelocity gale = uniform_wind(scene.spec, {30.0, -10.0, 5.0});
    run(ref, scene.spec, scene.solid, gale, 20);
    for (int j = 0; j < n; ++j) {
      CHECK(ref.leaf(j).position == landed_at[std::size_t(j)]);
      CHECK(ref.leaf(j).state == trees::LeafState::landed);
    }
  }
}

TEST_CASE("leaves: leaves exit through open sides and wrap through periodic ones", "[leaves]") {
  trees::LeafSettings settings;
  settings.fraction = 0.05;
  fluid::GridSpec spec = grid(16, 8, 40, {0.0, 0.0, 0.0});
  const fluid::MacVelocity wind = uniform_wind(spec, {8.0, 0.0, 0.0});
  const double start_x = 14.0, top = 35.0;  // 2 m from the east side, high above the ground
  const int steps = 20;                     // 1 s: 8 m downwind, 1.3 m down

  SECTION("an open east side") {
    trees::LeafReference ref = small_forest(settings);
    launch(ref, [&](int j) { return Eigen::Vector3d(start_x, 4.0, top - 0.01 * j); });
    run(ref, spec, {}, wind, steps);
    const trees::LeafCounts counts = ref.counts();
    CHECK(counts.exited == ref.count());
    CHECK(counts.flying == 0);
    CHECK(counts.shed == ref.count());
    for (int j = 0; j < ref.count(); ++j) CHECK(ref.leaf(j).position.x() >= spec.nx * spec.h);
  }

  SECTION("periodic west and east sides") {
    spec.boundary[FW_FACE_WEST] = spec.boundary[FW_FACE_EAST] = fluid::BoundaryType::periodic;
    trees::LeafReference ref = small_forest(settings);
    launch(ref, [&](int j) { return Eigen::Vector3d(start_x, 4.0, top - 0.01 * j); });
    run(ref, spec, {}, wind, steps);
    CHECK(ref.counts().flying == ref.count());
    CHECK(ref.counts().exited == 0);
    for (int j = 0; j < ref.count(); ++j) {
      const double x = ref.leaf(j).position.x();
      CHECK(x >= 0.0);
      CHECK(x < start_x - 2.0);  // wrapped: it went east about 8 m and came in again from the west
    }
  }
}

TEST_CASE("leaves: shedding rises strictly with the wind", "[leaves]") {
  const trees::LeafSettings settings;  // default strengths: median 1 N
  const fluid::GridSpec spec = grid(20, 20, 12, {-10.0, -10.0, 0.0});
  std::vector<long> shed;
  long total = 0;
  for (const double speed : {10.0, 20.0, 30.0}) {
    trees::LeafReference ref = small_forest(settings);
    total = ref.count();
    run(ref, spec, {}, uniform_wind(spec, {speed, 0.0, 0.0}), 5);
    shed.push_back(ref.counts().shed);
    INFO("wind " << speed << " m/s: " << shed.back() << " of " << total << " shed");
    CHECK(shed.back() == ref.counts().flying + ref.counts().landed + ref.counts().exited);
    CHECK(ref.counts().attached + shed.back() == total);
  }
  INFO("shed at 10, 20, 30 m/s: " << shed[0] << ", " << shed[1] << ", " << shed[2] << " of " << total);
  CHECK(shed[0] < shed[1]);
  CHECK(shed[1] < shed[2]);
  CHECK(shed[2] < total);
}

namespace {

// RMS over the leaves and 4 s of steps of theta (pseudo-branch) or of the normal's angle from its rest
// (stochastic), in a uniform wind along x.
double flutter_rms(trees::FlutterModel model, double speed) {
  trees::LeafSettings settings;
  settings.model = model;
  settings.petiole_strength = 1e9;  // N: nothing is shed
  settings.fraction = 0.2;
  trees::LeafReference ref = small_forest(settings);
  const fluid::GridSpec spec = grid(20, 20, 12, {-10.0, -10.0, 0.0});
  const fluid::MacVelocity wind = uniform_wind(spec, {speed, 0.0, 0.0});
  const int steps = 80;
  double sum = 0.0;
  for (int n = 0; n < steps; ++n) {
    ref.step(spec, {}, wind, n * kDt, kDt);
    for (int j = 0; j < ref.count(); ++j) {
      const trees::WorldLeaf& leaf = ref.leaf(j);
      REQUIRE(leaf.state == trees::LeafState::attached);
      const double angle = model == trees::FlutterModel::pseudo_branch
                               ? leaf.theta
                               : std::acos(std::clamp(leaf.normal.dot(leaf.rest_normal), -1.0, 1.0));
      sum += angle * angle;
    }
  }
  return std::sqrt(sum / (double(steps) * ref.count()));
}

}  // namespace

TEST_CASE("leaves: the flutter grows with the wind speed", "[leaves]") {
  for (const auto model : {trees::FlutterModel::pseudo_branch, trees::FlutterModel::stochastic}) {
    const double slow = flutter_rms(model, 3.0), mid = flutter_rms(model, 6.0),
                 fast = flutter_rms(model, 12.0);
    INFO(trees::to_string(model) << ": RMS angle at 3, 6, 12 m/s: " << slow << ", " << mid << ", " << fast
                                 << " rad");
    CHECK(slow > 0.0);
    CHECK(slow < mid);
    CHECK(mid < fast);
    CHECK(fast <= 0.5 * std::numbers::pi);  // the clamp of theta; the stochastic angles stay below it too
  }
}

TEST_CASE("leaves: the pseudo-branch settles at its static balance for any dt", "[leaves]") {
  trees::LeafSettings settings;
  settings.petiole_strength = 1e9;  // N: nothing is shed
  settings.damping_ratio = 0.5;     // settles within a second: decay rate zeta omega = 9.4 1/s
  settings.fraction = 0.1;
  const fluid::GridSpec spec = grid(20, 20, 12, {-10.0, -10.0, 0.0});
  const double speed = 0.2;  // m/s: a small torque, so that theta stays small and nearly linear in it
  const fluid::MacVelocity wind = uniform_wind(spec, {speed, 0.0, 0.0});
  const Eigen::Vector3d u(double(float(speed)), 0.0, 0.0);  // the grid stores float32 velocities
  const double omega = 2.0 * std::numbers::pi * settings.frequency;

  trees::LeafReference coarse = small_forest(settings), fine = coarse;
  run(coarse, spec, {}, wind, 100, kDt);  // 5 s: e^-47 of the start is left
  run(fine, spec, {}, wind, 1000, 0.1 * kDt);
  REQUIRE(coarse.count() > 0);
  double largest = 0.0;
  for (int j = 0; j < coarse.count(); ++j) {
    const trees::WorldLeaf& leaf = coarse.leaf(j);
    const Eigen::Vector3d n = Eigen::AngleAxisd(leaf.theta, leaf.hinge) * leaf.rest_normal;
    const Eigen::Vector3d c = leaf.hinge.cross(Eigen::AngleAxisd(leaf.theta, leaf.hinge) * leaf.petiole);
    auto torque = [&](const Eigen::Vector3d& normal) {  // docs/leaves.md at theta' = 0
      const double un = u.dot(normal);
      return leaf.lever * 0.5 * trees::kAirDensity * trees::kLeafNormalForceCoefficient * leaf.area *
             std::abs(un) * un * c.dot(n);
    };
    const double inertia = leaf.mass * (leaf.lever * leaf.lever + leaf.side * leaf.side / 12.0);
    const double balance = torque(n) / (inertia * omega * omega);
    const double linear = torque(leaf.rest_normal) / (inertia * omega * omega);
    INFO("leaf " << j << ": theta " << leaf.theta << ", balance " << balance << ", linear " << linear);
    CHECK(std::abs(leaf.theta_rate) < 1e-12);                          // at rest, up to round-off
    CHECK(leaf.theta == Approx(balance).epsilon(1e-9).margin(1e-15));  // the fixed point of the step
    // The wind's turning of the blade (the aerodynamic stiffness, ~ 2% of I omega^2 at 0.2 m/s) moves the
    // balance off the rest torque's: 5% bounds it.
    CHECK(leaf.theta == Approx(linear).epsilon(0.05).margin(1e-15));
    CHECK(fine.leaf(j).theta == Approx(leaf.theta).epsilon(1e-9).margin(1e-15));  // dt does not matter
    largest = std::max(largest, std::abs(leaf.theta));
  }
  CHECK(largest > 0.0);
}

TEST_CASE("leaves: a pseudo-branch swings freely at the leaf frequency", "[leaves]") {
  trees::LeafSettings settings;
  settings.fraction = 0.02;
  trees::LeafReference ref = small_forest(settings);
  REQUIRE(ref.count() > 0);
  const fluid::GridSpec spec = grid(20, 20, 12, {-10.0, -10.0, 0.0});
  const fluid::MacVelocity still = uniform_wind(spec, Eigen::Vector3d::Zero());
  constexpr double kStartAngle = 0.05, kStep = 1e-3, kDuration = 3.0;  // rad, s, s: nine periods
  for (int j = 0; j < ref.count(); ++j) ref.leaf(j).theta = kStartAngle;
  std::vector<std::vector<double>> crossings(std::size_t(ref.count()));
  for (int n = 0; n < int(kDuration / kStep); ++n) {
    std::vector<double> before;
    for (int j = 0; j < ref.count(); ++j) before.push_back(ref.leaf(j).theta);
    ref.step(spec, {}, still, n * kStep, kStep);
    for (int j = 0; j < ref.count(); ++j) {
      const double a = before[std::size_t(j)], b = ref.leaf(j).theta;
      if ((a > 0.0) != (b > 0.0)) crossings[std::size_t(j)].push_back((n + a / (a - b)) * kStep);
    }
  }
  const double damped = settings.frequency * std::sqrt(1.0 - settings.damping_ratio * settings.damping_ratio);
  for (const auto& times : crossings) {
    REQUIRE(times.size() >= 10);
    const double measured = 0.5 * double(times.size() - 1) / (times.back() - times.front());
    INFO("free swing " << measured << " Hz, damped petiole " << damped << " Hz");
    // The air's damping of the blade's own motion (quadratic, some zeta 0.05 at the start and less as it
    // decays) lowers the frequency by a few tenths of a percent: 1% bounds it.
    CHECK(measured == Approx(damped).epsilon(0.01));
  }
}

TEST_CASE("leaves: the Radau step is third order and damps motions far faster than the step", "[leaves]") {
  // x'' + gamma x' + w2 x = f over one second, against the exact step (exact_modal_step is exact for a held
  // f): the error at the end falls as dt^3.
  constexpr double kOmega = 2.0 * std::numbers::pi * 3.0, kGamma = 2.0 * 0.05 * kOmega, kForce = 4.0;
  auto error_after_one_second = [&](int steps) {
    const double dt = 1.0 / steps;
    double x = 0.1, v = 0.0, xe = 0.1, ve = 0.0;
    for (int n = 0; n < steps; ++n) {
      trees::radau_oscillator_step(x, v, kForce, kOmega * kOmega, kGamma, dt);
      trees::exact_modal_step(xe, ve, kForce, kOmega, kGamma, dt);
    }
    return std::abs(x - xe);
  };
  const double coarse = error_after_one_second(100), fine = error_after_one_second(200);
  INFO("error " << coarse << " at dt 10 ms, " << fine << " at 5 ms");
  // A third-order method: halving dt divides the error by 8; 6..10 allows the next order's share.
  CHECK(coarse / fine > 6.0);
  CHECK(coarse / fine < 10.0);

  // Free swing at w dt = 0.4 (a 3 Hz leaf at the storm's 21 ms step): the amplitude lost per step is the
  // method's damping, |R(0.4 i)| = 0.99966, below 1e-3 of the amplitude.
  double x = 1.0, v = 0.0;
  const double dt = 0.4 / kOmega;
  const int per_period = int(std::round(2.0 * std::numbers::pi / 0.4));
  for (int n = 0; n < 10 * per_period; ++n) trees::radau_oscillator_step(x, v, 0.0, kOmega * kOmega, 0.0, dt);
  const double amplitude = std::sqrt(x * x + v * v / (kOmega * kOmega));
  CHECK(std::pow(amplitude, 1.0 / (10 * per_period)) > 1.0 - 1e-3);
  CHECK(amplitude <= 1.0);  // it never gains energy

  // A motion 100 times faster than the step: one step leaves |R(100 i)| ~ 2/100 of it, where the
  // trapezoidal rule would keep all of it and flip its sign (ringing). 0.03 bounds 0.02.
  double stiff_x = 1.0, stiff_v = 0.0;
  trees::radau_oscillator_step(stiff_x, stiff_v, 0.0, 1e4, 0.0, 1.0);
  CHECK(std::abs(stiff_x) < 0.03);
  CHECK(std::abs(stiff_v) < 0.03 * 100.0);
}
