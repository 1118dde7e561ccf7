// A rank's block of a cell-centred field with its halo, and the exchange that fills the halo from the
// neighbouring blocks (docs/parallel.md).
//
//   fw::host::BlockArray layout = fw::host::block_array(decomposition, rank, nz, halo);
//   fw::host::HaloExchange halo(cc, world, layout);
//   halo.exchange(field);       // field: layout.cells() floats on the device, x fastest
//
// An exchange runs in two phases, along x and then along y: each sends the block's own cells next to a
// border to the neighbour across it (non-blocking MPI, both sides at once) and writes what comes back into
// the halo. The y phase sends whole rows, x halos included, so the corners arrive from the diagonal blocks
// without messages of their own. A side without a neighbour (a domain face, or an axis that is not cut) has
// no halo and sends nothing. In one process there is nothing to exchange, and exchange() does nothing.
#pragma once

#include <array>
#include <cstddef>
#include <vector>

#include "fluid/Decomposition.hpp"
#include "host/runtime/Communicator.hpp"
#include "host/runtime/ComputeContext.hpp"

namespace fw::host {

/// The layout of a rank's array: its block's cells plus the halo, x fastest, then y, then z.
struct BlockArray {
  std::array<int, 3> extent{1, 1, 1};                                // cells along x, y, z, the halo included
  std::array<int, 2> halo_low{0, 0}, halo_high{0, 0};                // halo cells on each side along x and y
  std::array<int, 2> neighbour_low{-1, -1}, neighbour_high{-1, -1};  // the rank across each side, or -1
  std::array<int, 2> origin{0, 0};  // the global index of local cell (0, 0) (negative across a periodic wrap)

  std::size_t cells() const { return std::size_t(extent[0]) * extent[1] * extent[2]; }
};

/// Rank `rank`'s block of a level whose cuts are the decomposition's divided by 2^level, with `halo` cells
/// on every side that has a neighbour, nz cells deep.
BlockArray block_array(const fluid::Decomposition& decomposition, int rank, int level, int nz, int halo);

class HaloExchange {
 public:
  HaloExchange(ComputeContext& cc, const Communicator& world, const BlockArray& layout);

  /// Fills the halo of `field` (layout.cells() floats) from the neighbours' own cells. Collective with the
  /// neighbours: every rank of the decomposition calls it for the same field. Blocks until done.
  void exchange(cl::Buffer& field);
  /// Bytes sent by this rank in one exchange.
  std::size_t bytes_sent() const { return bytes_sent_; }
  const BlockArray& layout() const { return layout_; }

 private:
  void exchange_axis(cl::Buffer& field, int axis);

  ComputeContext& cc_;
  const Communicator& world_;
  BlockArray layout_;
  std::size_t bytes_sent_ = 0;
  std::array<std::vector<float>, 4> staging_;  // send low, send high, receive low, receive high
};

}  // namespace fw::host
