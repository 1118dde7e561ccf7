// trees/BranchStemLoads: the stem loads of the element trees. A rigid-bodies pole at its static equilibrium
// in a uniform wind carries the beam's moments; its joints' moments once its motion has died out are the
// same; a branched tree's joints at each stem node carry the statics of every element load above the node;
// the springs carry their own element's load; and the weight's moment follows the pose.
#include "trees/BranchStemLoads.hpp"

#include <catch2/catch.hpp>

#include <algorithm>

#include <cmath>
#include <numbers>
#include <vector>

#include "tests/support/BranchModels.hpp"
#include "tests/support/SmallSpecies.hpp"
#include "trees/BranchPose.hpp"
#include "trees/RigidBranches.hpp"
#include "trees/SpringBranches.hpp"
#include "trees/StemLoads.hpp"

namespace {

using fw::test::uniform_loads;
using fw::trees::BranchElements;
using fw::trees::BranchStem;
using fw::trees::Material;
using fw::trees::Skeleton;
using fw::trees::SkeletonNode;
using fw::trees::TreeDynamics;
using fw::trees::WindBasisSettings;

const Material kWood{1.0e10, 3.85e9, 900.0};
constexpr double kGravity = fw::trees::kGravity;

// A uniform vertical cylinder of n elements.
constexpr double kPoleLength = 10.0, kPoleRadius = 0.05;
Skeleton pole(int n) {
  std::vector<SkeletonNode> nodes;
  for (int i = 0; i <= n; ++i)
    nodes.push_back({i - 1, Eigen::Vector3d(0.0, 0.0, kPoleLength * i / n), kPoleRadius});
  return Skeleton::from_nodes(std::move(nodes));
}

// The Euler-Bernoulli cantilever of length L, bending stiffness EI and mass per metre mu under a uniform load
// w: its deflection u(x) = w x^2 (6 L^2 - 4 L x + x^2) / (24 EI), and the moment its weight adds on that
// deflection at x, mu g int_x^L (u(xi) - u(x)) dxi.
struct Beam {
  double L, EI, mu, w;
  double u(double x) const { return w * x * x * (6.0 * L * L - 4.0 * L * x + x * x) / (24.0 * EI); }
  double u_integral(double x) const {  // int_0^x u
    return w * (2.0 * L * L * x * x * x - L * x * x * x * x + x * x * x * x * x / 5.0) / (24.0 * EI);
  }
  double wind_moment(double x) const { return 0.5 * w * (L - x) * (L - x); }
  double weight_moment(double x) const {
    return mu * kGravity * (u_integral(L) - u_integral(x) - (L - x) * u(x));
  }
};

struct PoleErrors {
  double elastic = 0.0;       // largest |elastic - w (L - x)^2 / 2| over the root's w L^2 / 2
  double weight = 0.0;        // largest |weight - the beam's| over the root's weight moment
  double total = 0.0;         // largest |bending - the beam's sum| over the root's sum
  double weight_share = 0.0;  // the root's weight moment over its wind moment
};

// A rigid-bodies pole of n elements in a uniform wind along x, its moments at `angles` against the beam's.
PoleErrors pole_errors(int n, const std::vector<Eigen::Vector3d>& angles, const BranchElements& elements,
                       const Skeleton& skeleton, double w) {
  const BranchStem stem = BranchStem::of(skeleton);
  const auto moments =
      fw::trees::branch_stem_moments(skeleton, elements, stem, TreeDynamics::rigid_bodies, 1.0, angles);
  const double area = std::numbers::pi * kPoleRadius * kPoleRadius;
  const Beam beam{kPoleLength, kWood.youngs_modulus * area * kPoleRadius * kPoleRadius / 4.0,
                  kWood.density * area, w};
  PoleErrors e;
  // More nodes than kMaxStemSections: the sections are spread along the pole, each at its node's height.
  REQUIRE(stem.section_count() == std::min(n, fw::trees::kMaxStemSections));
  for (int j = 0; j < stem.section_count(); ++j) {
    const double x = skeleton.node(stem.section_nodes()[std::size_t(j)]).position.z();
    // The wind along +x bends the pole about +y; nothing else.
    e.elastic = std::max(e.elastic, std::abs(moments.elastic(1, j) - beam.wind_moment(x)));
    e.weight = std::max(e.weight, std::abs(moments.weight(1, j) - beam.weight_moment(x)));
    e.total = std::max(e.total, std::abs(moments.bending(j) - beam.wind_moment(x) - beam.weight_moment(x)));
    CHECK(std::abs(moments.elastic(0, j)) + std::abs(moments.elastic(2, j)) < 1e-9 * beam.wind_moment(0.0));
  }
  e.elastic /= beam.wind_moment(0.0);
  e.weight /= beam.weight_moment(0.0);
  e.total /= beam.wind_moment(0.0) + beam.weight_moment(0.0);
  e.weight_share = beam.weight_moment(0.0) / beam.wind_moment(0.0);
  CHECK(moments.root == Approx(moments.bending(0)).epsilon(1e-12));  // a vertical pole: all horizontal
  return e;
}

}  // namespace

TEST_CASE("BranchStemLoads: a rigid-bodies pole at rest in a uniform wind carries the beam's moments",
          "[trees]") {
  // 5 m/s: the tip bends by 5 mm a metre, so that the pose's finite rotations (a relative (angle)^2 / 6,
  // 6e-6 at the tip's 0.006 rad) leave the joints' lumping alone in the weight's error. The weight's share
  // does not depend on the wind (mu g L^3 / (10 EI): 14%).
  const Eigen::Vector3d wind(5.0, 0.0, 0.0);
  double previous = 0.0;
  for (const int n : {20, 40}) {
    const Skeleton skeleton = pole(n);
    const BranchElements elements = BranchElements::of(skeleton, kWood, WindBasisSettings{});
    const std::vector<Eigen::Vector3d> loads = uniform_loads(elements, wind);
    const double w = loads[1].norm() / elements[1].length;
    const fw::trees::RigidBranches rigid(elements, 1.0, 0.0);
    const PoleErrors e = pole_errors(n, rigid.equilibrium(loads).angle, elements, skeleton, w);
    WARN(n << " elements: elastic error " << e.elastic << ", weight error " << e.weight << ", total "
           << e.total << " (weight share " << e.weight_share << ")");
    // The joint moment at equilibrium is the statics of the element loads, at their centres: the midpoint
    // rule integrates w (xi - x) exactly, so only rounding is left.
    CHECK(e.elastic < 1e-12);
    // The deflection the weight acts on is the joints' lumped curvature: the trapezoidal rule of
    // int M (x - xi) / EI, whose error is (h / L)^2 = 1 / n^2 of the tip's (the tip deflection under a
    // uniform load is (1 + 1/n^2) the beam's), and the lumped masses are a trapezoidal rule of the weight's
    // integral. Measured: 1.66 / n^2 of the root's weight moment (4.2e-3 at n = 20, 1.0e-3 at n = 40).
    CHECK(e.weight < 2.0 / (n * n));
    CHECK(e.total < 2.0 / (n * n) * e.weight_share);
    CHECK(e.weight_share == Approx(0.14).epsilon(0.05));
    // Second order: halving the elements quarters the error.
    if (previous > 0.0) CHECK(previous / e.weight == Approx(4.0).epsilon(0.05));
    previous = e.weight;
  }
}

TEST_CASE(
    "BranchStemLoads: a rigid-bodies pole's joint moments settle on the static ones as its sway dies out",
    "[trees]") {
  constexpr int n = 20;
  const Skeleton skeleton = pole(n);
  const BranchElements elements = BranchElements::of(skeleton, kWood, WindBasisSettings{});
  const std::vector<Eigen::Vector3d> loads = uniform_loads(elements, Eigen::Vector3d(5.0, 0.0, 0.0));
  // Damping ratio 0.7 of a 2.9 rad/s first mode: the slowest decay, the stiffness-proportional damping's
  // overdamped high modes at omega_1 / (2 zeta) = 2.1 /s, leaves e^-62 of the start after 30 s.
  const fw::trees::RigidBranches rigid(elements, 1.0, fw::trees::rigid_damping(0.7, 2.9));
  const BranchStem stem = BranchStem::of(skeleton);
  const auto at_rest = fw::trees::branch_stem_moments(skeleton, elements, stem, TreeDynamics::rigid_bodies,
                                                      1.0, rigid.equilibrium(loads).angle);
  fw::trees::RigidBranchState state{
      std::vector<Eigen::Vector3d>(std::size_t(n + 1), Eigen::Vector3d::Zero()),
      std::vector<Eigen::Vector3d>(std::size_t(n + 1), Eigen::Vector3d::Zero())};
  double overshoot = 0.0;
  for (int step = 0; step < 1500; ++step) {
    rigid.step(loads, 0.02, state);
    const auto moving = fw::trees::branch_stem_moments(skeleton, elements, stem, TreeDynamics::rigid_bodies,
                                                       1.0, state.angle);
    overshoot = std::max(overshoot, moving.bending(0) / at_rest.bending(0));
  }
  const auto settled =
      fw::trees::branch_stem_moments(skeleton, elements, stem, TreeDynamics::rigid_bodies, 1.0, state.angle);
  WARN("settled: " << (settled.bending - at_rest.bending).norm() / at_rest.bending.norm()
                   << " off the static moments; the root's largest was " << overshoot << " of its static");
  CHECK((settled.bending - at_rest.bending).norm() < 1e-9 * at_rest.bending.norm());
  // The sudden wind's overshoot reached the root: the joints carry the dynamics, not only the wind's statics.
  CHECK(overshoot > 1.02);
}

TEST_CASE(
    "BranchStemLoads: a branched tree's joints at each stem node carry the statics of every element load "
    "above it, and the elements' masses at their centres the lumped masses' weight moment",
    "[trees]") {
  const Skeleton skeleton = fw::test::small_broadleaf();
  WindBasisSettings drag;
  drag.leaf_area_index = 3.0;
  const BranchElements elements = BranchElements::of(skeleton, kWood, drag);
  const BranchStem stem = BranchStem::of(skeleton);
  constexpr double s = 1.3;
  const double s3 = s * s * s;
  const int n = elements.size(), J = stem.section_count();
  // The stem and its sections are the modal model's.
  const std::vector<int> path = fw::trees::stem_path(skeleton);
  CHECK(stem.path() == path);
  const std::vector<int> indices =
      fw::trees::stem_section_indices(fw::trees::stem_arc_length(skeleton, path));
  REQUIRE(J == int(indices.size()));
  for (int i = 0; i < J; ++i) CHECK(stem.section_nodes()[std::size_t(i)] == path[std::size_t(indices[i])]);
  int side_joints = 0;
  for (int j = 1; j < n; ++j) {
    const int section = stem.joint_sections()[std::size_t(j)];
    if (section < 0) continue;
    CHECK(elements[j].parent_node == stem.section_nodes()[std::size_t(section)]);
    side_joints += std::find(path.begin(), path.end(), elements[j].node) == path.end();
  }
  CHECK(side_joints > 0);  // side branches leave the stem nodes: their joints are in the sections' sums

  // At rest in a wind oblique to the tree, at scale s (the loads of its elements, s^2 each).
  std::vector<Eigen::Vector3d> loads = uniform_loads(elements, Eigen::Vector3d(9.0, -4.0, 1.0));
  for (Eigen::Vector3d& f : loads) f *= s * s;
  const fw::trees::RigidBranches rigid(elements, s, 0.0);
  const std::vector<Eigen::Vector3d> angles = rigid.equilibrium(loads).angle;
  const auto moments =
      fw::trees::branch_stem_moments(skeleton, elements, stem, TreeDynamics::rigid_bodies, s, angles);
  const Eigen::MatrixX3d u = fw::trees::branch_displacements(elements, s, angles);

  double elastic_error = 0.0, weight_error = 0.0, largest = 0.0, largest_weight = 0.0;
  for (int i = 0; i < J; ++i) {
    const int node = stem.section_nodes()[std::size_t(i)];
    const Eigen::Vector3d x = s * skeleton.node(node).position;
    const Eigen::Vector3d u_i = u.row(node).transpose();
    Eigen::Vector3d statics = Eigen::Vector3d::Zero(), weight = Eigen::Vector3d::Zero();
    for (int j = 1; j < n; ++j) {
      if (stem.element_sections()[std::size_t(j)] < i) continue;  // not above section i
      const fw::trees::BranchElement& e = elements[j];
      statics += (s * e.centre - x).cross(loads[std::size_t(j)]);
      const Eigen::Vector3d centre = 0.5 * (u.row(e.node) + u.row(e.parent_node)).transpose();
      weight += (centre - u_i).cross(Eigen::Vector3d(0.0, 0.0, -s3 * e.mass * kGravity));
    }
    elastic_error = std::max(elastic_error, (moments.elastic.col(i) - statics).norm());
    weight_error = std::max(weight_error, (moments.weight.col(i) - weight).norm());
    largest = std::max(largest, statics.norm());
    largest_weight = std::max(largest_weight, weight.norm());
  }
  WARN("statics: " << elastic_error / largest << "; weight at the centres: " << weight_error / largest_weight
                   << " (largest weight moment " << largest_weight / largest << " of the wind's)");
  CHECK(elastic_error < 1e-12 * largest);
  CHECK(weight_error < 1e-12 * largest_weight);
  CHECK(largest_weight > 1e-3 * largest);
}

TEST_CASE(
    "BranchStemLoads: a springs pole carries only each element's own load, w L_e^2 at every section, and its "
    "weight acts on the pose's finite bend",
    "[trees]") {
  constexpr int n = 20;
  const Skeleton skeleton = pole(n);
  // Wood far softer than a tree's, as a user after a visible bend sets it: every element bends by 0.04 rad.
  const Material soft{6.0e5, 2.3e5, 900.0};
  const BranchElements elements = BranchElements::of(skeleton, soft, WindBasisSettings{});
  const std::vector<Eigen::Vector3d> loads = uniform_loads(elements, Eigen::Vector3d(8.0, 0.0, 0.0));
  fw::trees::SpringSettings settings;
  settings.sway_amplitude = 0.0;  // no sine: the steady bend
  const std::vector<Eigen::Vector3d> angles =
      fw::trees::spring_angles(elements, settings, 1.0, loads, fw::trees::spring_phases(3, n + 1), 0.0);
  const double h = kPoleLength / n, w = loads[1].norm() / h, theta = angles[1].norm();
  REQUIRE(theta > 0.02);
  REQUIRE(theta < settings.max_angle_deg * std::numbers::pi / 180.0);
  const BranchStem stem = BranchStem::of(skeleton);
  const auto moments =
      fw::trees::branch_stem_moments(skeleton, elements, stem, TreeDynamics::springs, 1.0, angles);
  // Element i is turned by i theta from the vertical (every joint by theta about y), so node k sits
  // sum_{i <= k} h sin(i theta) downwind; node masses rho A h, the top's half.
  const double mass = kWood.density * std::numbers::pi * kPoleRadius * kPoleRadius * h;
  std::vector<double> X(std::size_t(n + 1), 0.0);
  for (int k = 1; k <= n; ++k) X[std::size_t(k)] = X[std::size_t(k) - 1] + h * std::sin(k * theta);
  for (int j = 0; j < stem.section_count(); ++j) {
    INFO("section " << j);
    const int node = stem.section_nodes()[std::size_t(j)];  // the pole's node i is its i-th stem node
    CHECK(moments.elastic(1, j) == Approx(w * h * h).epsilon(1e-12));
    double weight = 0.0;
    for (int k = node + 1; k <= n; ++k)
      weight += (k == n ? 0.5 : 1.0) * mass * kGravity * (X[std::size_t(k)] - X[std::size_t(node)]);
    CHECK(moments.weight(1, j) == Approx(weight).epsilon(1e-12));
  }
  // Against the beam's w (L - x)^2 / 2, the root carries 2 / n^2 of it: not the tree's load.
  CHECK(moments.elastic(1, 0) / (0.5 * w * kPoleLength * kPoleLength) ==
        Approx(2.0 / (n * n)).epsilon(1e-12));

  // The largest bend's cap caps the moment: k L^2 tan(theta_max).
  const std::vector<Eigen::Vector3d> storm = uniform_loads(elements, Eigen::Vector3d(100.0, 0.0, 0.0));
  const auto capped = fw::trees::branch_stem_moments(
      skeleton, elements, stem, TreeDynamics::springs, 1.0,
      fw::trees::spring_angles(elements, settings, 1.0, storm, fw::trees::spring_phases(3, n + 1), 0.0));
  const double cap =
      elements[1].spring_stiffness * h * h * std::tan(settings.max_angle_deg * std::numbers::pi / 180.0);
  CHECK(capped.elastic(1, 0) == Approx(cap).epsilon(1e-12));
  CHECK(storm[1].norm() * h > 10.0 * cap);
}

TEST_CASE("BranchStemLoads: a scaled tree's loads are those of the tree grown by s against its own strength",
          "[trees]") {
  const Skeleton skeleton = fw::test::asymmetric_skeleton();
  const WindBasisSettings drag;
  const BranchElements elements = BranchElements::of(skeleton, kWood, drag);
  constexpr double s = 1.4;
  const Skeleton grown = skeleton.transformed(Eigen::Matrix3d::Identity(), Eigen::Vector3d::Zero(), s);
  const BranchElements grown_elements = BranchElements::of(grown, kWood, drag);
  const auto strength = fw::trees::strength_preset(fw::trees::StrengthPreset::scots_pine);
  const BranchStem stem = BranchStem::of(skeleton);
  // The same angles bend both: the scaled tree by the scaled stiffness, the grown one by its own.
  std::vector<Eigen::Vector3d> angles(std::size_t(elements.size()), Eigen::Vector3d::Zero());
  for (std::size_t j = 1; j < angles.size(); ++j)
    angles[j] = Eigen::Vector3d(0.02 * std::sin(double(j)), 0.03 * std::cos(3.0 * double(j)), 0.004);
  for (const TreeDynamics model : {TreeDynamics::rigid_bodies, TreeDynamics::springs}) {
    const auto critical = [&](const Skeleton& tree) {
      fw::trees::BeamModel beam(tree, kWood);
      fw::trees::ModalSettings modal;
      modal.mode_count = 3;
      return fw::trees::critical_moments(
          fw::trees::StemLoads::compute(tree, beam, fw::trees::ModalBasis::compute(beam, modal)), strength);
    };
    const auto load = fw::trees::branch_tree_load(
        fw::trees::branch_stem_moments(skeleton, elements, stem, model, s, angles), critical(skeleton), s);
    const auto direct = fw::trees::branch_tree_load(
        fw::trees::branch_stem_moments(grown, grown_elements, BranchStem::of(grown), model, 1.0, angles),
        critical(grown), 1.0);
    CHECK((load.utilisation - direct.utilisation).norm() < 1e-9 * direct.utilisation.norm());
    CHECK(load.overturning == Approx(direct.overturning).epsilon(1e-9));
    CHECK(load.root_moment == Approx(direct.root_moment).epsilon(1e-9));
    CHECK(direct.largest() > 0.0);
  }
}
