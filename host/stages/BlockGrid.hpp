// A rank's block of the wind grid with its halo (docs/parallel.md): its layout, its grid as the stages see
// it, and whole-grid arrays cut down to it.
//
//   fw::host::BlockArray cells = fw::host::block_array(decomposition, rank, /*level=*/0, spec.nz, halo);
//   fw::fluid::GridSpec local = fw::host::block_spec(spec, decomposition, cells);  // what FluidStages gets
//   std::vector<std::uint8_t> solid = fw::host::block_of(whole_solid, spec.nx, spec.ny, cells);
//
// The block's arrays are its cells plus the halo on every side where another block lies, x fastest. Its grid
// keeps the domain's boundary condition on the sides that are domain faces, and a cut axis does not wrap
// inside a block: its sides inside the domain become slip walls. What the stages compute near those walls
// is wrong, but it lies in the halo, which an exchange then replaces (host/stages/HaloExchange).
#pragma once

#include <array>
#include <cstddef>
#include <memory>
#include <vector>

#include "fluid/Decomposition.hpp"
#include "fluid/GridSpec.hpp"

namespace fw::host {

class Communicator;

/// The stages over ranks (the wind grid, the trees' samples, the probes): the ranks and this run's
/// decomposition of the grid among them.
struct WindBlocks {
  const Communicator* world = nullptr;
  fluid::Decomposition decomposition;
};

/// The ranks of `world` over `decomposition`, or null where they are one: a process alone runs its stages
/// as a whole grid. The one place outside the runtime that asks how many ranks there are
/// (tests/cli/rank_queries.sh).
std::unique_ptr<WindBlocks> blocks_over(const Communicator* world, const fluid::Decomposition& decomposition);
/// `blocks` where they split the grid over ranks, else null (no blocks, or a single rank's).
const WindBlocks* splitting(const WindBlocks* blocks);

/// The layout of a rank's array: its block's cells plus the halo, x fastest, then y, then z; or the faces
/// of a velocity component across one axis (staggered), one more along that axis.
struct BlockArray {
  std::array<int, 3> extent{1, 1, 1};                                // cells along x, y, z, the halo included
  std::array<int, 2> halo_low{0, 0}, halo_high{0, 0};                // halo cells on each side along x and y
  std::array<int, 2> neighbour_low{-1, -1}, neighbour_high{-1, -1};  // the rank across each side, or -1
  /// Where a side is the domain's periodic seam on a cut axis: the rank across it (else -1). The seam's
  /// face is the domain's face 0 and its face n at once; the rules of a whole grid make face n a copy of
  /// face 0 at each boundary pass (HaloExchange::copy_seam).
  std::array<int, 2> seam_low{-1, -1}, seam_high{-1, -1};
  std::array<int, 2> origin{0, 0};  // the global index of local cell (0, 0) (negative across a periodic wrap)
  int staggered = -1;               // the axis a face array has one more value along; -1: cells

  /// Values along an axis: the cells, or one more for the faces across it.
  int values(int axis) const { return extent[axis] + (staggered == axis ? 1 : 0); }
  std::size_t cells() const { return std::size_t(values(0)) * values(1) * values(2); }
};

/// Rank `rank`'s block of a level whose cuts are the decomposition's divided by 2^level, with `halo` cells
/// on every side that has a neighbour, nz cells deep.
BlockArray block_array(const fluid::Decomposition& decomposition, int rank, int level, int nz, int halo);

/// The faces of velocity component c on a cell layout: one more value along axis c. A face's global index is
/// that of the cell above it; the face between two blocks is computed by both (alike) and sent by neither.
BlockArray face_array(BlockArray cells, int c);

/// The grid of a rank's block (cells: its block_array at level 0): its extent and block_offset (the domain's
/// origin), the domain's boundary conditions on its domain faces, slip on its sides inside the domain.
fluid::GridSpec block_spec(const fluid::GridSpec& spec, const fluid::Decomposition& decomposition,
                           const BlockArray& cells);

/// The block `a` of a whole-grid array of values (x fastest; nx, ny the whole grid's values along x and y,
/// the faces' count for a face array), wrapped across periodic faces. A face array's periodic wrap repeats
/// after nx - 1 faces (its last face is its first).
template <typename T>
std::vector<T> block_of(const std::vector<T>& whole, int nx, int ny, const BlockArray& a) {
  std::vector<T> block(a.cells());
  const auto wrap = [](int i, int n) { return ((i % n) + n) % n; };
  // Along a staggered axis the period is one face fewer than the faces.
  const int period_x = a.staggered == 0 ? nx - 1 : nx, period_y = a.staggered == 1 ? ny - 1 : ny;
  const int ex = a.values(0), ey = a.values(1), ez = a.values(2);
  for (int k = 0; k < ez; ++k)
    for (int j = 0; j < ey; ++j)
      for (int i = 0; i < ex; ++i) {
        int gi = a.origin[0] + i, gj = a.origin[1] + j;
        if (gi < 0 || gi >= nx) gi = wrap(gi, period_x);
        if (gj < 0 || gj >= ny) gj = wrap(gj, period_y);
        block[i + std::size_t(ex) * (j + std::size_t(ey) * k)] =
            whole[gi + std::size_t(nx) * (gj + std::size_t(ny) * k)];
      }
  return block;
}

/// Which block of a decomposition a rank holds, for what is known before any device or message: the
/// estimates and the planner's report of each rank. A null decomposition, or one of a single block, is the
/// whole grid.
struct BlockShare {
  const fluid::Decomposition* decomposition = nullptr;
  int rank = 0;

  /// This process's share under `blocks` (null: one process).
  static BlockShare of(const WindBlocks* blocks);
  bool splits() const { return decomposition != nullptr && decomposition->splits(); }
  /// The rank's cells with the halo, and the grid they make.
  BlockArray block(const fluid::GridSpec& whole) const;
  fluid::GridSpec local(const fluid::GridSpec& whole) const;
  /// The rank's block of a whole-grid array of cells (or of component c's faces), x fastest.
  template <typename T>
  std::vector<T> cut(std::vector<T> values, const fluid::GridSpec& whole, int component = -1) const {
    if (!splits()) return values;
    const BlockArray cells = block(whole);
    const BlockArray a = component < 0 ? cells : face_array(cells, component);
    return block_of(values, whole.nx + (component == 0), whole.ny + (component == 1), a);
  }
};

}  // namespace fw::host
