// The wind grid cut into px x py blocks of whole columns, one block per MPI rank, as PALM cuts its grid.
//
//   fw::fluid::Decomposition d = fw::fluid::Decomposition::make(spec, /*ranks=*/4, std::nullopt, /*halo=*/3);
//   d.blocks();                          // {2, 2}: chosen to exchange the fewest halo cells
//   fw::fluid::Block b = d.block(3);     // rank 3 = block (1, 1): b.first, b.count along x and y
//   d.alignment();                       // every cut lies on a multiple of this many cells (a power of 2)
//
// Rank r holds block (r % px, r / px). Along an axis of n cells cut into p blocks the cuts lie at
// round(b n / (a p)) a for b = 1 .. p - 1, a the alignment: a power of two up to kMaxAlignment that divides
// n and leaves every block at least max(halo, 2) cells, the one that balances the blocks best (the larger on
// a tie; on a periodic axis one that leaves every block even). The alignment is what keeps the
// pressure hierarchy's coarse levels per rank: a block coarsens on its own while its cuts stay whole coarse
// cells (docs/parallel.md). A block is never thinner than the halo, so a halo is only ever exchanged with
// the next block.
//
// make() throws DecompositionError (an std::invalid_argument) before anything is allocated when:
//   - the blocks asked for do not multiply to the ranks;
//   - an axis has fewer cells than its blocks need (max(halo, 2) each): more ranks than the grid can take;
//   - a periodic axis would get a block of an odd cell count (red-black colouring and the pressure
//     hierarchy pair cells across the periodic wrap).
// Without blocks asked for, it takes the valid split that exchanges the fewest halo cells (ties: more
// blocks along y, whose halos are whole rows), and throws only when no split of the ranks is valid.
#pragma once

#include <array>
#include <optional>
#include <stdexcept>
#include <string>

#include "fluid/GridSpec.hpp"
#include "fluid/WindSettings.hpp"

namespace fw::fluid {

struct DecompositionError : std::invalid_argument {
  using std::invalid_argument::invalid_argument;
};

/// One rank's block: cells first .. first + count - 1 along x and y, every z, and the halo it receives on
/// each side: the decomposition's halo where another block lies across that side (a periodic wrap onto
/// itself included only when the axis is cut), else 0.
struct Block {
  std::array<int, 2> first{0, 0};
  std::array<int, 2> count{0, 0};
  std::array<int, 2> halo_low{0, 0}, halo_high{0, 0};
  /// Cells along x or y with the halo: what the rank allocates.
  int extent(int axis) const { return count[axis] + halo_low[axis] + halo_high[axis]; }
};

class Decomposition {
 public:
  /// One block: the whole grid on one rank (before make()).
  Decomposition() = default;
  /// The largest alignment taken: 16 cells keeps four coarse levels of the pressure hierarchy per rank.
  static constexpr int kMaxAlignment = 16;

  /// ranks >= 1; requested: {px, py}, else chosen; halo: the cells a block exchanges with each neighbour
  /// (>= 1). Throws DecompositionError as above.
  static Decomposition make(const GridSpec& spec, int ranks, std::optional<std::array<int, 2>> requested,
                            int halo);

  std::array<int, 2> blocks() const { return blocks_; }
  int ranks() const { return blocks_[0] * blocks_[1]; }
  /// More than one block: the grid is split over ranks, and its stages exchange halos.
  bool splits() const { return ranks() > 1; }
  int halo() const { return halo_; }
  /// Cells along x and y: the cuts lie on multiples of it (1 along an axis that is not cut).
  std::array<int, 2> alignment() const { return alignment_; }
  Block block(int rank) const;
  /// The rank holding block (bx, by), wrapped along a periodic axis; -1 past a non-periodic edge.
  int rank_of(int bx, int by) const;
  /// The rank whose block holds cell column (i, j) (inside the grid).
  int rank_holding(int i, int j) const;
  /// Halo cells all blocks receive per exchange of one cell-centred field (both axes, every z).
  long long halo_cells() const;
  /// "2 x 2 blocks of 32 x 32 cells" or "2 x 1 blocks of 33..31 x 64 cells".
  std::string describe() const;

 private:
  /// The cut before block b along axis a (cuts_[a][0] = 0, cuts_[a][blocks] = cells).
  int cut(int axis, int b) const;

  GridSpec spec_;
  std::array<int, 2> blocks_{1, 1};
  std::array<int, 2> alignment_{1, 1};
  int halo_ = 1;
};

}  // namespace fw::fluid
