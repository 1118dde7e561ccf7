#include "fluid/PressureLevels.hpp"

#include <catch2/catch.hpp>

#include <cmath>
#include <cstdint>
#include <random>
#include <stdexcept>
#include <vector>

#include "fluid/ReferenceStages.hpp"

using fw::fluid::BoundaryType;
using fw::fluid::GridSpec;
using fw::fluid::PressureLevel;

namespace {

GridSpec grid(int nx, int ny, int nz) {
  GridSpec spec;
  spec.nx = nx;
  spec.ny = ny;
  spec.nz = nz;
  spec.h = 1.0;
  return spec;
}

void set_axis(GridSpec& spec, int axis, BoundaryType lo, BoundaryType hi) {
  spec.boundary[2 * axis] = lo;
  spec.boundary[2 * axis + 1] = hi;
}

std::size_t index(int nx, int ny, int i, int j, int k) {
  return std::size_t(i) + std::size_t(nx) * (std::size_t(j) + std::size_t(ny) * std::size_t(k));
}

std::uint8_t mask_at(const PressureLevel& level, int i, int j, int k) {
  return level.mask[index(level.nx, level.ny, i, j, k)];
}

bool has_bit(std::uint8_t m, int face) {
  return (m & (1u << face)) != 0;
}

bool is_fluid(std::uint8_t m) {
  return (m & FW_MASK_FLUID) != 0;
}

// Cell across face f of (i,j,k) on `level`. Returns false when the face is on the domain boundary and does
// not wrap (non-periodic axis, or a periodic axis of one cell).
bool neighbour(const PressureLevel& level, const GridSpec& spec, int i, int j, int k, int f, int out[3]) {
  const int n[3] = {level.nx, level.ny, level.nz};
  out[0] = i;
  out[1] = j;
  out[2] = k;
  const int a = f / 2;
  out[a] += (f % 2) ? 1 : -1;
  if (out[a] >= 0 && out[a] < n[a]) return true;
  if (!spec.periodic(a) || n[a] == 1) return false;
  out[a] = (out[a] + n[a]) % n[a];
  return true;
}

// One byte per cell, solid with probability `fraction`.
std::vector<std::uint8_t> random_solids(const GridSpec& spec, double fraction, unsigned seed) {
  std::mt19937 random(seed);
  std::bernoulli_distribution solid(fraction);
  std::vector<std::uint8_t> cells(spec.cell_count());
  for (auto& c : cells) c = solid(random) ? 1 : 0;
  return cells;
}

std::vector<float> random_vector(std::size_t n, std::mt19937& random) {
  std::uniform_real_distribution<float> value(-1.0f, 1.0f);
  std::vector<float> v(n);
  for (auto& x : v) x = value(random);
  return v;
}

// Sum over fluid cells of a_c * b_c, in double.
double fluid_dot(const PressureLevel& level, const std::vector<float>& a, const std::vector<float>& b) {
  double sum = 0.0;
  for (std::size_t c = 0; c < level.cell_count(); ++c)
    if (is_fluid(level.mask[c])) sum += double(a[c]) * double(b[c]);
  return sum;
}

// Every open bit is consistent: only fluid cells have open bits; an open face to a cell inside the domain
// (or across a periodic wrap) leads to a fluid cell that has the opposite face open; an open face on the
// domain boundary is an outflow face. Returns the number of violations (each is reported through INFO).
int check_symmetric(const PressureLevel& level, const GridSpec& spec) {
  int violations = 0;
  for (int k = 0; k < level.nz; ++k)
    for (int j = 0; j < level.ny; ++j)
      for (int i = 0; i < level.nx; ++i) {
        const std::uint8_t m = mask_at(level, i, j, k);
        if (!is_fluid(m)) {
          if ((m & FW_MASK_OPEN_ALL) != 0) {
            UNSCOPED_INFO("solid cell (" << i << ", " << j << ", " << k << ") has open bits");
            ++violations;
          }
          continue;
        }
        for (int f = 0; f < 6; ++f) {
          if (!has_bit(m, f)) continue;
          int nb[3];
          if (!neighbour(level, spec, i, j, k, f, nb)) {
            if (spec.boundary[f] != BoundaryType::outflow) {
              UNSCOPED_INFO("cell (" << i << ", " << j << ", " << k << ") face " << f
                                     << " is open on a closed domain boundary");
              ++violations;
            }
            continue;
          }
          const std::uint8_t other = mask_at(level, nb[0], nb[1], nb[2]);
          if (!is_fluid(other) || !has_bit(other, f ^ 1)) {
            UNSCOPED_INFO("cell (" << i << ", " << j << ", " << k << ") face " << f << " is open but cell ("
                                   << nb[0] << ", " << nb[1] << ", " << nb[2] << ") face " << (f ^ 1)
                                   << " is not");
            ++violations;
          }
        }
      }
  return violations;
}

// A grid with an outflow face, a periodic axis and no-slip ground, with random solids.
GridSpec mixed_grid(int nx, int ny, int nz) {
  GridSpec spec = grid(nx, ny, nz);
  set_axis(spec, 0, BoundaryType::inflow, BoundaryType::outflow);
  set_axis(spec, 1, BoundaryType::periodic, BoundaryType::periodic);
  set_axis(spec, 2, BoundaryType::no_slip, BoundaryType::slip);
  return spec;
}

}  // namespace

TEST_CASE(
    "PressureLevels: an outflow east face opens the east column's +x face, a slip west face stays closed") {
  GridSpec spec = grid(4, 3, 2);
  spec.boundary[FW_FACE_EAST] = BoundaryType::outflow;
  const PressureLevel level = fw::fluid::build_fine_pressure_level(spec, {});
  REQUIRE(level.nx == 4);
  REQUIRE(level.ny == 3);
  REQUIRE(level.nz == 2);
  REQUIRE(level.mask.size() == 24);
  for (int k = 0; k < 2; ++k)
    for (int j = 0; j < 3; ++j) {
      INFO("j = " << j << ", k = " << k);
      const std::uint8_t east = mask_at(level, 3, j, k);
      const std::uint8_t west = mask_at(level, 0, j, k);
      CHECK(is_fluid(east));
      CHECK(has_bit(east, FW_FACE_EAST));
      CHECK(has_bit(east, FW_FACE_WEST));  // interior neighbour
      CHECK(is_fluid(west));
      CHECK_FALSE(has_bit(west, FW_FACE_WEST));
      CHECK(has_bit(west, FW_FACE_EAST));
      // The slip walls along y and z stay closed.
      CHECK(has_bit(east, FW_FACE_SOUTH) == (j > 0));
      CHECK(has_bit(east, FW_FACE_NORTH) == (j < 2));
      CHECK(has_bit(east, FW_FACE_GROUND) == (k > 0));
      CHECK(has_bit(east, FW_FACE_TOP) == (k < 1));
    }
  // An interior cell is open on every face.
  CHECK(mask_at(level, 1, 1, 0) == (FW_MASK_FLUID | (63 & ~(1 << FW_FACE_GROUND))));
  CHECK(mask_at(level, 2, 1, 1) == (FW_MASK_FLUID | (63 & ~(1 << FW_FACE_TOP))));
}

TEST_CASE("PressureLevels: every face of the domain boundary is open only where it is outflow or periodic") {
  for (int f = 0; f < 6; ++f) {
    GridSpec spec = grid(3, 4, 2);
    spec.boundary[f] = BoundaryType::outflow;
    const PressureLevel level = fw::fluid::build_fine_pressure_level(spec, {});
    INFO("outflow face " << fw::fluid::face_name(f));
    for (int k = 0; k < 2; ++k)
      for (int j = 0; j < 4; ++j)
        for (int i = 0; i < 3; ++i) {
          const std::uint8_t m = mask_at(level, i, j, k);
          for (int g = 0; g < 6; ++g) {
            int nb[3];
            const bool inside = neighbour(level, spec, i, j, k, g, nb);
            CHECK(has_bit(m, g) == (inside || g == f));
          }
        }
  }
}

TEST_CASE("PressureLevels: periodic axes set the wrap bits on both boundary layers") {
  GridSpec spec = grid(4, 6, 2);
  set_axis(spec, 1, BoundaryType::periodic, BoundaryType::periodic);
  const PressureLevel level = fw::fluid::build_fine_pressure_level(spec, {});
  for (int k = 0; k < 2; ++k)
    for (int i = 0; i < 4; ++i) {
      INFO("i = " << i << ", k = " << k);
      CHECK(has_bit(mask_at(level, i, 0, k), FW_FACE_SOUTH));
      CHECK(has_bit(mask_at(level, i, 5, k), FW_FACE_NORTH));
      // x is slip: no wrap.
      CHECK_FALSE(has_bit(mask_at(level, 0, 0, k), FW_FACE_WEST));
      CHECK_FALSE(has_bit(mask_at(level, 3, 0, k), FW_FACE_EAST));
    }
  CHECK(check_symmetric(level, spec) == 0);

  SECTION("a solid cell across the wrap closes the wrap face") {
    std::vector<std::uint8_t> solid(spec.cell_count(), 0);
    solid[index(4, 6, 1, 5, 0)] = 1;
    const PressureLevel with_solid = fw::fluid::build_fine_pressure_level(spec, solid);
    CHECK_FALSE(has_bit(mask_at(with_solid, 1, 0, 0), FW_FACE_SOUTH));
    CHECK(has_bit(mask_at(with_solid, 2, 0, 0), FW_FACE_SOUTH));
    CHECK(check_symmetric(with_solid, spec) == 0);
  }
  SECTION("a periodic axis of one cell couples to itself and sets no bits") {
    GridSpec flat = grid(4, 4, 1);
    set_axis(flat, 2, BoundaryType::periodic, BoundaryType::periodic);
    const PressureLevel one = fw::fluid::build_fine_pressure_level(flat, {});
    for (auto m : one.mask) {
      CHECK_FALSE(has_bit(m, FW_FACE_GROUND));
      CHECK_FALSE(has_bit(m, FW_FACE_TOP));
    }
  }
}

TEST_CASE("PressureLevels: solid cells have no FLUID bit and close the faces of their fluid neighbours") {
  GridSpec spec = grid(4, 4, 4);
  spec.boundary[FW_FACE_EAST] = BoundaryType::outflow;
  std::vector<std::uint8_t> solid(spec.cell_count(), 0);
  solid[index(4, 4, 1, 2, 1)] = 1;
  const PressureLevel level = fw::fluid::build_fine_pressure_level(spec, solid);
  CHECK(mask_at(level, 1, 2, 1) == 0);
  std::size_t fluid = 0;
  for (auto m : level.mask) fluid += is_fluid(m) ? 1 : 0;
  CHECK(fluid == spec.cell_count() - 1);
  CHECK_FALSE(has_bit(mask_at(level, 0, 2, 1), FW_FACE_EAST));
  CHECK_FALSE(has_bit(mask_at(level, 2, 2, 1), FW_FACE_WEST));
  CHECK_FALSE(has_bit(mask_at(level, 1, 1, 1), FW_FACE_NORTH));
  CHECK_FALSE(has_bit(mask_at(level, 1, 3, 1), FW_FACE_SOUTH));
  CHECK_FALSE(has_bit(mask_at(level, 1, 2, 0), FW_FACE_TOP));
  CHECK_FALSE(has_bit(mask_at(level, 1, 2, 2), FW_FACE_GROUND));
  // The neighbours keep their other faces.
  CHECK(has_bit(mask_at(level, 2, 2, 1), FW_FACE_EAST));
  CHECK(has_bit(mask_at(level, 1, 1, 1), FW_FACE_SOUTH));
  CHECK(check_symmetric(level, spec) == 0);
}

TEST_CASE("PressureLevels: a solid map of the wrong size is rejected") {
  const GridSpec spec = grid(4, 4, 4);
  CHECK_THROWS_AS(fw::fluid::build_fine_pressure_level(spec, std::vector<std::uint8_t>(63, 0)),
                  std::invalid_argument);
  CHECK_THROWS_AS(fw::fluid::build_fine_pressure_level(grid(0, 4, 4), {}), std::invalid_argument);
}

TEST_CASE(
    "PressureLevels: fine masks with random solids are symmetric and open exactly between fluid cells") {
  for (unsigned seed : {1u, 2u, 3u}) {
    const GridSpec spec = mixed_grid(7, 6, 5);
    const auto solid = random_solids(spec, 0.3, seed);
    const PressureLevel level = fw::fluid::build_fine_pressure_level(spec, solid);
    INFO("seed " << seed);
    CHECK(check_symmetric(level, spec) == 0);
    for (int k = 0; k < spec.nz; ++k)
      for (int j = 0; j < spec.ny; ++j)
        for (int i = 0; i < spec.nx; ++i) {
          const std::uint8_t m = mask_at(level, i, j, k);
          const bool fluid = solid[index(spec.nx, spec.ny, i, j, k)] == 0;
          REQUIRE(is_fluid(m) == fluid);
          if (!fluid) continue;
          for (int f = 0; f < 6; ++f) {
            int nb[3];
            const bool open = neighbour(level, spec, i, j, k, f, nb)
                                  ? solid[index(spec.nx, spec.ny, nb[0], nb[1], nb[2])] == 0
                                  : spec.boundary[f] == BoundaryType::outflow;
            CHECK(has_bit(m, f) == open);
          }
        }
  }
}

TEST_CASE("PressureLevels: coarsening halves every dimension, rounding up") {
  const GridSpec spec = grid(7, 6, 1);
  const PressureLevel fine = fw::fluid::build_fine_pressure_level(spec, {});
  const PressureLevel coarse = fw::fluid::coarsen_pressure_level(fine, spec);
  CHECK(coarse.nx == 4);
  CHECK(coarse.ny == 3);
  CHECK(coarse.nz == 1);
  CHECK(coarse.mask.size() == 12);
  const PressureLevel coarser = fw::fluid::coarsen_pressure_level(coarse, spec);
  CHECK(coarser.nx == 2);
  CHECK(coarser.ny == 2);
  CHECK(coarser.nz == 1);
}

TEST_CASE(
    "PressureLevels: a coarse cell is fluid iff a child is, and its faces are open iff children across "
    "them are") {
  GridSpec spec = grid(9, 8, 5);
  set_axis(spec, 0, BoundaryType::inflow, BoundaryType::outflow);
  set_axis(spec, 1, BoundaryType::periodic, BoundaryType::periodic);
  // Solid 2x2x2 blocks (so that some coarse cells are all solid) plus scattered single solid cells.
  std::mt19937 random(42);
  std::bernoulli_distribution block(0.3), single(0.2);
  std::vector<std::uint8_t> solid(spec.cell_count(), 0);
  for (int K = 0; K < 3; ++K)
    for (int J = 0; J < 4; ++J)
      for (int I = 0; I < 5; ++I) {
        const bool whole = block(random);
        for (int k = 2 * K; k < std::min(2 * K + 2, spec.nz); ++k)
          for (int j = 2 * J; j < 2 * J + 2; ++j)
            for (int i = 2 * I; i < std::min(2 * I + 2, spec.nx); ++i)
              solid[index(spec.nx, spec.ny, i, j, k)] = (whole || single(random)) ? 1 : 0;
      }
  const PressureLevel fine = fw::fluid::build_fine_pressure_level(spec, solid);
  const PressureLevel coarse = fw::fluid::coarsen_pressure_level(fine, spec);
  REQUIRE(coarse.nx == 5);
  REQUIRE(coarse.ny == 4);
  REQUIRE(coarse.nz == 3);
  auto fine_fluid = [&](int i, int j, int k) {
    return i < fine.nx && j < fine.ny && k < fine.nz && is_fluid(mask_at(fine, i, j, k));
  };
  int all_solid = 0;
  for (int K = 0; K < coarse.nz; ++K)
    for (int J = 0; J < coarse.ny; ++J)
      for (int I = 0; I < coarse.nx; ++I) {
        INFO("coarse cell (" << I << ", " << J << ", " << K << ")");
        bool any_child = false;
        for (int c = 0; c < 8; ++c)
          any_child = any_child || fine_fluid(2 * I + (c & 1), 2 * J + ((c >> 1) & 1), 2 * K + (c >> 2));
        const std::uint8_t m = mask_at(coarse, I, J, K);
        CHECK(is_fluid(m) == any_child);
        all_solid += any_child ? 0 : 1;
        // Interior +x, +y, +z faces: open iff some pair of fine cells across the face is fluid on both sides.
        const int C[3] = {I, J, K};
        const int nc[3] = {coarse.nx, coarse.ny, coarse.nz};
        for (int a = 0; a < 3; ++a) {
          if (C[a] + 1 >= nc[a]) continue;
          bool pair = false;
          for (int s = 0; s < 2; ++s)
            for (int t = 0; t < 2; ++t) {
              int lo[3], hi[3];
              const int b = (a + 1) % 3, c = (a + 2) % 3;
              lo[a] = 2 * C[a] + 1;
              hi[a] = 2 * C[a] + 2;
              lo[b] = hi[b] = 2 * C[b] + s;
              lo[c] = hi[c] = 2 * C[c] + t;
              pair = pair || (fine_fluid(lo[0], lo[1], lo[2]) && fine_fluid(hi[0], hi[1], hi[2]));
            }
          INFO("axis " << a);
          CHECK(has_bit(m, 2 * a + 1) == pair);
        }
      }
  CHECK(all_solid > 0);  // the test covers coarse cells without fluid children
  CHECK(check_symmetric(coarse, spec) == 0);
}

TEST_CASE("PressureLevels: every level of a hierarchy with random solids has symmetric open bits") {
  for (unsigned seed : {5u, 6u}) {
    const GridSpec spec = mixed_grid(13, 16, 11);
    const auto levels = fw::fluid::build_pressure_levels(spec, random_solids(spec, 0.25, seed), 1);
    REQUIRE(levels.size() >= 3);
    for (std::size_t l = 0; l < levels.size(); ++l) {
      INFO("seed " << seed << ", level " << l << ": " << levels[l].nx << " x " << levels[l].ny << " x "
                   << levels[l].nz);
      CHECK(check_symmetric(levels[l], spec) == 0);
      if (l > 0) {
        CHECK(levels[l].nx == (levels[l - 1].nx + 1) / 2);
        CHECK(levels[l].ny == (levels[l - 1].ny + 1) / 2);
        CHECK(levels[l].nz == (levels[l - 1].nz + 1) / 2);
      }
    }
  }
}

TEST_CASE("PressureLevels: coarsening stops before a periodic axis would get an odd cell count") {
  GridSpec spec = grid(24, 8, 8);
  set_axis(spec, 0, BoundaryType::periodic, BoundaryType::periodic);
  const auto levels = fw::fluid::build_pressure_levels(spec, {}, 1);
  // 24 -> 12 -> 6; 3 would be odd.
  REQUIRE(levels.size() == 3);
  CHECK(levels[1].nx == 12);
  CHECK(levels[2].nx == 6);
  CHECK(levels[2].ny == 2);
  CHECK(levels[2].nz == 2);
  CHECK_FALSE(fw::fluid::can_coarsen(levels[2], spec));

  SECTION("without periodicity the same grid coarsens down to one cell") {
    const auto open = fw::fluid::build_pressure_levels(grid(24, 8, 8), {}, 1);
    CHECK(open.back().cell_count() == 1);
    CHECK(open.size() == 6);  // 24, 12, 6, 3, 2, 1 cells along x
    CHECK_FALSE(fw::fluid::can_coarsen(open.back(), grid(24, 8, 8)));
  }
  SECTION("a periodic axis may reach one cell") {
    GridSpec pow2 = grid(8, 4, 4);
    set_axis(pow2, 0, BoundaryType::periodic, BoundaryType::periodic);
    const auto l = fw::fluid::build_pressure_levels(pow2, {}, 1);
    CHECK(l.back().nx == 1);
    CHECK(check_symmetric(l.back(), pow2) == 0);
    for (auto m : l.back().mask) CHECK((m & ((1 << FW_FACE_WEST) | (1 << FW_FACE_EAST))) == 0);
  }
  SECTION("the cell budget stops coarsening too") {
    const auto budget = fw::fluid::build_pressure_levels(grid(32, 32, 32), {}, 512);
    CHECK(budget.back().cell_count() <= 512);
    CHECK(budget[budget.size() - 2].cell_count() > 512);
  }
}

TEST_CASE("PressureLevels: the fine operator is symmetric on random vectors") {
  const GridSpec spec = mixed_grid(8, 6, 5);
  const auto levels = fw::fluid::build_pressure_levels(spec, random_solids(spec, 0.2, 11), 1);
  std::mt19937 random(12);
  for (std::size_t l = 0; l < std::min<std::size_t>(levels.size(), 2); ++l) {
    const PressureLevel& level = levels[l];
    for (int trial = 0; trial < 5; ++trial) {
      const auto x = random_vector(level.cell_count(), random);
      const auto y = random_vector(level.cell_count(), random);
      const auto Ax = fw::fluid::reference::apply_operator(spec, level, x);
      const auto Ay = fw::fluid::reference::apply_operator(spec, level, y);
      const double xAy = fluid_dot(level, x, Ay), yAx = fluid_dot(level, y, Ax);
      const double scale = std::sqrt(fluid_dot(level, x, x) * fluid_dot(level, Ay, Ay));
      INFO("level " << l << ", trial " << trial << ": x.Ay = " << xAy << ", y.Ax = " << yAx);
      // Tolerance: 1e-5 of |x| |Ay|; A y is stored in float (relative rounding 6e-8 per entry).
      CHECK(std::abs(xAy - yAx) <= 1e-5 * scale);
    }
  }
}

TEST_CASE("PressureLevels: with an outflow face the operator is positive definite, without one singular") {
  const GridSpec spec = mixed_grid(8, 6, 5);
  // Few solids, so that no fluid pocket is cut off from the outflow face.
  std::vector<std::uint8_t> solid(spec.cell_count(), 0);
  solid[index(8, 6, 3, 2, 0)] = solid[index(8, 6, 3, 3, 0)] = solid[index(8, 6, 5, 1, 2)] = 1;
  const PressureLevel level = fw::fluid::build_fine_pressure_level(spec, solid);
  std::mt19937 random(7);
  for (int trial = 0; trial < 20; ++trial) {
    const auto x = random_vector(level.cell_count(), random);
    const double xAx = fluid_dot(level, x, fw::fluid::reference::apply_operator(spec, level, x));
    INFO("trial " << trial);
    CHECK(xAx > 0.0);
  }
  // The constant vector: A 1 is non-zero only next to the outflow face, so 1.A1 > 0.
  const std::vector<float> ones(level.cell_count(), 1.0f);
  CHECK(fluid_dot(level, ones, fw::fluid::reference::apply_operator(spec, level, ones)) > 0.0);

  SECTION("closed domain: constants are in the null space") {
    GridSpec closed = spec;
    closed.boundary[FW_FACE_EAST] = BoundaryType::slip;
    REQUIRE_FALSE(closed.has_dirichlet_pressure());
    const PressureLevel closed_level = fw::fluid::build_fine_pressure_level(closed, solid);
    const auto A1 = fw::fluid::reference::apply_operator(closed, closed_level, ones);
    for (float v : A1) CHECK(v == 0.0f);  // exact: integer arithmetic
  }
}
