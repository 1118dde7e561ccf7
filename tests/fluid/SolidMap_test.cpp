#include "fluid/SolidMap.hpp"

#include <fmt/format.h>
#include <catch2/catch.hpp>

#include "tests/support/TempDir.hpp"

#include <cmath>
#include <cstdint>
#include <filesystem>
#include <fstream>
#include <limits>
#include <numbers>
#include <random>
#include <stdexcept>
#include <string>
#include <string_view>

using fw::fluid::GridSpec;
using fw::fluid::Heightmap;
using fw::fluid::SolidBox;
using fw::fluid::SolidCylinder;
using fw::fluid::SolidMap;
using fw::fluid::SolidSphere;

namespace {

using fw::test::TempDir;

GridSpec grid(int nx, int ny, int nz, double h_m, std::array<double, 3> origin_m = {0, 0, 0}) {
  GridSpec spec;
  spec.nx = nx;
  spec.ny = ny;
  spec.nz = nz;
  spec.h = h_m;
  spec.origin = origin_m;
  return spec;
}

std::string bytes(std::initializer_list<int> values) {
  std::string out;
  for (int v : values) out += static_cast<char>(v);
  return out;
}

// Solid cells in column (i, j); fails when they are not one run from the ground up.
int column_height(const SolidMap& map, int i, int j) {
  int count = 0;
  while (count < map.spec().nz && map.solid(i, j, count)) ++count;
  for (int k = count; k < map.spec().nz; ++k) {
    INFO("column (" << i << ", " << j << ") has a solid cell above the terrain at k = " << k);
    CHECK_FALSE(map.solid(i, j, k));
  }
  return count;
}

// Terrain of the 3 x 2 test image (cell_size 2 m, max_height 8 m) on a 6 x 4 x 10 grid of 1 m cells: the
// north row of pixels is 0, 4, 8 m at x = 1, 3, 5 and the south row is 0. Cells per column, row j = 0 south,
// from the bilinear surface H at the cell centre and the rule "centre z < H".
constexpr int kPgmColumns[4][6] = {
    {0, 0, 0, 0, 0, 0},  // y = 0.5: clamped to the south row
    {0, 0, 1, 1, 2, 2},  // y = 1.5: H = 0.25 * north = 0, 0.25, 0.75, 1.25, 1.75, 2
    {0, 1, 2, 4, 5, 6},  // y = 2.5: H = 0.75 * north = 0, 0.75, 2.25, 3.75, 5.25, 6
    {0, 1, 3, 5, 7, 8},  // y = 3.5: clamped to the north row, H = 0, 1, 3, 5, 7, 8
};

void check_pgm_terrain(const Heightmap& terrain) {
  // The floor sits at z = 100 m: terrain heights count from the domain floor.
  SolidMap map(grid(6, 4, 10, 1.0, {0, 0, 100}));
  const std::size_t added = map.add_terrain(terrain);
  int expected_total = 0;
  for (int j = 0; j < 4; ++j) {
    for (int i = 0; i < 6; ++i) {
      INFO("column (" << i << ", " << j << ")");
      CHECK(column_height(map, i, j) == kPgmColumns[j][i]);
      expected_total += kPgmColumns[j][i];
    }
  }
  CHECK(added == std::size_t(expected_total));
  CHECK(map.solid_count() == std::size_t(expected_total));
}

}  // namespace

TEST_CASE("SolidMap: a new map is all fluid") {
  const SolidMap map(grid(4, 3, 2, 1.0));
  CHECK(map.cells().size() == 24);
  CHECK(map.solid_count() == 0);
  for (auto cell : map.cells()) CHECK(cell == 0);
  CHECK_THROWS_AS(SolidMap(grid(0, 3, 2, 1.0)), std::invalid_argument);
}

TEST_CASE("SolidMap: a box marks the cells whose centres lie inside it") {
  // Box faces on cell boundaries: [12, 15) x [-4, -2) x [3, 4.5) m with h = 0.5 m and origin (10, -5, 2).
  SolidMap map(grid(32, 32, 16, 0.5, {10, -5, 2}));
  const SolidBox box{"shed", {13.5, -3.0, 3.75}, {3.0, 2.0, 1.5}, 0.0};
  const double h = 0.5;
  const std::size_t expected = std::size_t(std::lround(3.0 * 2.0 * 1.5 / (h * h * h)));  // 72
  CHECK(map.add(box) == expected);
  CHECK(map.solid_count() == expected);

  std::size_t counted = 0;
  for (int k = 0; k < 16; ++k)
    for (int j = 0; j < 32; ++j)
      for (int i = 0; i < 32; ++i) {
        const double x = 10 + (i + 0.5) * h, y = -5 + (j + 0.5) * h, z = 2 + (k + 0.5) * h;
        const bool inside = x > 12 && x < 15 && y > -4 && y < -2 && z > 3 && z < 4.5;
        if (map.solid(i, j, k) != inside) FAIL("cell (" << i << ", " << j << ", " << k << ")");
        counted += map.cells()[i + 32 * (j + 32 * k)];
      }
  CHECK(counted == expected);
  CHECK(map.add(box) == 0);  // already solid
}

TEST_CASE("SolidMap: a box yawed 45 degrees counter-clockwise lies along the north-east diagonal") {
  // 8 m x 2 m x 4 m box centred on the cell centre (10.5, 10.5); its long axis turns from east to north-east.
  SolidMap map(grid(21, 21, 4, 1.0));
  map.add(SolidBox{"diagonal", {10.5, 10.5, 2.0}, {8.0, 2.0, 4.0}, 45.0 * std::numbers::pi / 180.0});
  auto solid_at = [&](int di, int dj) { return map.solid(10 + di, 10 + dj, 1); };
  // Along the north-east diagonal: local x = sqrt(2) * d, inside while < 4 m.
  CHECK(solid_at(0, 0));
  CHECK(solid_at(1, 1));
  CHECK(solid_at(2, 2));
  CHECK(solid_at(-2, -2));
  CHECK_FALSE(solid_at(3, 3));  // local x = 4.24 m
  CHECK_FALSE(solid_at(-3, -3));
  // Along the unturned long axis (east): local y = -0.71 d leaves the 1 m half-width at d = 2.
  CHECK(solid_at(1, 0));
  CHECK(solid_at(0, 1));
  CHECK_FALSE(solid_at(2, 0));
  CHECK_FALSE(solid_at(3, 0));
  CHECK_FALSE(solid_at(-2, 0));
  // Along the north-west diagonal (where a clockwise turn would put the box): local y = sqrt(2) * d.
  CHECK_FALSE(solid_at(1, -1));
  CHECK_FALSE(solid_at(-1, 1));
  CHECK_FALSE(solid_at(2, -2));
  // Full height: z from 0 to 4 m.
  for (int k = 0; k < 4; ++k) CHECK(map.solid(12, 12, k));
}

TEST_CASE("SolidMap: a cylinder of radius 10 cells marks pi r^2 H / h^3 cells") {
  SolidMap map(grid(40, 40, 30, 1.0));
  const double r = 10.0, height = 20.0;
  const std::size_t added = map.add(SolidCylinder{"silo", {20.0, 20.0, 0.0}, r, height});
  // Tolerance 2%: the staircase error of a voxelised circle of radius 10 cells is about 1%.
  CHECK(double(added) == Approx(std::numbers::pi * r * r * height).epsilon(0.02));
  CHECK(map.solid(20, 20, 0));
  CHECK(map.solid(20, 20, 19));
  CHECK_FALSE(map.solid(20, 20, 20));  // above the top
  CHECK(map.solid(29, 20, 5));         // x = 29.5, 9.5 m from the axis
  CHECK_FALSE(map.solid(30, 20, 5));   // 10.5 m from the axis
}

TEST_CASE("SolidMap: a sphere of radius 10 cells marks 4/3 pi r^3 / h^3 cells") {
  SolidMap map(grid(40, 40, 30, 0.5, {-10, -10, 0}));
  // r = 5 m = 10 cells of 0.5 m.
  const double r = 5.0, h = 0.5;
  const std::size_t added = map.add(SolidSphere{"dome", {0.0, 0.0, 7.5}, r});
  // Tolerance 2%: the staircase error of a voxelised sphere of radius 10 cells is about 1%.
  CHECK(double(added) * h * h * h == Approx(4.0 / 3.0 * std::numbers::pi * r * r * r).epsilon(0.02));
  CHECK(map.solid(20, 20, 15));
  CHECK(map.solid(29, 20, 15));        // x = 4.75 m from the centre
  CHECK_FALSE(map.solid(30, 20, 15));  // 5.25 m
  CHECK_FALSE(map.solid(27, 27, 15));  // (3.75, 3.75): 5.3 m
}

TEST_CASE("SolidMap: shapes reaching outside the grid mark only the cells inside it") {
  SolidMap map(grid(20, 20, 20, 1.0));
  // A sphere centred on the grid's corner: one octant lies inside.
  const std::size_t octant = map.add(SolidSphere{"corner", {0.0, 0.0, 0.0}, 10.0});
  // Tolerance 2%: the voxelised octant is within about 1%.
  CHECK(double(octant) == Approx(4.0 / 3.0 * std::numbers::pi * 1000.0 / 8.0).epsilon(0.02));
  CHECK(map.add(SolidBox{"far", {1e12, -1e12, 5.0}, {10.0, 10.0, 10.0}, 30.0 * std::numbers::pi / 180.0}) ==
        0);
  CHECK(map.add(SolidCylinder{"below", {10.0, 10.0, -50.0}, 5.0, 10.0}) == 0);
  // A box larger than the domain fills it.
  CHECK(
      map.add(SolidBox{"everything", {10.0, 10.0, 10.0}, {1e9, 1e9, 1e9}, 10.0 * std::numbers::pi / 180.0}) ==
      8000 - octant);
  CHECK(map.solid_count() == 8000);
}

TEST_CASE("SolidMap: overlapping shapes count each cell once") {
  SolidMap map(grid(10, 10, 10, 1.0));
  CHECK(map.add(SolidBox{"a", {3.0, 5.0, 5.0}, {6.0, 10.0, 10.0}, 0.0}) == 600);  // x in [0, 6)
  CHECK(map.add(SolidBox{"b", {7.0, 5.0, 5.0}, {6.0, 10.0, 10.0}, 0.0}) ==
        400);  // x in [4, 10): 4 new columns
  CHECK(map.solid_count() == 1000);
}

TEST_CASE("SolidMap: terrain from a P2 PGM marks each column up to the interpolated surface") {
  TempDir dir;
  const std::string path = dir.write("hills.pgm",
                                     "P2\n"
                                     "# north row first\n"
                                     "3 2\n"
                                     "10\n"
                                     "0 5 10\n"
                                     "0 0 0\n");
  check_pgm_terrain(Heightmap::read(path, 2.0, 8.0));
}

TEST_CASE("SolidMap: terrain from 8-bit and 16-bit P5 PGMs marks the same columns as from P2") {
  TempDir dir;
  SECTION("8-bit") {
    const std::string path = dir.write("hills8.pgm", "P5\n3 2\n10\n" + bytes({0, 5, 10, 0, 0, 0}));
    check_pgm_terrain(Heightmap::read(path, 2.0, 8.0));
  }
  SECTION("16-bit big-endian") {
    // 500 = 0x01F4, 1000 = 0x03E8 of maxval 1000.
    const std::string path =
        dir.write("hills16.pgm", "P5\n3 2\n1000\n" + bytes({0, 0, 0x01, 0xF4, 0x03, 0xE8, 0, 0, 0, 0, 0, 0}));
    check_pgm_terrain(Heightmap::read(path, 2.0, 8.0));
  }
}

TEST_CASE("SolidMap: terrain samples are placed by their south-west centre in world coordinates") {
  // Samples 4 m apart at x = 12, 16 and y = 22 (south row: 1, 5 m), 26 (north row: 3, 0 m), as a raster
  // with its corner at (10, 20) gives them (io/scenario/Terrain.cpp).
  const Heightmap terrain(2, 2, 4.0, {12.0, 22.0}, {1.0, 5.0, 3.0, 0.0});
  SolidMap map(grid(8, 8, 8, 1.0, {10, 20, 0}));
  map.add_terrain(terrain);
  CHECK(column_height(map, 0, 0) == 1);  // south-west: 1 m
  CHECK(column_height(map, 1, 1) == 1);
  CHECK(column_height(map, 7, 0) == 5);  // south-east: 5 m
  CHECK(column_height(map, 0, 7) == 3);  // north-west: 3 m
  CHECK(column_height(map, 7, 7) == 0);  // north-east: 0 m, flat ground
  // (13.5, 23.5): bilinear H = 2.27 m.
  CHECK(column_height(map, 3, 3) == 2);
}

TEST_CASE("SolidMap: invalid shapes throw std::invalid_argument naming the shape and the field") {
  SolidMap map(grid(4, 4, 4, 1.0));
  const double nan = std::numeric_limits<double>::quiet_NaN();
  const double inf = std::numeric_limits<double>::infinity();
  using Catch::Contains;
  CHECK_THROWS_AS(map.add(SolidBox{"barn", {1, 1, 1}, {1, -2, 1}, 0}), std::invalid_argument);
  CHECK_THROWS_WITH(map.add(SolidBox{"barn", {1, 1, 1}, {1, -2, 1}, 0}),
                    Contains("SolidMap: box 'barn'") && Contains("size[1]"));
  CHECK_THROWS_WITH(map.add(SolidBox{"barn", {1, 1, 1}, {0, 2, 1}, 0}), Contains("size[0]"));
  CHECK_THROWS_WITH(map.add(SolidBox{"barn", {1, nan, 1}, {1, 2, 1}, 0}), Contains("center[1]"));
  CHECK_THROWS_WITH(map.add(SolidBox{"barn", {1, 1, 1}, {1, 2, 1}, inf}), Contains("yaw"));
  CHECK_THROWS_WITH(map.add(SolidBox{"", {1, 1, 1}, {1, 2, inf}, 0}),
                    Contains("box (unnamed)") && Contains("size[2]"));
  CHECK_THROWS_AS(map.add(SolidCylinder{"silo", {1, 1, 0}, 0.0, 3.0}), std::invalid_argument);
  CHECK_THROWS_WITH(map.add(SolidCylinder{"silo", {1, 1, 0}, 0.0, 3.0}),
                    Contains("SolidMap: cylinder 'silo'") && Contains("radius"));
  CHECK_THROWS_WITH(map.add(SolidCylinder{"silo", {1, 1, 0}, 1.0, -3.0}), Contains("height"));
  CHECK_THROWS_WITH(map.add(SolidCylinder{"silo", {inf, 1, 0}, 1.0, 3.0}), Contains("base[0]"));
  CHECK_THROWS_WITH(map.add(SolidSphere{"dome", {1, 1, 1}, -1.0}),
                    Contains("SolidMap: sphere 'dome'") && Contains("radius"));
  CHECK_THROWS_WITH(map.add(SolidSphere{"dome", {1, 1, nan}, 1.0}), Contains("center[2]"));
  CHECK_THROWS_AS(map.add(SolidSphere{"dome", {1, 1, 1}, nan}), std::invalid_argument);
  CHECK(map.solid_count() == 0);
}

TEST_CASE("SolidMap: solid() rejects cells outside the grid") {
  const SolidMap map(grid(4, 3, 2, 1.0));
  CHECK_FALSE(map.solid(3, 2, 1));
  CHECK_THROWS_AS(map.solid(4, 0, 0), std::out_of_range);
  CHECK_THROWS_AS(map.solid(0, -1, 0), std::out_of_range);
  CHECK_THROWS_AS(map.solid(0, 0, 2), std::out_of_range);
}
