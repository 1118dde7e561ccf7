// CanopyField: exact clipping of skeleton elements into cells, conservation of frontal area, the leaf rule,
// trees outside the domain and argument checks.
#include <catch2/catch.hpp>

#include <cmath>
#include <numbers>
#include <random>
#include <set>
#include <vector>

#include "fluid/CanopyField.hpp"
#include "trees/Skeleton.hpp"

using namespace fw;
using fluid::CanopyField;

namespace {

fluid::GridSpec grid(int nx, int ny, int nz, double h) {
  fluid::GridSpec spec;
  spec.nx = nx;
  spec.ny = ny;
  spec.nz = nz;
  spec.h = h;
  return spec;
}

std::size_t cell(const fluid::GridSpec& s, int i, int j, int k) {
  return std::size_t(i) + std::size_t(s.nx) * (j + std::size_t(s.ny) * k);
}

double sum(const std::vector<float>& v) {
  double s = 0.0;
  for (float x : v) s += x;
  return s;
}

// sum over elements of D x L for a tapered element: L (r0 + r1).
double woody_area(const trees::Skeleton& s) {
  double a = 0.0;
  for (auto [p, c] : s.elements())
    a += (s.node(c).position - s.node(p).position).norm() * (s.node(p).radius + s.node(c).radius);
  return a;
}

// A random branched tree about 14 m tall and 10 m wide, rooted at the origin: a stem of 8 nodes, then
// branches that grow outwards and upwards from random earlier nodes, thinning as they go.
trees::Skeleton random_tree(std::uint32_t seed, int extra_nodes) {
  std::mt19937 rng(seed);
  std::uniform_real_distribution<double> u(-1.0, 1.0);
  std::vector<trees::SkeletonNode> nodes;
  nodes.push_back({-1, {0, 0, 0}, 0.30});
  for (int n = 1; n < 8; ++n)
    nodes.push_back({n - 1, {0.05 * u(rng), 0.05 * u(rng), 2.0 * n}, 0.30 - 0.03 * n});
  for (int n = 0; n < extra_nodes; ++n) {
    const int parent = 2 + int(std::uniform_int_distribution<int>(0, int(nodes.size()) - 3)(rng));
    const auto& p = nodes[std::size_t(parent)];
    Eigen::Vector3d dir(u(rng), u(rng), 0.3 + 0.5 * std::abs(u(rng)));
    nodes.push_back({parent, p.position + 1.3 * dir.normalized(), std::max(0.01, 0.6 * p.radius)});
  }
  return trees::Skeleton::from_nodes(std::move(nodes));
}

}  // namespace

TEST_CASE("CanopyField: a vertical trunk of diameter D gives a = D h / h^3 in every cell it crosses",
          "[canopy]") {
  const auto spec = grid(8, 8, 10, 0.5);
  CanopyField canopy(spec);
  // A pole from z 0.5 to 3.5 m (cells k = 1..6) through the centre of column (2, 2), with a node at 2.25 m
  // in the middle of cell 4: pieces on both sides of the node add up.
  const double D = 0.2;
  auto pole = trees::Skeleton::from_nodes(
      {{-1, {1.25, 1.25, 0.5}, D / 2}, {0, {1.25, 1.25, 2.25}, D / 2}, {1, {1.25, 1.25, 3.5}, D / 2}});
  const auto r = canopy.add_tree(pole, 1.2, 3.0, 0.2);
  // A vertical pole has no horizontal crown: no leaves.
  CHECK(r.crown_projected_area == 0.0);
  CHECK(r.leaf_area == 0.0);
  CHECK(r.woody_area == Approx(D * 3.0).epsilon(1e-12));
  CHECK(r.dropped_area == 0.0);
  CHECK_FALSE(r.outside);
  const auto a = canopy.frontal_area_density();
  const auto k = canopy.drag_density();
  const double h = spec.h, expected = D * h / (h * h * h);  // 0.8 1/m
  for (int kk = 0; kk < spec.nz; ++kk) {
    INFO("cell k = " << kk);
    const bool crossed = kk >= 1 && kk <= 6;
    CHECK(a[cell(spec, 2, 2, kk)] == Approx(crossed ? expected : 0.0).epsilon(1e-6));
    CHECK(k[cell(spec, 2, 2, kk)] == Approx(crossed ? 1.2 * expected : 0.0).epsilon(1e-6));
  }
  CHECK(sum(a) == Approx(6 * expected).epsilon(1e-6));  // nothing anywhere else

  SECTION("a tapered horizontal element is clipped exactly at cell faces") {
    CanopyField bar(grid(4, 2, 2, 1.0));
    // x 0.3 .. 2.7 m at y = z = 0.5: pieces 0.7, 1.0, 0.7 m; radius 0.1 -> 0.2 linearly along x.
    const fluid::CanopyElement e{{0.3, 0.5, 0.5}, {2.7, 0.5, 0.5}, 0.1, 0.2, false};
    const auto rb = bar.add_elements(std::span(&e, 1), 1.0, 0.0, 0.0);
    auto diameter = [](double x) { return 2.0 * (0.1 + 0.1 * (x - 0.3) / 2.4); };
    const auto f = bar.frontal_area_density();
    CHECK(f[0] == Approx(0.7 * diameter(0.65)).epsilon(1e-6));
    CHECK(f[1] == Approx(1.0 * diameter(1.5)).epsilon(1e-6));
    CHECK(f[2] == Approx(0.7 * diameter(2.35)).epsilon(1e-6));
    CHECK(f[3] == 0.0f);
    CHECK(rb.woody_area == Approx(2.4 * 0.3).epsilon(1e-12));
  }
}

TEST_CASE("CanopyField: frontal area is conserved for trees crossing many cells and the domain's edge",
          "[canopy]") {
  auto spec = grid(40, 30, 24, 0.5);
  spec.origin = {100.0, 200.0, 0.0};  // 20 x 15 x 12 m
  const double cd_branch = 1.2, lai = 3.5, cd_leaf = 0.2;
  CanopyField canopy(spec), woody(spec);
  double total = 0.0, dropped = 0.0, woody_total = 0.0, leaves = 0.0;
  // Three trees: one inside, one straddling the east edge, one poking out of the top (scaled up).
  const std::array<Eigen::Vector3d, 3> at = {Eigen::Vector3d(108, 207, 0), Eigen::Vector3d(119, 212, 0),
                                             Eigen::Vector3d(110, 206, 0)};
  const std::array<double, 3> scale = {0.8, 0.9, 1.1};
  for (int t = 0; t < 3; ++t) {
    const auto tree = random_tree(17 + t, 150);
    const Eigen::Matrix3d yaw = Eigen::AngleAxisd(0.7 * t + 0.3, Eigen::Vector3d::UnitZ()).toRotationMatrix();
    const auto world = tree.transformed(yaw, at[std::size_t(t)], scale[std::size_t(t)]);
    const auto r = canopy.add_tree(world, cd_branch, lai, cd_leaf);
    woody.add_tree(world, cd_branch, 0.0, cd_leaf);
    CHECK(r.woody_area == Approx(woody_area(world)).epsilon(1e-12));
    CHECK(r.crown_projected_area > 10.0);  // a crown several metres across
    CHECK(r.leaf_area == Approx(lai * r.crown_projected_area).epsilon(1e-12));
    total += r.woody_area + r.leaf_area;
    dropped += r.dropped_area;
    woody_total += r.woody_area;
    leaves += r.leaf_area;
  }
  const double h3 = spec.h * spec.h * spec.h;
  const double inside = total - dropped;
  INFO("total " << total << " m^2, dropped outside the domain " << dropped << " m^2 ("
                << 100 * dropped / total << "%)");
  WARN("canopy conservation: total frontal area " << total << " m^2 (woody " << woody_total << ", leaves "
                                                  << leaves << "), dropped " << dropped
                                                  << " m^2 = " << 100 * dropped / total << "%");
  CHECK(canopy.total_frontal_area() == Approx(total).epsilon(1e-12));
  CHECK(canopy.dropped_frontal_area() == Approx(dropped).epsilon(1e-12));
  CHECK(dropped > 0.01 * total);  // the edge trees really lose something
  CHECK(dropped < 0.5 * total);
  CHECK(canopy.frontal_area_in_domain() == Approx(inside).epsilon(1e-9));
  const auto a = canopy.frontal_area_density();
  const double float_sum = sum(a) * h3;
  WARN("canopy conservation: relative error of sum(a h^3) in float "
       << std::abs(float_sum - inside) / inside);
  CHECK(float_sum == Approx(inside).epsilon(1e-6));
  // Drag: Cd_branch on the woody part inside, Cd_leaf on the leaves inside.
  const double woody_inside = woody.frontal_area_in_domain();
  const double expected_drag = cd_branch * woody_inside + cd_leaf * (inside - woody_inside);
  CHECK(sum(canopy.drag_density()) * h3 == Approx(expected_drag).epsilon(1e-6));
  CHECK(canopy.tree_count() == 3);
  CHECK(canopy.trees_outside() == 0);
  // Many cells: the crowns are resolved, not lumped.
  std::size_t filled = 0;
  for (float x : a) filled += x > 0.0f;
  CHECK(filled > 500);
}

TEST_CASE("CanopyField: leaves land only in cells the crown's branches touch", "[canopy]") {
  const auto spec = grid(16, 16, 16, 0.5);
  // Stem (4, 4, 0) -> (4, 4, 6) m, thick; at z = 4 m four thin branches reach out 2 m, rising 1 m.
  std::vector<trees::SkeletonNode> nodes = {{-1, {4, 4, 0}, 0.2}, {0, {4, 4, 4}, 0.15}, {1, {4, 4, 6}, 0.1}};
  const double tips[4][2] = {{6, 4}, {2, 4}, {4, 6}, {4, 2}};
  for (const auto& t : tips) nodes.push_back({1, {t[0], t[1], 5}, 0.03});
  const auto tree = trees::Skeleton::from_nodes(nodes);
  CanopyField with_leaves(spec), bare(spec);
  const auto r = with_leaves.add_tree(tree, 1.0, 2.0, 0.3);
  bare.add_tree(tree, 1.0, 0.0, 0.3);
  // The crown hull is the diamond through the four tips (diagonals 4 m): 8 m^2, so 16 m^2 of leaves.
  CHECK(r.crown_projected_area == Approx(8.0).epsilon(1e-12));
  CHECK(r.leaf_area == Approx(16.0).epsilon(1e-12));

  // Cells the four branches pass through, by fine sampling of their interiors.
  std::set<std::size_t> branch_cells;
  for (const auto& t : tips)
    for (int s = 1; s < 4000; ++s) {
      const double f = s / 4000.0;
      const double x = 4 + f * (t[0] - 4), y = 4 + f * (t[1] - 4), z = 4 + f;
      branch_cells.insert(cell(spec, int(x / spec.h), int(y / spec.h), int(z / spec.h)));
    }
  const auto a = with_leaves.frontal_area_density(), a0 = bare.frontal_area_density();
  double leaf_sum = 0.0;
  std::size_t leaf_cells = 0;
  for (std::size_t id = 0; id < a.size(); ++id) {
    const double leaf = double(a[id]) - a0[id];
    if (std::abs(leaf) < 1e-6) continue;
    ++leaf_cells;
    leaf_sum += leaf;
    CHECK(branch_cells.count(id) == 1);
  }
  // Each branch crosses 4 cells; the +x and +y branches share their first, cell (8, 8, 8).
  CHECK(leaf_cells == 15);
  CHECK(leaf_sum * std::pow(spec.h, 3) == Approx(16.0).epsilon(1e-6));
  // The stem below the crown carries no leaves.
  for (int k = 0; k < 8; ++k) CHECK(a[cell(spec, 8, 8, k)] == Approx(a0[cell(spec, 8, 8, k)]).epsilon(1e-7));
}

TEST_CASE("CanopyField: a tree outside the domain contributes nothing and is reported", "[canopy]") {
  auto spec = grid(10, 10, 10, 1.0);
  CanopyField canopy(spec);
  const auto tree = random_tree(5, 40);
  const auto far = tree.transformed(Eigen::Matrix3d::Identity(), {-100.0, 5.0, 0.0}, 1.0);
  const auto r = canopy.add_tree(far, 1.2, 3.5, 0.2);
  CHECK(r.outside);
  CHECK(r.dropped_area == Approx(r.woody_area + r.leaf_area).epsilon(1e-12));
  CHECK(canopy.trees_outside() == 1);
  CHECK(canopy.frontal_area_in_domain() == 0.0);
  for (float x : canopy.frontal_area_density()) CHECK(x == 0.0f);
  for (float x : canopy.drag_density()) CHECK(x == 0.0f);
  // Below the ground counts as outside too.
  const auto sunk = tree.transformed(Eigen::Matrix3d::Identity(), {5.0, 5.0, -50.0}, 1.0);
  CHECK(canopy.add_tree(sunk, 1.2, 3.5, 0.2).outside);
  CHECK(canopy.trees_outside() == 2);
  CHECK(canopy.tree_count() == 2);
}

TEST_CASE("CanopyField: bad arguments throw std::invalid_argument naming the class", "[canopy]") {
  using Catch::Matchers::Contains;
  CHECK_THROWS_WITH(CanopyField(grid(0, 4, 4, 1.0)), Contains("CanopyField"));
  CHECK_THROWS_WITH(CanopyField(grid(4, 4, 4, -1.0)), Contains("CanopyField"));
  CanopyField canopy(grid(4, 4, 4, 1.0));
  const auto tree = random_tree(3, 10);
  CHECK_THROWS_AS(canopy.add_tree(tree, -1.0, 1.0, 0.2), std::invalid_argument);
  CHECK_THROWS_WITH(canopy.add_tree(tree, -1.0, 1.0, 0.2),
                    Contains("CanopyField") && Contains("branch drag"));
  CHECK_THROWS_WITH(canopy.add_tree(tree, 1.0, NAN, 0.2),
                    Contains("CanopyField") && Contains("leaf area index"));
  CHECK_THROWS_WITH(canopy.add_tree(tree, 1.0, 1.0, INFINITY), Contains("leaf drag"));
  CHECK_THROWS_WITH(canopy.add_tree(trees::Skeleton{}, 1.0, 1.0, 0.2), Contains("CanopyField"));
  const fluid::CanopyElement bad{{0, 0, 0}, {1, NAN, 0}, 0.1, 0.1, false};
  CHECK_THROWS_WITH(canopy.add_elements(std::span(&bad, 1), 1.0, 0.0, 0.0),
                    Contains("CanopyField: element 0"));
  CHECK(canopy.tree_count() == 0);  // nothing was added by the failed calls
}
