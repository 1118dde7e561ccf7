// CanopyDrag: momentum balances between the air and the trees (docs/design.md, "Coupling"). In a steady
// uniform wind the force the canopy field takes from the air, rho_air sum_cells k |u| u h^3, equals the drag
// the trees receive through their wind basis: in total for generated trees at a yaw and scale != 1, with and
// without leaves, and per cell (per height band of the basis) for a small hand-built tree. Also the foliage
// rule (trees/Foliage.hpp) and argument checks.
#include "trees/CanopyDrag.hpp"

#include <catch2/catch.hpp>

#include <Eigen/Geometry>

#include <cmath>
#include <set>
#include <string>
#include <vector>

#include "fluid/CanopyField.hpp"
#include "trees/BeamModel.hpp"
#include "trees/Foliage.hpp"
#include "trees/Forest.hpp"
#include "trees/SpeciesBasis.hpp"
#include "trees/TreeGenerator.hpp"
#include "trees/WindBasis.hpp"

using namespace fw;

namespace {

constexpr double kRho = trees::WindBasisSettings::kAirDensity;

// The acceptance tolerance for the balance of forces: 1%.
constexpr double kBalanceTolerance = 1e-2;
// What the balance actually achieves: both sides integrate the same constant drag width over the same exact
// element pieces, so they differ only by rounding. The canopy's k is stored as float32 (relative rounding
// 2^-24 ~ 6e-8 per cell); a sum of positive terms keeps that relative size, so 1e-6 leaves a factor ~16.
constexpr double kFloatTolerance = 1e-6;
// Two double computations of the same sums in a different order (~1e-16 per term, thousands of terms).
constexpr double kDoubleTolerance = 1e-10;

fluid::GridSpec grid(int nx, int ny, int nz, double h) {
  fluid::GridSpec spec;
  spec.nx = nx;
  spec.ny = ny;
  spec.nz = nz;
  spec.h = h;
  return spec;
}

// Sum over the nodes of the translational nodal loads F = G w: the total force on the tree, N.
Eigen::Vector3d total_force(const Eigen::MatrixXd& load, const Eigen::VectorXd& squared_wind) {
  const Eigen::VectorXd F = load * squared_wind;
  Eigen::Vector3d sum = Eigen::Vector3d::Zero();
  for (Eigen::Index node = 0; 6 * node < F.size(); ++node) sum += F.segment<3>(6 * node);
  return sum;
}

// The same wind at every sample, as the rows of an S x 3 matrix.
Eigen::MatrixX3d uniform(const Eigen::Vector3d& u, int samples) {
  Eigen::MatrixX3d wind(samples, 3);
  for (int s = 0; s < samples; ++s) wind.row(s) = u.transpose();
  return wind;
}

// rho_air sum_cells k |u| u h^3, from the float32 field the wind kernels receive.
Eigen::Vector3d air_loss(const fluid::CanopyField& canopy, const Eigen::Vector3d& u) {
  double sum = 0.0;
  for (float k : canopy.drag_density()) sum += k;
  const double h = canopy.spec().h;
  return kRho * sum * h * h * h * u.norm() * u;
}

double relative(const Eigen::Vector3d& a, const Eigen::Vector3d& b) {
  return (a - b).norm() / b.norm();
}

// A small tree for exact per-cell sums in 1 m cells: a vertical stem at x = y = 2.5 m from z = 0 to 4 m
// (diameter 0.2 m, node at 2.5 m) and two horizontal branches from (2.5, 2.5, 2.5) m, 2.2 m along +x and
// +y (tip radius 0.02 m, so D_e = 0.1 + 0.02 m: the element diameter is twice the mean node radius). The
// branches bear the leaves; their end points span a right triangle of 2.42 m^2.
constexpr double kStemRadius = 0.1, kBranchRadius = 0.02, kBranchLength = 2.2;

trees::Skeleton small_tree() {
  return trees::Skeleton::from_nodes({{-1, {2.5, 2.5, 0.0}, kStemRadius},
                                      {0, {2.5, 2.5, 2.5}, kStemRadius},
                                      {1, {2.5, 2.5, 4.0}, kStemRadius},
                                      {1, {2.5 + kBranchLength, 2.5, 2.5}, kBranchRadius},
                                      {1, {2.5, 2.5 + kBranchLength, 2.5}, kBranchRadius}});
}

}  // namespace

TEST_CASE("CanopyDrag: in a uniform wind the air loses the force the trees' wind basis receives",
          "[canopy][windbasis]") {
  const std::string preset = GENERATE(as<std::string>{}, "broadleaf", "conifer");
  const double lai = GENERATE(0.0, 3.0);
  INFO(preset << ", LAI " << lai);

  trees::GeneratorSettings generator;
  generator.preset = preset;
  generator.height = 12.0;
  trees::SpeciesSettings settings;
  settings.modal.mode_count = 8;
  settings.wind.samples = 3;
  settings.wind.leaf_area_index = lai;
  const trees::Skeleton skeleton = trees::generate_tree(generator);
  trees::SpeciesBasis species = trees::SpeciesBasis::compute(skeleton, settings);

  const double yaw = 0.7, scale = 1.3;
  const Eigen::Vector3d position(40.3, 31.7, 0.2);
  const trees::Forest forest({species}, {{0, position, yaw, scale}});
  const Eigen::Matrix3d R = forest.rotation(0);

  // 1 m cells, 80 x 64 x 24 m: the whole tree (15.6 m tall, a crown about 12 m across) is inside.
  fluid::CanopyField canopy(grid(80, 64, 24, 1.0));
  const fluid::CanopyTreeReport report = trees::ForestCanopy(forest).add(canopy, 0);
  REQUIRE(report.dropped_area == 0.0);
  REQUIRE_FALSE(report.outside);
  CHECK(canopy.tree_count() == 1);
  if (lai > 0.0) {
    CHECK(report.crown_projected_area > 10.0);
    CHECK(report.leaf_area == Approx(lai * report.crown_projected_area).epsilon(1e-12));
  } else {
    CHECK(report.leaf_area == 0.0);
  }
  CHECK(report.frontal_area == Approx(report.woody_area + report.leaf_area).epsilon(1e-12));

  const Eigen::Vector3d u(7.0, -3.0, 1.5);  // m/s, world frame
  const Eigen::Vector3d air = air_loss(canopy, u);

  // The trees' side, 1: total drag on the world skeleton, the sum of the translational nodal loads.
  const trees::Skeleton world = skeleton.transformed(R, position, scale);
  const Eigen::MatrixXd G = trees::WindBasis::load_operator(world, settings.wind);
  const Eigen::Vector3d tree = total_force(G, trees::WindBasis::squared_wind(uniform(u, 3)));
  const double error = relative(tree, air);
  WARN("CanopyDrag balance, " << preset << " LAI " << lai << ": |F_tree| = " << tree.norm()
                              << " N, relative difference to the air's loss " << error);
  CHECK(error < kBalanceTolerance);
  CHECK(error < kFloatTolerance);
  // Against the double-precision sum of the canopy field: no float rounding left.
  const Eigen::Vector3d air_double = kRho * canopy.drag_in_domain() * u.norm() * u;
  CHECK(relative(tree, air_double) < kDoubleTolerance);
  // The convention in closed form: 1/2 rho (C_Db x woody area + C_Df x leaf area) |u| u.
  const Eigen::Vector3d closed = 0.5 * kRho *
                                 (settings.wind.branch_drag_coefficient * report.woody_area +
                                  settings.wind.leaf_drag_coefficient * report.leaf_area) *
                                 u.norm() * u;
  CHECK(relative(tree, closed) < kDoubleTolerance);

  // The trees' side, 2: the instance's modal forces (similarity law p -> s^1/2 p, wind in the skeleton
  // frame) against shapes^T F with F the nodal loads on the scaled skeleton, computed independently.
  const trees::SpeciesBasis instance = species.scaled(scale);
  const Eigen::Vector3d local_u = R.transpose() * u;
  const Eigen::VectorXd f = instance.wind().modal_forces(uniform(local_u, 3));
  const Eigen::MatrixXd G_local = trees::WindBasis::load_operator(instance.skeleton(), settings.wind);
  const Eigen::VectorXd F_local = G_local * trees::WindBasis::squared_wind(uniform(local_u, 3));
  const Eigen::MatrixXd& shapes = instance.modes().shapes();  // free DOFs: node order without the root
  Eigen::VectorXd F_free(shapes.rows());
  const int root = instance.skeleton().root();
  for (int node = 0; node < instance.skeleton().size(); ++node)
    for (int j = 0; j < 6; ++j) {
      const int dof = trees::BeamModel::free_dof_index(root, node, j);
      if (dof >= 0) F_free(dof) = F_local(6 * node + j);
    }
  const Eigen::VectorXd f_ref = shapes.transpose() * F_free;
  CHECK((f - f_ref).norm() < kDoubleTolerance * f_ref.norm());
  // Rotating the skeleton-frame total back gives the world total.
  CHECK(relative(R * total_force(G_local, trees::WindBasis::squared_wind(uniform(local_u, 3))), tree) <
        kDoubleTolerance);
}

TEST_CASE("CanopyDrag: leaves add 1/2 rho C_Df A_leaf |u| u to both sides and bend the tree", "[canopy]") {
  trees::GeneratorSettings generator;
  generator.preset = "broadleaf";
  generator.height = 10.0;
  const trees::Skeleton skeleton = trees::generate_tree(generator);
  trees::SpeciesSettings bare_settings;
  bare_settings.modal.mode_count = 6;
  trees::SpeciesSettings leafy_settings = bare_settings;
  leafy_settings.wind.leaf_area_index = 3.0;
  const trees::SpeciesBasis bare = trees::SpeciesBasis::compute(skeleton, bare_settings);
  const trees::SpeciesBasis leafy = trees::SpeciesBasis::compute(skeleton, leafy_settings);
  const trees::Forest forest({bare, leafy},
                             {{0, {20.0, 20.0, 0.0}, 0.0, 1.0}, {1, {20.0, 20.0, 0.0}, 0.0, 1.0}});
  fluid::CanopyField air_bare(grid(40, 40, 16, 1.0)), air_leafy(grid(40, 40, 16, 1.0));
  trees::ForestCanopy(forest).add(air_bare, 0);
  const auto report = trees::ForestCanopy(forest).add(air_leafy, 1);
  const Eigen::Vector3d u(10.0, 0.0, 0.0);
  const Eigen::Vector3d leaves =
      0.5 * kRho * leafy_settings.wind.leaf_drag_coefficient * report.leaf_area * u.norm() * u;
  REQUIRE(report.leaf_area > 0.0);
  // The air's side.
  // A difference of two float32 sums: each side's rounding (kFloatTolerance of its own size, the bare part
  // a fraction of the leafy one) measured against the leaves' share alone, so ten times looser.
  constexpr double kDifferenceTolerance = 10 * kFloatTolerance;
  CHECK(relative(air_loss(air_leafy, u) - air_loss(air_bare, u), leaves) < kDifferenceTolerance);
  // The trees' side: the leaf-bearing elements carry the leaves' drag.
  const auto w = trees::WindBasis::squared_wind(uniform(u, 1));
  const Eigen::Vector3d tree_leaves =
      total_force(trees::WindBasis::load_operator(skeleton, leafy_settings.wind), w) -
      total_force(trees::WindBasis::load_operator(skeleton, bare_settings.wind), w);
  CHECK(relative(tree_leaves, leaves) < kDoubleTolerance);
  // Leaves bend the tree: the modal forces grow (mode shapes do not depend on the wind settings).
  const Eigen::VectorXd f_bare = bare.wind().modal_forces(uniform(u, 1));
  const Eigen::VectorXd f_leafy = leafy.wind().modal_forces(uniform(u, 1));
  CHECK(f_leafy.norm() > 1.5 * f_bare.norm());
}

TEST_CASE("CanopyDrag: per cell, the air in each cell loses what the tree's elements in it receive",
          "[canopy]") {
  trees::SpeciesSettings settings;
  settings.modal.mode_count = 4;
  settings.wind.samples = 4;  // bands of 1 m over the 4 m tall tree: exactly the grid's layers k = 0..3
  settings.wind.leaf_area_index = 2.0;
  const trees::Skeleton skeleton = small_tree();
  const trees::Forest forest({trees::SpeciesBasis::compute(skeleton, settings)}, {{0, {0, 0, 0}, 0.0, 1.0}});
  const fluid::GridSpec spec = grid(6, 6, 5, 1.0);
  fluid::CanopyField canopy(spec);
  const auto report = trees::ForestCanopy(forest).add(canopy, 0);

  // Foliage: LAI x the triangle of the branch ends, shared over the two branches per metre.
  const double crown = 0.5 * kBranchLength * kBranchLength;  // 2.42 m^2
  CHECK(report.crown_projected_area == Approx(crown).epsilon(1e-12));
  const double lambda = settings.wind.leaf_area_index * crown / (2.0 * kBranchLength);  // 1.1 m^2/m
  // Drag area per metre beta and k = 1/2 beta l / h^3 of each piece (h = 1 m).
  const double cb = settings.wind.branch_drag_coefficient, cf = settings.wind.leaf_drag_coefficient;
  const double stem = cb * 2.0 * kStemRadius;  // 0.24 m^2/m
  const double branch =
      cb * (kStemRadius + kBranchRadius) + cf * lambda;  // D_e = r_a + r_b = 0.12 m: 0.584 m^2/m
  auto id = [&](int i, int j, int k) { return std::size_t(i + spec.nx * (j + spec.ny * k)); };
  std::vector<double> expected(spec.cell_count(), 0.0);
  for (int k = 0; k < 4; ++k) expected[id(2, 2, k)] += 0.5 * stem;  // 1 m of stem per layer
  // The branches at z = 2.5 m (layer 2) start in the middle of cell (2, 2, 2): 0.5, 1 and 0.7 m pieces.
  const double pieces[3] = {0.5, 1.0, kBranchLength - 1.5};
  for (int c = 0; c < 3; ++c) {
    expected[id(2 + c, 2, 2)] += 0.5 * branch * pieces[c];
    expected[id(2, 2 + c, 2)] += 0.5 * branch * pieces[c];
  }
  const std::vector<float> k = canopy.drag_density();
  for (std::size_t c = 0; c < k.size(); ++c) {
    INFO("cell " << c);
    CHECK(k[c] == Approx(expected[c]).epsilon(kFloatTolerance).margin(1e-12));
  }
  CHECK(k[id(2, 2, 2)] == Approx(0.412).epsilon(kFloatTolerance));  // 0.12 stem + 2 x 0.146 branches

  // Per layer: band s of the wind basis' load operator against the air's loss in layer k = s.
  const Eigen::MatrixXd G = trees::WindBasis::load_operator(skeleton, settings.wind);
  const Eigen::Vector3d u(3.0, 4.0, -1.0);
  for (int s = 0; s < settings.wind.samples; ++s) {
    Eigen::MatrixX3d wind = Eigen::MatrixX3d::Zero(settings.wind.samples, 3);
    wind.row(s) = u.transpose();  // only band s sees wind
    const Eigen::Vector3d tree = total_force(G, trees::WindBasis::squared_wind(wind));
    double layer = 0.0;
    for (int j = 0; j < spec.ny; ++j)
      for (int i = 0; i < spec.nx; ++i) layer += k[id(i, j, s)];
    const Eigen::Vector3d air = kRho * layer * u.norm() * u;  // h^3 = 1 m^3
    INFO("layer " << s);
    CHECK(relative(tree, air) < kFloatTolerance);
  }
  CHECK(k[id(2, 2, 4)] == 0.0f);  // above the tree
}

TEST_CASE("CanopyDrag: leaves land only in cells the crown's branches touch", "[canopy]") {
  const auto spec = grid(16, 16, 16, 0.5);
  // Stem (4, 4, 0) -> (4, 4, 6) m, thick; at z = 4 m four thin branches reach out 2 m, rising 1 m.
  std::vector<trees::SkeletonNode> nodes = {{-1, {4, 4, 0}, 0.2}, {0, {4, 4, 4}, 0.15}, {1, {4, 4, 6}, 0.1}};
  const double tips[4][2] = {{6, 4}, {2, 4}, {4, 6}, {4, 2}};
  for (const auto& t : tips) nodes.push_back({1, {t[0], t[1], 5}, 0.03});
  const auto tree = trees::Skeleton::from_nodes(nodes);
  trees::WindBasisSettings leafy, bare;
  leafy.leaf_area_index = 2.0;
  fluid::CanopyField with_leaves(spec), without(spec);
  with_leaves.add_elements(trees::canopy_elements(tree, leafy));
  without.add_elements(trees::canopy_elements(tree, bare));

  // Cells the four branches pass through, by fine sampling of their interiors.
  constexpr int kSamples = 4000;
  std::set<std::size_t> branch_cells;
  auto id = [&](int i, int j, int k) { return std::size_t(i + spec.nx * (j + spec.ny * k)); };
  for (const auto& t : tips)
    for (int s = 1; s < kSamples; ++s) {
      const double f = double(s) / kSamples;
      const double x = 4 + f * (t[0] - 4), y = 4 + f * (t[1] - 4), z = 4 + f;
      branch_cells.insert(id(int(x / spec.h), int(y / spec.h), int(z / spec.h)));
    }
  const auto a = with_leaves.frontal_area_density(), a0 = without.frontal_area_density();
  double leaf_sum = 0.0;
  std::size_t leaf_cells = 0;
  for (std::size_t c = 0; c < a.size(); ++c) {
    const double leaf = double(a[c]) - a0[c];
    if (std::abs(leaf) < 1e-6) continue;  // float32 rounding of equal woody parts
    ++leaf_cells;
    leaf_sum += leaf;
    CHECK(branch_cells.count(c) == 1);
  }
  // Each branch crosses 4 cells; the +x and +y branches share their first, cell (8, 8, 8).
  CHECK(leaf_cells == 15);
  CHECK(leaf_sum * std::pow(spec.h, 3) == Approx(16.0).epsilon(1e-6));  // LAI 2 x the 8 m^2 diamond
  // The stem below the crown carries no leaves.
  for (int k = 0; k < 8; ++k) CHECK(a[id(8, 8, k)] == Approx(a0[id(8, 8, k)]).epsilon(1e-7));
}

TEST_CASE("CanopyDrag: the leaf-bearing rule and the foliage distribution", "[canopy]") {
  SECTION("branches off the main stem bear the leaves, shared per metre") {
    const trees::Skeleton tree = small_tree();
    const auto bearing = trees::leaf_bearing_elements(tree);
    REQUIRE(bearing.size() == 4);
    for (std::size_t e = 0; e < 4; ++e) {
      const int child = tree.elements()[e].second;
      CHECK(bearing[e] == (child >= 3));  // nodes 3, 4 end the branches; 1, 2 the stem
    }
    const auto foliage = trees::Foliage::of(tree, 2.0);
    CHECK(foliage.leaf_area == Approx(2.0 * 2.42).epsilon(1e-12));
    CHECK(foliage.leaf_bearing_length == Approx(2.0 * kBranchLength).epsilon(1e-12));
    for (std::size_t e = 0; e < 4; ++e)
      CHECK(foliage.leaf_area_per_metre[e] == Approx(bearing[e] ? 1.1 : 0.0).margin(1e-12));
  }
  SECTION("a vertical pole bears them on its terminal element, but has no crown hull") {
    const auto pole =
        trees::Skeleton::from_nodes({{-1, {0, 0, 0}, 0.1}, {0, {0, 0, 1}, 0.1}, {1, {0, 0, 2}, 0.1}});
    const auto bearing = trees::leaf_bearing_elements(pole);
    CHECK_FALSE(bearing[0]);
    CHECK(bearing[1]);
    CHECK(trees::Foliage::of(pole, 3.0).leaf_area == 0.0);
  }
  SECTION("a leaning pole: its terminal element bears the leaves, but two end points span no hull") {
    const auto pole =
        trees::Skeleton::from_nodes({{-1, {0, 0, 0}, 0.1}, {0, {0, 0, 1}, 0.1}, {1, {1, 1, 2}, 0.1}});
    CHECK(trees::leaf_bearing_elements(pole) == std::vector<bool>{false, true});
    CHECK(trees::Foliage::of(pole, 3.0).leaf_area == 0.0);
  }
  SECTION("the crown hull of the diamond through four tips") {
    std::vector<trees::SkeletonNode> nodes = {
        {-1, {4, 4, 0}, 0.2}, {0, {4, 4, 4}, 0.15}, {1, {4, 4, 6}, 0.1}};
    const double tips[4][2] = {{6, 4}, {2, 4}, {4, 6}, {4, 2}};
    for (const auto& t : tips) nodes.push_back({1, {t[0], t[1], 5}, 0.03});
    const auto foliage = trees::Foliage::of(trees::Skeleton::from_nodes(nodes), 2.0);
    CHECK(foliage.crown_projected_area == Approx(8.0).epsilon(1e-12));  // diagonals 4 m
    CHECK(foliage.leaf_area == Approx(16.0).epsilon(1e-12));
  }
  SECTION("similarity: leaf area scales as s^2, leaf area per metre as s, not with yaw") {
    const trees::Skeleton tree = small_tree();
    const auto a = trees::Foliage::of(tree, 2.0);
    const Eigen::Matrix3d yaw = Eigen::AngleAxisd(1.1, Eigen::Vector3d::UnitZ()).toRotationMatrix();
    const auto b = trees::Foliage::of(tree.transformed(yaw, {3, -2, 1}, 1.7), 2.0);
    CHECK(b.leaf_area == Approx(1.7 * 1.7 * a.leaf_area).epsilon(1e-12));
    CHECK(b.leaf_area_per_metre[2] == Approx(1.7 * a.leaf_area_per_metre[2]).epsilon(1e-12));
  }
}

TEST_CASE("CanopyDrag: an instance's elements, carried from its species', are its world skeleton's",
          "[canopy]") {
  trees::SpeciesSettings settings;
  settings.modal.mode_count = 2;
  settings.wind.leaf_area_index = 3.0;  // the crown's foliage too
  const trees::Forest forest({trees::SpeciesBasis::compute(small_tree(), settings)},
                             {{0, {3.2, 2.7, 0.0}, 0.9, 1.3}, {0, {4.1, 3.3, 0.0}, -2.0, 0.8}});
  const trees::ForestCanopy canopy(forest);
  for (int k = 0; k < forest.instance_count(); ++k) {
    const trees::TreeInstance& tree = forest.instances()[std::size_t(k)];
    const trees::Skeleton world =
        forest.species_of(k).skeleton().transformed(forest.rotation(k), tree.position, tree.scale);
    const auto expected = trees::canopy_elements(world, settings.wind);
    const auto carried = canopy.elements(k);
    REQUIRE(carried.size() == expected.size());
    // Tolerance: the same products in another order, a few ulps of metres and areas.
    for (std::size_t e = 0; e < carried.size(); ++e) {
      for (std::size_t axis = 0; axis < 3; ++axis) {
        CHECK(carried[e].start[axis] == Approx(expected[e].start[axis]).margin(1e-12));
        CHECK(carried[e].end[axis] == Approx(expected[e].end[axis]).margin(1e-12));
      }
      CHECK(carried[e].frontal_area_per_metre == Approx(expected[e].frontal_area_per_metre).epsilon(1e-12));
      CHECK(carried[e].drag_area_per_metre == Approx(expected[e].drag_area_per_metre).epsilon(1e-12));
    }
    fluid::CanopyField field(grid(8, 8, 8, 1.0));
    const fluid::CanopyTreeReport report = canopy.add(field, k);
    const trees::Foliage foliage = trees::Foliage::of(world, settings.wind.leaf_area_index);
    CHECK(report.leaf_area == Approx(foliage.leaf_area).epsilon(1e-12));
    CHECK(report.crown_projected_area == Approx(foliage.crown_projected_area).epsilon(1e-12));
  }
  CHECK_THROWS_WITH(canopy.elements(2), Catch::Matchers::Contains("instance"));
}

TEST_CASE("CanopyDrag: bad arguments throw std::invalid_argument naming the unit", "[canopy]") {
  using Catch::Matchers::Contains;
  trees::SpeciesSettings settings;
  settings.modal.mode_count = 2;
  const trees::Forest forest({trees::SpeciesBasis::compute(small_tree(), settings)},
                             {{0, {0, 0, 0}, 0.0, 1.0}});
  fluid::CanopyField canopy(grid(6, 6, 6, 1.0));
  CHECK_THROWS_WITH(trees::ForestCanopy(forest).add(canopy, 1),
                    Contains("CanopyDrag") && Contains("instance"));
  CHECK_THROWS_AS(trees::ForestCanopy(forest).add(canopy, -1), std::invalid_argument);
  CHECK(canopy.tree_count() == 0);
  trees::WindBasisSettings bad;
  bad.leaf_area_index = -1.0;
  CHECK_THROWS_WITH(trees::canopy_elements(small_tree(), bad),
                    Contains("CanopyDrag") && Contains("leaf_area_index"));
  CHECK_THROWS_WITH(trees::canopy_elements(trees::Skeleton::from_nodes({{-1, {0, 0, 0}, 0.1}}), {}),
                    Contains("CanopyDrag"));
  CHECK_THROWS_WITH(trees::Foliage::of(small_tree(), NAN),
                    Contains("Foliage") && Contains("leaf area index"));
}
