// fluid/Decomposition: blocks tile the grid, cuts are aligned, the choice exchanges the fewest halo cells,
// and splits that cannot work are refused with the reason.
#include "fluid/Decomposition.hpp"

#include <catch2/catch.hpp>

#include <set>
#include <vector>

using fw::fluid::Block;
using fw::fluid::BoundaryType;
using fw::fluid::Decomposition;
using fw::fluid::DecompositionError;
using fw::fluid::GridSpec;

namespace {

GridSpec grid(int nx, int ny, int nz, bool periodic_x = false) {
  GridSpec spec;
  spec.nx = nx, spec.ny = ny, spec.nz = nz, spec.h = 1.0;
  if (periodic_x) spec.boundary[FW_FACE_WEST] = spec.boundary[FW_FACE_EAST] = BoundaryType::periodic;
  return spec;
}

// Every column lies in exactly one block, and rank_holding names that block.
void check_tiles(const GridSpec& spec, const Decomposition& d) {
  std::vector<int> owner(std::size_t(spec.nx) * spec.ny, -1);
  for (int r = 0; r < d.ranks(); ++r) {
    const Block b = d.block(r);
    for (int a = 0; a < 2; ++a) {
      CHECK(b.count[a] >= d.halo());
      if (d.blocks()[a] > 1) CHECK(b.first[a] % d.alignment()[a] == 0);
    }
    for (int j = b.first[1]; j < b.first[1] + b.count[1]; ++j)
      for (int i = b.first[0]; i < b.first[0] + b.count[0]; ++i) {
        CHECK(owner[i + std::size_t(spec.nx) * j] == -1);
        owner[i + std::size_t(spec.nx) * j] = r;
        CHECK(d.rank_holding(i, j) == r);
      }
  }
  CHECK(std::set<int>(owner.begin(), owner.end()).count(-1) == 0);
}

}  // namespace

TEST_CASE("Decomposition: the blocks tile the grid on aligned cuts", "[fluid]") {
  const GridSpec spec = grid(96, 40, 8);
  for (int ranks : {1, 2, 3, 4, 6, 8}) {
    INFO(ranks << " ranks");
    const Decomposition d = Decomposition::make(spec, ranks, std::nullopt, 3);
    CHECK(d.ranks() == ranks);
    check_tiles(spec, d);
  }
  // 96 = 6 x 16: three blocks of 32 cells along x, cut on multiples of 16; four of 24 on multiples of 8 (16
  // would leave 32, 16, 32, 16).
  CHECK(Decomposition::make(spec, 4, std::array<int, 2>{4, 1}, 3).describe() ==
        "4 x 1 blocks of 24 x 40 x 8 cells");
  const Decomposition d = Decomposition::make(spec, 3, std::array<int, 2>{3, 1}, 3);
  CHECK(d.alignment()[0] == 16);
  CHECK(d.block(1).first[0] == 32);
  CHECK(d.block(1).count[0] == 32);
  CHECK(d.describe() == "3 x 1 blocks of 32 x 40 x 8 cells");
}

TEST_CASE("Decomposition: the automatic split exchanges the fewest halo cells", "[fluid]") {
  // A long grid is cut across its length: 4 x 1 exchanges 3 faces of 16 x 8 cells a halo deep, 2 x 2 more.
  const GridSpec spec = grid(256, 16, 8);
  const Decomposition d = Decomposition::make(spec, 4, std::nullopt, 3);
  CHECK(d.blocks() == std::array<int, 2>{4, 1});
  // Inner blocks receive two faces, the end blocks one: 6 faces of 16 x 8 cells, 3 deep.
  CHECK(d.halo_cells() == 6LL * 16 * 8 * 3);
  for (auto blocks : {std::array<int, 2>{2, 2}, std::array<int, 2>{1, 4}})
    CHECK(Decomposition::make(spec, 4, blocks, 3).halo_cells() > d.halo_cells());
  // A square grid: 2 x 2.
  CHECK(Decomposition::make(grid(64, 64, 8), 4, std::nullopt, 3).blocks() == std::array<int, 2>{2, 2});
  // A tie goes to cuts across y, whose halos are whole rows of x: 1 x 2 on a square grid.
  CHECK(Decomposition::make(grid(64, 64, 8), 2, std::nullopt, 3).blocks() == std::array<int, 2>{1, 2});
}

TEST_CASE("Decomposition: neighbours wrap on periodic axes only", "[fluid]") {
  const Decomposition open = Decomposition::make(grid(64, 64, 4), 4, std::array<int, 2>{4, 1}, 2);
  CHECK(open.rank_of(-1, 0) == -1);
  CHECK(open.rank_of(4, 0) == -1);
  CHECK(open.rank_of(2, 0) == 2);
  CHECK(open.block(0).halo_low == std::array<int, 2>{0, 0});
  CHECK(open.block(0).halo_high == std::array<int, 2>{2, 0});
  CHECK(open.block(0).extent(0) == 16 + 2);
  const Decomposition periodic = Decomposition::make(grid(64, 64, 4, true), 4, std::array<int, 2>{4, 1}, 2);
  CHECK(periodic.rank_of(-1, 0) == 3);
  CHECK(periodic.rank_of(4, 0) == 0);
  CHECK(periodic.block(0).halo_low == std::array<int, 2>{2, 0});  // from block 3, across the wrap
  // Periodic: every block receives two faces of 64 x 4 cells, 2 deep.
  CHECK(periodic.halo_cells() == 4LL * 2 * 64 * 4 * 2);
}

TEST_CASE("Decomposition: splits that cannot work are refused with the reason", "[fluid]") {
  const GridSpec spec = grid(32, 32, 8);
  CHECK_THROWS_WITH(Decomposition::make(spec, 4, std::array<int, 2>{3, 1}, 3),
                    Catch::Contains("must multiply to the ranks"));
  // 32 cells with a halo of 3 take at most 10 blocks of 3 cells.
  CHECK_THROWS_WITH(Decomposition::make(spec, 11, std::array<int, 2>{11, 1}, 3),
                    Catch::Contains("more ranks than the grid can be split into"));
  CHECK_THROWS_WITH(Decomposition::make(spec, 17 * 17, std::nullopt, 2),
                    Catch::Contains("no split of 289 ranks"));
  // 5 blocks along a periodic axis of 18 cells with a halo of 3: cuts on even cells leave a block of 2, so
  // the cuts fall on single cells, 4, 3, 4, 3, 4: odd blocks on a periodic axis.
  CHECK_THROWS_WITH(Decomposition::make(grid(18, 8, 4, true), 5, std::array<int, 2>{5, 1}, 3),
                    Catch::Contains("periodic x axis of 18 cells leave a block of 3 cells"));
  // The same cut on an axis that is not periodic is valid.
  CHECK(Decomposition::make(grid(18, 8, 4), 5, std::array<int, 2>{5, 1}, 3).alignment()[0] == 1);
  CHECK_THROWS_AS(Decomposition::make(spec, 0, std::nullopt, 3), DecompositionError);
}
