// CanopyField: exact clipping of line elements into cells, conservation of frontal and drag area, the
// k = 1/2 sum C_D A / h^3 convention, trees outside the domain and argument checks. (The leaf rule and the
// balance against the wind basis live in trees/, tests/trees/CanopyDrag_test.cpp.)
#include <catch2/catch.hpp>

#include <array>
#include <cmath>
#include <random>
#include <vector>

#include "fluid/CanopyField.hpp"

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

// Random line elements about a 14 m tall, 10 m wide bush rooted at `base`: each starts at the end of an
// earlier one (or the base) and grows outwards and upwards, with random frontal and drag areas per metre.
std::vector<fluid::CanopyElement> random_elements(std::uint32_t seed, int count,
                                                  const std::array<double, 3>& base) {
  std::mt19937 rng(seed);
  std::uniform_real_distribution<double> u(-1.0, 1.0), area(0.01, 0.5), cd(0.2, 1.2);
  std::vector<fluid::CanopyElement> out;
  std::vector<std::array<double, 3>> ends{base};
  for (int n = 0; n < count; ++n) {
    const auto from = ends[std::uniform_int_distribution<std::size_t>(0, ends.size() - 1)(rng)];
    const double dz = n < 8 ? 1.75 : 0.3 + 0.5 * std::abs(u(rng));
    const double dx = n < 8 ? 0.0 : 1.3 * u(rng), dy = n < 8 ? 0.0 : 1.3 * u(rng);
    fluid::CanopyElement e;
    e.start = from;
    e.end = {from[0] + dx, from[1] + dy, std::min(from[2] + dz, base[2] + 14.0)};
    e.frontal_area_per_metre = area(rng);
    e.drag_area_per_metre = cd(rng) * e.frontal_area_per_metre;
    out.push_back(e);
    ends.push_back(e.end);
  }
  return out;
}

double length(const fluid::CanopyElement& e) {
  return std::hypot(e.end[0] - e.start[0], e.end[1] - e.start[1], e.end[2] - e.start[2]);
}

}  // namespace

TEST_CASE("CanopyField: a vertical trunk of diameter D gives a = D h / h^3 and k = 1/2 C_D a in every cell",
          "[canopy]") {
  const auto spec = grid(8, 8, 10, 0.5);
  CanopyField canopy(spec);
  // A pole from z 0.5 to 3.5 m (cells k = 1..6) through the centre of column (2, 2), in two elements with
  // a joint at 2.25 m in the middle of cell 4: pieces on both sides of the joint add up.
  const double D = 0.2, cd = 1.2;
  const fluid::CanopyElement pole[2] = {{{1.25, 1.25, 0.5}, {1.25, 1.25, 2.25}, D, cd * D},
                                        {{1.25, 1.25, 2.25}, {1.25, 1.25, 3.5}, D, cd * D}};
  const auto r = canopy.add_elements(pole);
  CHECK(r.frontal_area == Approx(D * 3.0).epsilon(1e-12));
  CHECK(r.drag_area == Approx(cd * D * 3.0).epsilon(1e-12));
  CHECK(r.dropped_area == 0.0);
  CHECK(r.dropped_drag_area == 0.0);
  CHECK_FALSE(r.outside);
  CHECK(r.leaf_area == 0.0);  // only trees::ForestCanopy knows about leaves
  const auto a = canopy.frontal_area_density();
  const auto k = canopy.drag_density();
  const double h = spec.h, expected = D * h / (h * h * h);  // 0.8 1/m
  for (int kk = 0; kk < spec.nz; ++kk) {
    INFO("cell k = " << kk);
    const bool crossed = kk >= 1 && kk <= 6;
    CHECK(a[cell(spec, 2, 2, kk)] == Approx(crossed ? expected : 0.0).epsilon(1e-6));
    // The air in the cell loses rho k |u| u h^3 = 1/2 rho C_D (D h) |u| u: the drag on the pole's piece.
    CHECK(k[cell(spec, 2, 2, kk)] == Approx(crossed ? 0.5 * cd * expected : 0.0).epsilon(1e-6));
  }
  CHECK(sum(a) == Approx(6 * expected).epsilon(1e-6));  // nothing anywhere else
  CHECK(canopy.drag_in_domain() == Approx(0.5 * cd * D * 3.0).epsilon(1e-12));

  SECTION("a horizontal element is clipped exactly at cell faces") {
    CanopyField bar(grid(4, 2, 2, 1.0));
    // x 0.3 .. 2.7 m at y = z = 0.5: pieces 0.7, 1.0, 0.7 m, 0.3 m^2/m frontal, 0.12 m^2/m drag area.
    const fluid::CanopyElement e{{0.3, 0.5, 0.5}, {2.7, 0.5, 0.5}, 0.3, 0.12};
    const auto rb = bar.add_elements(std::span(&e, 1));
    const auto f = bar.frontal_area_density();
    const auto kb = bar.drag_density();
    const double pieces[3] = {0.7, 1.0, 0.7};
    for (int i = 0; i < 3; ++i) {
      CHECK(f[std::size_t(i)] == Approx(pieces[i] * 0.3).epsilon(1e-6));
      CHECK(kb[std::size_t(i)] == Approx(0.5 * pieces[i] * 0.12).epsilon(1e-6));
    }
    CHECK(f[3] == 0.0f);
    CHECK(rb.frontal_area == Approx(2.4 * 0.3).epsilon(1e-12));
  }
}

TEST_CASE("CanopyField: frontal and drag area are conserved for elements crossing many cells and the edge",
          "[canopy]") {
  auto spec = grid(40, 30, 24, 0.5);
  spec.origin = {100.0, 200.0, 0.0};  // 20 x 15 x 12 m
  CanopyField canopy(spec);
  double total = 0.0, dropped = 0.0, drag = 0.0, dropped_drag = 0.0;
  // Three bushes: one inside, one straddling the east edge, one poking out of the top.
  const std::array<std::array<double, 3>, 3> at = {{{108, 207, 0}, {119, 212, 0}, {110, 206, 1}}};
  for (int t = 0; t < 3; ++t) {
    const auto elements = random_elements(17 + t, 150, at[std::size_t(t)]);
    double frontal = 0.0, beta = 0.0;
    for (const auto& e : elements) {
      frontal += length(e) * e.frontal_area_per_metre;
      beta += length(e) * e.drag_area_per_metre;
    }
    const auto r = canopy.add_elements(elements);
    CHECK(r.frontal_area == Approx(frontal).epsilon(1e-12));
    CHECK(r.drag_area == Approx(beta).epsilon(1e-12));
    total += r.frontal_area;
    dropped += r.dropped_area;
    drag += r.drag_area;
    dropped_drag += r.dropped_drag_area;
  }
  const double h3 = spec.h * spec.h * spec.h;
  const double inside = total - dropped;
  WARN("canopy conservation: total frontal area " << total << " m^2, dropped " << dropped
                                                  << " m^2 = " << 100 * dropped / total << "%");
  CHECK(canopy.total_frontal_area() == Approx(total).epsilon(1e-12));
  CHECK(canopy.dropped_frontal_area() == Approx(dropped).epsilon(1e-12));
  CHECK(dropped > 0.01 * total);  // the edge bushes really lose something
  CHECK(dropped < 0.5 * total);
  CHECK(dropped_drag > 0.0);
  CHECK(canopy.frontal_area_in_domain() == Approx(inside).epsilon(1e-9));
  // k h^3 sums to half the drag area inside: the force rho k |u| u h^3 is 1/2 rho C_D A |u| u.
  CHECK(canopy.drag_in_domain() == Approx(0.5 * (drag - dropped_drag)).epsilon(1e-9));
  // The float fields: float32 rounding (~6e-8 relative per cell) of sums of positive terms.
  const double float_sum = sum(canopy.frontal_area_density()) * h3;
  WARN("canopy conservation: relative error of sum(a h^3) in float "
       << std::abs(float_sum - inside) / inside);
  CHECK(float_sum == Approx(inside).epsilon(1e-6));
  CHECK(sum(canopy.drag_density()) * h3 == Approx(0.5 * (drag - dropped_drag)).epsilon(1e-6));
  CHECK(canopy.tree_count() == 3);
  CHECK(canopy.trees_outside() == 0);
  // Many cells: the crowns are resolved, not lumped.
  std::size_t filled = 0;
  for (float x : canopy.frontal_area_density()) filled += x > 0.0f;
  CHECK(filled > 500);
}

TEST_CASE("CanopyField: a tree outside the domain contributes nothing and is reported", "[canopy]") {
  auto spec = grid(10, 10, 10, 1.0);
  CanopyField canopy(spec);
  const auto r = canopy.add_elements(random_elements(5, 40, {-100.0, 5.0, 0.0}));
  CHECK(r.outside);
  CHECK(r.dropped_area == Approx(r.frontal_area).epsilon(1e-12));
  CHECK(r.dropped_drag_area == Approx(r.drag_area).epsilon(1e-12));
  CHECK(canopy.trees_outside() == 1);
  CHECK(canopy.frontal_area_in_domain() == 0.0);
  CHECK(canopy.drag_in_domain() == 0.0);
  for (float x : canopy.frontal_area_density()) CHECK(x == 0.0f);
  for (float x : canopy.drag_density()) CHECK(x == 0.0f);
  // Below the ground counts as outside too.
  CHECK(canopy.add_elements(random_elements(5, 40, {5.0, 5.0, -50.0})).outside);
  CHECK(canopy.trees_outside() == 2);
  CHECK(canopy.tree_count() == 2);
}

TEST_CASE(
    "CanopyField: a rectangle's columns are those whose centres lie in it, with the frontal area in them",
    "[canopy]") {
  fluid::GridSpec spec = grid(8, 6, 4, 2.0);
  spec.origin = {10.0, -4.0, 0.0};
  CanopyField canopy(spec);
  // Two vertical stems, 6 m tall, frontal area 0.3 and 0.5 m^2 per metre: one in column (1, 1), centre
  // (13, -1); one in column (6, 4), centre (23, 5).
  const auto stem = [](double x, double y, double alpha) {
    fluid::CanopyElement e;
    e.start = {x, y, 0.0};
    e.end = {x, y, 6.0};
    e.frontal_area_per_metre = alpha;
    return e;
  };
  const std::vector<fluid::CanopyElement> stems{stem(12.5, -1.5, 0.3), stem(23.5, 5.5, 0.5)};
  canopy.add_elements(stems);
  // [12, 18] x [-2, 6] holds the centres x 13, 15, 17 and y -1, 1, 3, 5: 12 columns, the first stem only.
  const fluid::CanopyColumns first = canopy.columns_in({12.0, -2.0}, {18.0, 6.0});
  CHECK(first.columns == 12);
  CHECK(first.ground_area == 12 * 4.0);
  CHECK(first.frontal_area == Approx(0.3 * 6.0).epsilon(1e-12));  // sums of a h^3 in double: rounding only
  // Edges included: [13, 23] x [-1, 5] holds the centres 13 .. 23 and -1 .. 5, both stems.
  const fluid::CanopyColumns both = canopy.columns_in({13.0, -1.0}, {23.0, 5.0});
  CHECK(both.columns == 6 * 4);
  CHECK(both.frontal_area == Approx(0.3 * 6.0 + 0.5 * 6.0).epsilon(1e-12));
  CHECK(both.frontal_area == Approx(canopy.frontal_area_in_domain()).epsilon(1e-12));
  // A rectangle between centres holds no column.
  const fluid::CanopyColumns none = canopy.columns_in({13.2, -1.0}, {14.8, 5.0});
  CHECK(none.columns == 0);
  CHECK(none.ground_area == 0.0);
  CHECK(none.frontal_area == 0.0);
}

TEST_CASE(
    "CanopyField: a field that stores only the cells its trees reach gives the whole grid's figures, "
    "bit for bit",
    "[canopy]") {
  auto spec = grid(40, 30, 24, 0.5);
  spec.origin = {100.0, 200.0, 0.0};
  // A bush at (108, 207) inside; one straddling the east edge at (119, 212), whose part outside is dropped.
  const std::array<std::array<double, 3>, 2> at = {{{108, 207, 0}, {119, 212, 0}}};
  // Cells 6..39 along x (103 .. 120 m), 6..29 along y, 0..23: the bushes reach at most 7 m from their base.
  const fluid::CellBox box{{6, 6, 0}, {34, 24, 24}};
  CanopyField whole(spec), boxed(spec, box);
  for (int t = 0; t < 2; ++t) {
    const auto elements = random_elements(17 + t, 150, at[std::size_t(t)]);
    const auto a = whole.add_elements(elements), b = boxed.add_elements(elements);
    CHECK(b.dropped_area == a.dropped_area);
  }
  CHECK(boxed.frontal_area_in_domain() == whole.frontal_area_in_domain());
  CHECK(boxed.drag_in_domain() == whole.drag_in_domain());
  CHECK(boxed.frontal_area_density() == whole.frontal_area_density());
  CHECK(boxed.drag_density() == whole.drag_density());
  CHECK(boxed.occupied_cells() == whole.occupied_cells());
  CHECK(boxed.occupied_cells() > 500);
  for (const auto& [min, max] :
       {std::pair<std::array<double, 2>, std::array<double, 2>>{{104, 203}, {112, 211}},
        {{100, 200}, {120, 215}},
        {{101.2, 214}, {102, 215}}}) {
    const fluid::CanopyColumns a = whole.columns_in(min, max), b = boxed.columns_in(min, max);
    CHECK(b.columns == a.columns);
    CHECK(b.frontal_area == a.frontal_area);
  }
  // An element beyond the box is the caller's error, not a lost area.
  CHECK_THROWS_AS(boxed.add_elements(random_elements(3, 20, {101.0, 201.0, 0.0})), std::logic_error);
  CHECK_THROWS_AS(CanopyField(spec, fluid::CellBox{{30, 0, 0}, {11, 30, 24}}), std::invalid_argument);
}

TEST_CASE("CanopyField: bad arguments throw std::invalid_argument naming the class", "[canopy]") {
  using Catch::Matchers::Contains;
  CHECK_THROWS_WITH(CanopyField(grid(0, 4, 4, 1.0)), Contains("CanopyField"));
  CHECK_THROWS_WITH(CanopyField(grid(4, 4, 4, -1.0)), Contains("CanopyField"));
  CanopyField canopy(grid(4, 4, 4, 1.0));
  CHECK_THROWS_WITH(canopy.add_elements({}), Contains("CanopyField") && Contains("at least one element"));
  const fluid::CanopyElement bad_position{{0, 0, 0}, {1, NAN, 0}, 0.1, 0.1};
  CHECK_THROWS_WITH(canopy.add_elements(std::span(&bad_position, 1)), Contains("CanopyField: element 0"));
  const fluid::CanopyElement negative{{0, 0, 0}, {1, 1, 0}, -0.1, 0.1};
  CHECK_THROWS_AS(canopy.add_elements(std::span(&negative, 1)), std::invalid_argument);
  const fluid::CanopyElement infinite{{0, 0, 0}, {1, 1, 0}, 0.1, INFINITY};
  const fluid::CanopyElement pair[2] = {{{0, 0, 0}, {1, 1, 0}, 0.1, 0.1}, infinite};
  CHECK_THROWS_WITH(canopy.add_elements(pair), Contains("CanopyField: element 1") && Contains("areas"));
  CHECK(canopy.tree_count() == 0);  // nothing was added by the failed calls
  for (float x : canopy.drag_density()) CHECK(x == 0.0f);
}
