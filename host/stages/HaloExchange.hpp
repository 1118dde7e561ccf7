// A rank's block of a cell-centred field with its halo, and the exchange that fills the halo from the
// neighbouring blocks (docs/parallel.md).
//
//   fw::host::BlockArray layout = fw::host::block_array(decomposition, rank, 0, nz, halo);  // BlockGrid.hpp
//   fw::host::HaloExchange halo(cc, world, layout);
//   halo.exchange(field);       // field: layout.cells() floats on the device, x fastest
//
// An exchange runs in two phases, along x and then along y: each sends the block's own cells next to a
// border to the neighbour across it (non-blocking MPI, both sides at once) and writes what comes back into
// the halo. The y phase sends whole rows, x halos included, so the corners arrive from the diagonal blocks
// without messages of their own. A side without a neighbour (a domain face, or an axis that is not cut) has
// no halo and sends nothing. In one process there is nothing to exchange, and exchange() does nothing.
//
// Each exchange counts what it sent and the wall time it took (traffic()), for `forestwind bench` over
// ranks: the bytes are the halo's floats, the time runs from the queue's last kernel to the last halo
// written back, so it holds the device-host copies (copy_seconds) and the wait for the neighbours, which
// includes waiting for a slower neighbour to reach the exchange.
//
//   const fw::host::HaloTraffic before = halo.traffic();
//   halo.exchange(field);
//   const fw::host::HaloTraffic one = halo.traffic() - before;   // one.bytes, one.messages, one.seconds
#pragma once

#include <array>
#include <cstddef>
#include <limits>
#include <vector>

#include "host/runtime/Communicator.hpp"
#include "host/runtime/ComputeContext.hpp"
#include "host/stages/BlockGrid.hpp"

namespace fw::host {

/// What halo exchanges sent, and the wall time they took; zero in one process.
struct HaloTraffic {
  long long messages = 0;     // MPI messages sent
  long long bytes = 0;        // bytes sent (the halo's floats)
  double seconds = 0.0;       // wall time of the exchanges, copies and waits included
  double copy_seconds = 0.0;  // of which the device-host copies of the sent and received halos

  HaloTraffic& operator+=(const HaloTraffic& other);
  /// The traffic since `earlier`, a snapshot of the same counters.
  HaloTraffic operator-(const HaloTraffic& earlier) const;
};

class HaloExchange {
 public:
  HaloExchange(ComputeContext& cc, const Communicator& world, const BlockArray& layout);

  /// Fills the halo of `field` (layout.cells() floats) from the neighbours' own cells, or its `depth` cells
  /// next to the block when a stencil reads no further (the rest keep what they held). Collective with the
  /// neighbours: every rank of the decomposition calls it for the same field and depth. Blocks until done.
  void exchange(cl::Buffer& field, int depth = kWholeHalo);
  static constexpr int kWholeHalo = std::numeric_limits<int>::max();
  /// On a face array across a cut periodic axis: the domain's face n (the last block's) becomes a copy of
  /// face 0 (block 0's), as a whole grid's boundary pass makes it. Nothing elsewhere. Collective with the
  /// seam's two blocks.
  void copy_seam(cl::Buffer& field);
  /// Everything this exchange has sent since it was made (exchange() and copy_seam()).
  const HaloTraffic& traffic() const { return traffic_; }

  /// A box of the layout's values: first value and extent along x, y, z.
  struct Box {
    std::array<std::size_t, 3> first, extent;
    std::size_t values() const { return extent[0] * extent[1] * extent[2]; }
  };

 private:
  void exchange_axis(cl::Buffer& field, int axis, int depth);
  /// The strip along `axis` from `at`, `width` values wide, over the whole of the other axes.
  Box strip(int axis, int at, int width) const;
  /// A box as the rectangle calls take it: device origin and region (x in bytes), the layout's pitches and
  /// those of a packed host copy.
  struct Rect {
    std::array<cl::size_type, 3> origin, region;
    std::size_t row, slice, host_row, host_slice;
  };
  Rect rect(const Box& box) const;
  /// Blocking copies of a box of `field` to and from `host` (resized to the box), timed into
  /// traffic_.copy_seconds.
  void read_box(cl::Buffer& field, const Box& box, std::vector<float>& host);
  void write_box(cl::Buffer& field, const Box& box, const std::vector<float>& host);
  /// MPI_Isend of `values` to `peer`, counted in traffic_.
  void send(const std::vector<float>& values, int peer, int message_tag, MPI_Request& request);

  ComputeContext& cc_;
  const Communicator& world_;
  BlockArray layout_;
  std::array<std::vector<float>, 4> staging_;  // send low, send high, receive low, receive high
  HaloTraffic traffic_;
};

}  // namespace fw::host
