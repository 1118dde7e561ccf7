#include "host/stages/HaloExchange.hpp"

#include <fmt/format.h>

#include <stdexcept>

namespace fw::host {
namespace {

// Message tags: the axis and the direction the data travels, so that two messages between the same two
// ranks (two blocks along a periodic axis are each other's low and high neighbour) stay apart.
int tag(int axis, bool towards_high) {
  return 2 * axis + (towards_high ? 1 : 0);
}

// A box of cells in the local array: first cell and extent along x, y, z.
struct Box {
  std::array<std::size_t, 3> first, extent;
  std::size_t cells() const { return extent[0] * extent[1] * extent[2]; }
};

// The rectangle calls' pitches of the layout, bytes.
std::array<std::size_t, 2> pitches(const BlockArray& a) {
  const std::size_t row = std::size_t(a.extent[0]) * sizeof(float);
  return {row, row * std::size_t(a.extent[1])};
}

}  // namespace

BlockArray block_array(const fluid::Decomposition& decomposition, int rank, int level, int nz, int halo) {
  const fluid::Block block = decomposition.block(rank);
  const int bx = rank % decomposition.blocks()[0], by = rank / decomposition.blocks()[0];
  const int scale = 1 << level;
  BlockArray a;
  a.extent[2] = nz;
  for (int axis = 0; axis < 2; ++axis) {
    if (block.first[axis] % scale != 0 || block.count[axis] % scale != 0)
      throw std::logic_error(
          fmt::format("block_array: rank {}'s block does not coarsen to level {}", rank, level));
    a.halo_low[axis] = block.halo_low[axis] > 0 ? halo : 0;
    a.halo_high[axis] = block.halo_high[axis] > 0 ? halo : 0;
    a.extent[axis] = block.count[axis] / scale + a.halo_low[axis] + a.halo_high[axis];
    a.origin[axis] = block.first[axis] / scale - a.halo_low[axis];
    std::array<int, 2> below{bx, by}, above{bx, by};
    --below[axis], ++above[axis];
    a.neighbour_low[axis] = a.halo_low[axis] > 0 ? decomposition.rank_of(below[0], below[1]) : -1;
    a.neighbour_high[axis] = a.halo_high[axis] > 0 ? decomposition.rank_of(above[0], above[1]) : -1;
  }
  return a;
}

HaloExchange::HaloExchange(ComputeContext& cc, const Communicator& world, const BlockArray& layout)
    : cc_(cc), world_(world), layout_(layout) {}

void HaloExchange::exchange(cl::Buffer& field) {
  if (!world_.uses_mpi() || world_.size() == 1) return;
  bytes_sent_ = 0;
  exchange_axis(field, 0);
  exchange_axis(field, 1);
}

void HaloExchange::exchange_axis(cl::Buffer& field, int axis) {
  const BlockArray& a = layout_;
  const int low = a.neighbour_low[axis], high = a.neighbour_high[axis];
  if (low < 0 && high < 0) return;
  const auto [row_pitch, slice_pitch] = pitches(a);
  // The strip along `axis` from `at`, `width` cells wide, over the whole of the other axes.
  const auto strip = [&](int at, int width) {
    Box box{{0, 0, 0}, {std::size_t(a.extent[0]), std::size_t(a.extent[1]), std::size_t(a.extent[2])}};
    box.first[axis] = std::size_t(at);
    box.extent[axis] = std::size_t(width);
    return box;
  };
  const auto rect = [&](const Box& box) {
    return std::array<cl::size_type, 3>{box.first[0] * sizeof(float), box.first[1], box.first[2]};
  };
  const auto region = [&](const Box& box) {
    return std::array<cl::size_type, 3>{box.extent[0] * sizeof(float), box.extent[1], box.extent[2]};
  };
  const std::array<cl::size_type, 3> host_origin{0, 0, 0};
  // What each neighbour's halo holds: the own cells next to the border, as deep as that halo.
  const Box send_low = strip(a.halo_low[axis], a.halo_low[axis]);
  const Box send_high = strip(a.extent[axis] - 2 * a.halo_high[axis], a.halo_high[axis]);
  const Box receive_low = strip(0, a.halo_low[axis]);
  const Box receive_high = strip(a.extent[axis] - a.halo_high[axis], a.halo_high[axis]);

  std::vector<MPI_Request> requests;
  const auto post = [&](int peer, const Box& out, const Box& in, std::vector<float>& send,
                        std::vector<float>& receive, bool towards_high) {
    send.resize(out.cells());
    receive.resize(in.cells());
    const auto host_pitch = [](const Box& box) { return box.extent[0] * sizeof(float); };
    cc_.queue().enqueueReadBufferRect(field, CL_TRUE, rect(out), host_origin, region(out), row_pitch,
                                      slice_pitch, host_pitch(out), host_pitch(out) * out.extent[1],
                                      send.data());
    requests.emplace_back();
    MPI_Irecv(receive.data(), int(receive.size()), MPI_FLOAT, peer, tag(axis, !towards_high), world_.comm(),
              &requests.back());
    requests.emplace_back();
    MPI_Isend(send.data(), int(send.size()), MPI_FLOAT, peer, tag(axis, towards_high), world_.comm(),
              &requests.back());
    bytes_sent_ += send.size() * sizeof(float);
  };
  if (low >= 0) post(low, send_low, receive_low, staging_[0], staging_[2], false);
  if (high >= 0) post(high, send_high, receive_high, staging_[1], staging_[3], true);
  MPI_Waitall(int(requests.size()), requests.data(), MPI_STATUSES_IGNORE);
  const auto store = [&](const Box& in, const std::vector<float>& received) {
    const std::size_t host_row = in.extent[0] * sizeof(float);
    cc_.queue().enqueueWriteBufferRect(field, CL_TRUE, rect(in), host_origin, region(in), row_pitch,
                                       slice_pitch, host_row, host_row * in.extent[1], received.data());
  };
  if (low >= 0) store(receive_low, staging_[2]);
  if (high >= 0) store(receive_high, staging_[3]);
}

}  // namespace fw::host
