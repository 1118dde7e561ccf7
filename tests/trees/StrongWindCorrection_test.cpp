// trees::StrongWindCorrection, Diener's quadratic strong-wind correction (2008, section 5.2): element lengths
// under large loads, small-amplitude behaviour, the fit, scaling and yaw through the oracle ForestReference,
// the packing for the device, and bad arguments.
#include "trees/StrongWindCorrection.hpp"

#include <catch2/catch.hpp>

#include <Eigen/Geometry>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <string>
#include <vector>

#include "tests/support/SmallSpecies.hpp"
#include "trees/Forest.hpp"
#include "trees/ForestReference.hpp"
#include "trees/SpeciesBasis.hpp"
#include "trees/TreeGenerator.hpp"

using namespace fw;
using trees::StrongWindCorrection;

namespace {

// Fraction of its length by which the issue's load bends a branch tip.
constexpr double kTipDeflection = 0.3;
// The issue's bound on element length errors under that load, relative to the rest length.
constexpr double kIssueLengthError = 0.01;
// With the length-restoring pass: each length is a sum of a few unit vectors times L in double, so rounding
// of the tree's size only (measured: below 1e-15).
constexpr double kRestoredLengthError = 1e-12;
// The pass moves a node by at most this fraction of the tip's deflection: Diener's pose nearly keeps lengths
// already, so restoring them is a small change (measured: 1.6% on the cantilever, 2.2-4.5% on the broadleaf,
// where Diener left the most stretch).
constexpr double kPassMovesAtMost = 0.1;

// A tapering vertical cantilever (a sapling or a single branch) of 20 elements, 4 m long.
trees::Skeleton cantilever() {
  constexpr int kElements = 20;
  constexpr double kLength = 4.0, kBaseRadius = 0.05, kTipRadius = 0.02;
  std::vector<trees::SkeletonNode> nodes{{-1, {0.0, 0.0, 0.0}, kBaseRadius}};
  for (int k = 1; k <= kElements; ++k)
    nodes.push_back({k - 1,
                     {0.0, 0.0, kLength * k / kElements},
                     kBaseRadius + (kTipRadius - kBaseRadius) * k / kElements});
  return trees::Skeleton::from_nodes(std::move(nodes));
}

trees::SpeciesBasis species_of(const trees::Skeleton& skeleton, int modes) {
  trees::SpeciesSettings settings;
  settings.modal.mode_count = modes;
  settings.wind.samples = 3;
  return trees::SpeciesBasis::compute(skeleton, settings);
}

int highest_node(const trees::Skeleton& skeleton) {
  int top = 0;
  for (int k = 1; k < skeleton.size(); ++k)
    if (skeleton.node(k).position.z() > skeleton.node(top).position.z()) top = k;
  return top;
}

// max over elements of | |deformed element| / |rest element| - 1 |.
double max_length_error(const trees::Skeleton& skeleton, const Eigen::VectorXd& u) {
  double worst = 0.0;
  for (const auto& [parent, child] : skeleton.elements()) {
    const Eigen::Vector3d rest = skeleton.node(child).position - skeleton.node(parent).position;
    const Eigen::Vector3d deformed = rest + u.segment<3>(3 * child) - u.segment<3>(3 * parent);
    worst = std::max(worst, std::abs(deformed.norm() / rest.norm() - 1.0));
  }
  return worst;
}

// q scaled so that the linear displacement of `tip` is kTipDeflection * length.
Eigen::VectorXd scaled_to_tip(const trees::SpeciesBasis& sp, Eigen::VectorXd q, int tip, double length) {
  const Eigen::VectorXd u = sp.node_shapes() * q;
  return q * (kTipDeflection * length / u.segment<3>(3 * tip).norm());
}

// The static response q = f / omega^2 to a uniform wind `wind` (m/s) through the species' wind basis.
Eigen::VectorXd static_uniform_wind(const trees::SpeciesBasis& sp, const Eigen::Vector3d& wind) {
  const Eigen::MatrixX3d sampled = wind.transpose().replicate(sp.wind().sample_count(), 1);
  return sp.wind().modal_forces(sampled).cwiseQuotient(sp.modes().omega().cwiseAbs2());
}

double relative(const Eigen::MatrixXd& a, const Eigen::MatrixXd& b) {
  return (a - b).cwiseAbs().maxCoeff() / b.cwiseAbs().maxCoeff();
}

}  // namespace

TEST_CASE("StrongWindCorrection: the corrected walk keeps every element's rest length", "[strong-wind]") {
  const trees::Skeleton tree = test::small_broadleaf();
  const trees::SpeciesBasis sp = species_of(tree, 6);
  const Eigen::VectorXd q = Eigen::VectorXd::LinSpaced(6, 1.0, -0.5) * sp.strong_wind().fits()[0].q_max;
  const Eigen::VectorXd linear = sp.node_shapes() * q;
  const Eigen::VectorXd walked = StrongWindCorrection::corrected_deformation(tree, linear);
  INFO("linear: max length error " << max_length_error(tree, linear));
  CHECK(max_length_error(tree, linear) > 0.05);  // a strong pose, or the check below says nothing
  // Each length is a sum of a few unit vectors times L in double: rounding only.
  CHECK(max_length_error(tree, walked) < 1e-12);
  CHECK(walked.segment<3>(3 * tree.root()).norm() == 0.0);
  // At rest: L unit(rest) - rest is zero up to rounding of the tree's size (6 m).
  CHECK(StrongWindCorrection::corrected_deformation(tree, Eigen::VectorXd::Zero(3 * tree.size()))
            .cwiseAbs()
            .maxCoeff() < 1e-14);
}

TEST_CASE(
    "StrongWindCorrection: a load in the shape of one mode that bends the tip by 30% keeps lengths "
    "within 1%",
    "[strong-wind]") {
  for (const auto& [name, tree] :
       {std::pair{"cantilever", cantilever()}, std::pair{"broadleaf", test::small_broadleaf()}}) {
    const trees::SpeciesBasis sp = species_of(tree, 10);
    const int tip = highest_node(tree);
    for (int mode : {0, 1}) {  // the two sway modes
      Eigen::VectorXd q = Eigen::VectorXd::Zero(10);
      q(mode) = 1.0;
      q = scaled_to_tip(sp, q, tip, tree.height());
      const double linear = max_length_error(tree, sp.node_shapes() * q);
      const double diener = max_length_error(tree, sp.strong_wind().displacement(q));
      const double corrected = max_length_error(tree, sp.strong_wind().corrected_displacement(tree, q));
      WARN(name << ", mode " << mode << " alone, tip moved by 30% of the height: element length error "
                << corrected << " corrected, " << diener << " Diener's part alone, " << linear << " linear");
      CHECK(linear > 0.1);  // the load is strong: the linear pose stretches branches by > 10%
      // One mode is what Diener's per-mode fit is made for: within the issue's bound even without the pass.
      CHECK(diener <= kIssueLengthError);
      CHECK(corrected <= kRestoredLengthError);
    }
  }
}

TEST_CASE("StrongWindCorrection: a uniform wind that bends the tip by 30% keeps lengths within 1%",
          "[strong-wind]") {
  // The static response to a uniform wind mixes the sway modes with higher bending modes. Diener's per-mode
  // sum has no cross terms q_i q_j (the header's "Why the length-restoring pass") and alone leaves 1-2% on
  // the cantilever and 3-5% on the broadleaf; its bound below holds that measured improvement over the
  // linear pose with margin, so that a regression of the fit shows. The length-restoring pass then brings
  // every element back to its rest length, and moves nodes little: the pose stays Diener's.
  for (const auto& [name, tree, modes, bound] : {std::tuple{"cantilever", cantilever(), 6, 0.25},
                                                 std::tuple{"broadleaf", test::small_broadleaf(), 10, 0.6}}) {
    const trees::SpeciesBasis sp = species_of(tree, modes);
    const int tip = highest_node(tree);
    for (const Eigen::Vector3d& wind : {Eigen::Vector3d(8.0, 0.0, 0.0), Eigen::Vector3d(6.0, 6.0, 0.0)}) {
      const Eigen::VectorXd q = scaled_to_tip(sp, static_uniform_wind(sp, wind), tip, tree.height());
      const Eigen::VectorXd u_diener = sp.strong_wind().displacement(q);
      const Eigen::VectorXd u = sp.strong_wind().corrected_displacement(tree, q);
      const double linear = max_length_error(tree, sp.node_shapes() * q);
      const double diener = max_length_error(tree, u_diener);
      const double corrected = max_length_error(tree, u);
      // How far the pass moves a node, relative to the tip's linear deflection (30% of the height).
      const double moved = (u - u_diener).cwiseAbs().maxCoeff() / (kTipDeflection * tree.height());
      WARN(name << ", uniform wind (" << wind.transpose() << "), tip moved by 30% of the height: max element "
                << "length error " << corrected << " corrected, " << diener << " Diener's part alone, "
                << linear << " linear; the pass moves nodes by up to " << moved << " of the tip deflection");
      CHECK(linear > 0.1);
      CHECK(diener < bound * linear);
      CHECK(corrected <= kIssueLengthError);  // the issue's bound
      CHECK(corrected <= kRestoredLengthError);
      CHECK(moved < kPassMovesAtMost);
    }
  }
}

TEST_CASE("StrongWindCorrection: at small amplitudes the correction is q v + q^2 w, v within 5% of phi",
          "[strong-wind]") {
  const trees::Skeleton tree = test::small_broadleaf();
  const trees::SpeciesBasis sp = species_of(tree, 10);
  const StrongWindCorrection& c = sp.strong_wind();
  for (int i = 0; i < c.mode_count(); ++i) {
    INFO("mode " << i);
    const Eigen::VectorXd phi = sp.node_shapes().col(i);
    const Eigen::VectorXd v = c.linear_shapes().col(i), w = c.quadratic_shapes().col(i);
    CHECK((v - phi).norm() <= 0.05 * phi.norm());  // small motion changes by at most 5%
    CHECK(c.fits()[std::size_t(i)].shape_change == Approx((v - phi).norm() / phi.norm()));
    // u_c - u_lin = q (v - phi) + q^2 w + O(q^3) (q~ = q - b^2 q^3 / 3): what is left after the first two
    // terms, over q^2 |w|, tends to 1 like q / q_max.
    for (double fraction : {1e-2, 1e-3, 1e-4}) {
      const double q = fraction * c.fits()[std::size_t(i)].q_max;
      Eigen::VectorXd qs = Eigen::VectorXd::Zero(c.mode_count());
      qs(i) = q;
      const Eigen::VectorXd difference = c.displacement(qs) - sp.node_shapes() * qs;
      const double ratio = (difference - q * (v - phi)).norm() / (q * q * w.norm());
      INFO("q = " << fraction << " q_max: ratio " << ratio);
      // The O(q^3) remainder is b^2 q^3 |v| / 3 and the walk's own cubic terms: a few times q / q_max.
      CHECK(std::abs(ratio - 1.0) < 10.0 * fraction);
    }
  }
}

TEST_CASE("StrongWindCorrection: the fit matches the corrected trajectories far better than the linear modes",
          "[strong-wind]") {
  const trees::Skeleton tree = test::small_broadleaf();
  const auto start = std::chrono::steady_clock::now();
  const trees::SpeciesBasis sp = species_of(tree, 10);
  const double total = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  const StrongWindCorrection& c = sp.strong_wind();
  REQUIRE(c.mode_count() == 10);
  REQUIRE(c.node_count() == tree.size());
  for (int i = 0; i < c.mode_count(); ++i) {
    const trees::StrongWindModeFit& fit = c.fits()[std::size_t(i)];
    INFO("mode " << i << ": b q_max " << c.b()(i) * fit.q_max << ", residual " << fit.relative_residual
                 << ", linear " << fit.linear_relative_residual);
    CHECK(fit.q_max > 0.0);
    CHECK(c.b()(i) > 0.0);  // the arctan does work: b = 0 (q~ = q) is never the best
    // Measured: 0.5-1.3% of the trajectories missed against 12-16% for q phi.
    CHECK(fit.relative_residual < 0.02);
    CHECK(fit.relative_residual < 0.15 * fit.linear_relative_residual);
  }
  WARN("broadleaf, " << tree.size() << " nodes, 10 modes: fit residual of mode 0 "
                     << c.fits()[0].relative_residual << " (linear " << c.fits()[0].linear_relative_residual
                     << "); fit " << sp.timings().strong_wind << " s of " << total << " s for the species");
  // The root never moves.
  CHECK(c.linear_shapes().middleRows(3 * tree.root(), 3).norm() == 0.0);
  CHECK(c.quadratic_shapes().middleRows(3 * tree.root(), 3).norm() == 0.0);
}

TEST_CASE("StrongWindCorrection: a mode without translations gets v = w = 0 and b = 0", "[strong-wind]") {
  const trees::Skeleton tree = cantilever();
  const trees::SpeciesBasis sp = species_of(tree, 4);
  Eigen::MatrixXd shapes = sp.node_shapes();
  shapes.col(2).setZero();  // as the torsion of a straight pole shows its nodes
  const StrongWindCorrection c = StrongWindCorrection::fit(tree, shapes);
  CHECK(c.linear_shapes().col(2).norm() == 0.0);
  CHECK(c.quadratic_shapes().col(2).norm() == 0.0);
  CHECK(c.b()(2) == 0.0);
  CHECK(c.fits()[2].q_max == 0.0);
  CHECK(StrongWindCorrection::reparametrised(0.7, 0.0) == 0.7);
}

TEST_CASE("StrongWindCorrection: the scaled correction equals a fresh fit on the scaled species",
          "[strong-wind]") {
  const trees::SpeciesBasis sp = species_of(test::small_broadleaf(), 6);
  for (double s : {0.6, 1.45}) {
    INFO("scale " << s);
    const trees::SpeciesBasis grown = sp.scaled(s);  // carries sp.strong_wind().scaled(s)
    const StrongWindCorrection fresh =
        StrongWindCorrection::fit(grown.skeleton(), grown.node_shapes(), grown.settings().strong_wind);
    const StrongWindCorrection& scaled = grown.strong_wind();
    // The samples map one to one (the same beta = b q_max grid), but the residual is flat at its minimum:
    // rounding of the order of 1e-16 moves the golden-section answer by about its square root, relative to
    // beta (measured: 3e-7 in b, 4e-8 in v and w).
    CHECK(relative(scaled.b(), fresh.b()) < 1e-6);
    CHECK(relative(scaled.linear_shapes(), fresh.linear_shapes()) < 1e-6);
    CHECK(relative(scaled.quadratic_shapes(), fresh.quadratic_shapes()) < 1e-6);
    CHECK(scaled.fits()[0].q_max == Approx(fresh.fits()[0].q_max).epsilon(1e-12));
  }
}

TEST_CASE(
    "ForestReference: the corrected deformation of an instance of scale s and yaw psi is the grown "
    "species' turned by psi",
    "[strong-wind]") {
  const trees::SpeciesBasis sp = species_of(test::small_broadleaf(), 6);
  for (auto [s, yaw] : {std::pair{0.6, 0.8}, std::pair{1.45, -2.3}}) {
    INFO("scale " << s << ", yaw " << yaw);
    const trees::Forest instance({sp}, {{0, {3.0, -1.0, 0.0}, yaw, s}});
    const trees::Forest grown({sp.scaled(s)}, {{0, {3.0, -1.0, 0.0}, 0.0, 1.0}});
    // Large amplitudes, where the arctan and w matter: up to q_max of the grown tree.
    Eigen::VectorXd q(6);
    for (int i = 0; i < 6; ++i)
      q(i) = (i % 2 ? -0.8 : 0.6) * grown.species()[0].strong_wind().fits()[std::size_t(i)].q_max;
    const Eigen::MatrixX3d u = trees::ForestReference(instance).displacements(q, true);
    const Eigen::MatrixX3d u_grown = trees::ForestReference(grown).displacements(q, true);
    const Eigen::Matrix3d r = Eigen::AngleAxisd(yaw, Eigen::Vector3d::UnitZ()).toRotationMatrix();
    // Two routes through the same doubles (s^-5/2 q and s v against s^-3/2 v, s^-5/2 b): rounding only.
    CHECK(relative(u, u_grown * r.transpose()) < 1e-12);
    // And the correction matters at these amplitudes: it moves nodes by more than 5% of the largest motion.
    CHECK(relative(trees::ForestReference(instance).displacements(q, false), u) > 0.05);

    // A species solved afresh from the grown skeleton (its modes may differ in sign: q, v flip, w and b do
    // not) deflects the same under a uniform wind, corrected as well.
    const trees::SpeciesBasis fresh = species_of(
        test::small_broadleaf().transformed(Eigen::Matrix3d::Identity(), Eigen::Vector3d::Zero(), s), 6);
    const Eigen::Vector3d wind(9.0, 3.0, 0.0);
    const Eigen::VectorXd q_fresh = static_uniform_wind(fresh, wind);
    const Eigen::VectorXd q_grown = static_uniform_wind(grown.species()[0], wind);
    const Eigen::VectorXd u_fresh = fresh.strong_wind().displacement(q_fresh);
    const Eigen::VectorXd u_scaled = grown.species()[0].strong_wind().displacement(q_grown);
    // Two eigen solves agree to ~1e-8 in the shapes; the fits amplify that little.
    CHECK(relative(u_fresh, u_scaled) < 1e-6);
  }
}

// The cantilever numbered from the tip down: every parent has a larger index than its children.
trees::Skeleton cantilever_from_the_tip() {
  const trees::Skeleton upright = cantilever();
  const int last = upright.size() - 1;
  std::vector<trees::SkeletonNode> nodes(std::size_t(upright.size()));
  for (int k = 0; k <= last; ++k) {
    const trees::SkeletonNode& node = upright.node(k);
    nodes[std::size_t(last - k)] = {node.parent < 0 ? -1 : last - node.parent, node.position, node.radius};
  }
  return trees::Skeleton::from_nodes(std::move(nodes));
}

// Every walk entry of species `s` of `p` against the species `sp`: the walk is a permutation of the nodes
// with parents before children, and the strong-wind arrays hold each entry's element (node minus parent, the
// root's rows taken as zero) in the blocked layout of ForestPacking.
void check_strong_wind_packing(const trees::ForestPacking& p, int s, const trees::SpeciesBasis& sp) {
  const FwSpecies& row = p.species[std::size_t(s)];
  const trees::Skeleton& skeleton = sp.skeleton();
  const int n = skeleton.size(), m = sp.modes().mode_count();
  const Eigen::MatrixXd &v = sp.strong_wind().linear_shapes(), &w = sp.strong_wind().quadratic_shapes();
  std::vector<bool> placed(std::size_t(n), false);
  for (int j = 0; j < n; ++j) {
    const std::size_t at = std::size_t(row.skeleton_offset + j);
    const int node = p.walk[2 * at], parent = p.walk[2 * at + 1];
    INFO("species " << s << ", walk entry " << j << ": node " << node << ", parent " << parent);
    REQUIRE(node >= 0);
    REQUIRE(node < n);
    CHECK_FALSE(placed[std::size_t(node)]);
    CHECK(parent == skeleton.node(node).parent);
    CHECK((parent < 0 ? j == 0 : bool(placed[std::size_t(parent)])));  // the parent came first
    placed[std::size_t(node)] = true;

    const int first = j - j % trees::ForestPacking::kWalkBlock;
    const int count = std::min(trees::ForestPacking::kWalkBlock, n - first), lane = j - first;
    const bool below_root = parent == skeleton.root();
    for (int a = 0; a < 3; ++a) {
      const double rest =
          parent < 0 ? 0.0 : skeleton.node(node).position(a) - skeleton.node(parent).position(a);
      CHECK(p.rest_elements[std::size_t(3 * (row.skeleton_offset + first) + count * a + lane)] ==
            float(rest));
      for (int i = 0; i < m; ++i) {
        const std::size_t value =
            std::size_t(row.shape_offset + 3 * first * m + 3 * count * i + count * a + lane);
        const auto element = [&](const Eigen::MatrixXd& shapes) {
          if (parent < 0) return 0.0f;
          return float(shapes(3 * node + a, i) - (below_root ? 0.0 : shapes(3 * parent + a, i)));
        };
        CHECK(p.strong_v[value] == element(v));
        CHECK(p.strong_w[value] == element(w));
      }
    }
  }
}

TEST_CASE("Forest::pack: the strong-wind arrays hold each walk entry's element, in blocks", "[strong-wind]") {
  const trees::SpeciesBasis a = species_of(cantilever(), 4), b = species_of(test::small_broadleaf(), 6),
                            c = species_of(cantilever_from_the_tip(), 3);
  const trees::Forest forest({a, b, c}, {{1, {0.0, 0.0, 0.0}, 0.0, 1.0}});
  const trees::ForestPacking p = forest.pack();
  REQUIRE(p.strong_v.size() == p.node_shapes.size());
  REQUIRE(p.strong_w.size() == p.node_shapes.size());
  REQUIRE(p.strong_b.size() == p.omega.size());
  const FwSpecies& row = p.species[1];
  for (int i = 0; i < 6; ++i)
    CHECK(p.strong_b[std::size_t(row.modal_offset + i)] == float(b.strong_wind().b()(i)));
  // n entries per species back to back.
  REQUIRE(p.species[0].skeleton_offset == 0);
  REQUIRE(row.skeleton_offset == a.skeleton().size());
  REQUIRE(p.species[2].skeleton_offset == a.skeleton().size() + b.skeleton().size());
  const std::size_t entries = std::size_t(a.skeleton().size() + b.skeleton().size() + c.skeleton().size());
  REQUIRE(p.walk.size() == 2 * entries);
  REQUIRE(p.rest_elements.size() == 3 * entries);
  check_strong_wind_packing(p, 0, a);
  check_strong_wind_packing(p, 1, b);
  check_strong_wind_packing(p, 2, c);
  // Where every parent's index is below its children's (the upright cantilever, numbered from the root) the
  // walk is node order, so that the kernel stores in order; numbered from the tip, it starts at the root.
  for (int j = 0; j < a.skeleton().size(); ++j) CHECK(p.walk[2 * std::size_t(j)] == j);
  CHECK(p.walk[2 * std::size_t(p.species[2].skeleton_offset)] == c.skeleton().root());
}

TEST_CASE("StrongWindCorrection: bad settings, sizes and values throw invalid_argument", "[strong-wind]") {
  const trees::Skeleton tree = cantilever();
  trees::StrongWindSettings settings;
  settings.samples_per_side = 1;
  CHECK_THROWS_WITH(settings.validate(), "StrongWindSettings: samples_per_side must be >= 2, got 1");
  settings = {};
  settings.reach = 0.0;
  CHECK_THROWS_AS(settings.validate(), std::invalid_argument);
  settings = {};
  settings.max_slope = std::nan("");
  CHECK_THROWS_AS(settings.validate(), std::invalid_argument);
  settings = {};
  settings.search_points = 2;
  CHECK_THROWS_AS(settings.validate(), std::invalid_argument);
  settings = {};
  settings.beta_max = -1.0;
  CHECK_THROWS_AS(StrongWindCorrection::fit(tree, Eigen::MatrixXd::Zero(3 * tree.size(), 1), settings),
                  std::invalid_argument);

  CHECK_THROWS_WITH(StrongWindCorrection::fit(tree, Eigen::MatrixXd::Zero(6, 2)),
                    "StrongWindCorrection: node shapes have 6 rows, expected 3 x 21 nodes");
  Eigen::MatrixXd bad = Eigen::MatrixXd::Zero(3 * tree.size(), 1);
  bad(5, 0) = std::nan("");
  CHECK_THROWS_AS(StrongWindCorrection::fit(tree, bad), std::invalid_argument);
  CHECK_THROWS_AS(StrongWindCorrection::corrected_deformation(tree, Eigen::VectorXd::Zero(4)),
                  std::invalid_argument);

  const Eigen::MatrixXd vw = Eigen::MatrixXd::Zero(9, 2);
  CHECK_THROWS_AS(StrongWindCorrection::from_values(vw, Eigen::MatrixXd::Zero(6, 2), Eigen::VectorXd::Zero(2),
                                                    std::vector<trees::StrongWindModeFit>(2)),
                  std::invalid_argument);
  CHECK_THROWS_WITH(StrongWindCorrection::from_values(vw, vw, Eigen::Vector2d(1.0, -1.0),
                                                      std::vector<trees::StrongWindModeFit>(2)),
                    "StrongWindCorrection: b must be finite and >= 0");
  CHECK_THROWS_AS(StrongWindCorrection::from_values(vw, vw, Eigen::VectorXd::Zero(2),
                                                    std::vector<trees::StrongWindModeFit>(1)),
                  std::invalid_argument);
  const StrongWindCorrection ok = StrongWindCorrection::from_values(vw, vw, Eigen::VectorXd::Zero(2),
                                                                    std::vector<trees::StrongWindModeFit>(2));
  CHECK_THROWS_AS(ok.displacement(Eigen::VectorXd::Zero(3)), std::invalid_argument);
  CHECK_THROWS_WITH(ok.corrected_displacement(tree, Eigen::VectorXd::Zero(2)),
                    "StrongWindCorrection: the skeleton has 21 nodes, the correction 3");
  CHECK_THROWS_WITH(ok.scaled(0.0), "StrongWindCorrection: scale must be finite and > 0, got 0");

  const trees::SpeciesBasis sp = species_of(tree, 4);
  CHECK_THROWS_WITH(trees::SpeciesBasis::from_parts(sp.skeleton(), sp.settings(), sp.modes(), sp.wind(), ok),
                    "SpeciesBasis: the strong-wind correction has 2 modes of 3 nodes, expected 4 of 21");
}
