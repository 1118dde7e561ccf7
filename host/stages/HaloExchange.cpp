#include "host/stages/HaloExchange.hpp"

namespace fw::host {
namespace {

// Message tags: the axis and the direction the data travels, so that two messages between the same two
// ranks (two blocks along a periodic axis are each other's low and high neighbour) stay apart.
int tag(int axis, bool towards_high) {
  return 2 * axis + (towards_high ? 1 : 0);
}
// The periodic seam's copy (copy_seam), apart from the halos' four tags.
constexpr int kSeamTag = 4;

// A box of cells in the local array: first cell and extent along x, y, z.
struct Box {
  std::array<std::size_t, 3> first, extent;
  std::size_t cells() const { return extent[0] * extent[1] * extent[2]; }
};

// The rectangle calls' pitches of the layout, bytes.
std::array<std::size_t, 2> pitches(const BlockArray& a) {
  const std::size_t row = std::size_t(a.values(0)) * sizeof(float);
  return {row, row * std::size_t(a.values(1))};
}

}  // namespace

HaloExchange::HaloExchange(ComputeContext& cc, const Communicator& world, const BlockArray& layout)
    : cc_(cc), world_(world), layout_(layout) {}

void HaloExchange::exchange(cl::Buffer& field) {
  if (!world_.uses_mpi() || world_.size() == 1) return;
  bytes_sent_ = 0;
  exchange_axis(field, 0);
  exchange_axis(field, 1);
}

void HaloExchange::copy_seam(cl::Buffer& field) {
  const BlockArray& a = layout_;
  const int axis = a.staggered;
  if (!world_.uses_mpi() || axis < 0 || axis > 1) return;
  const int to = a.seam_low[axis], from = a.seam_high[axis];
  if (to < 0 && from < 0) return;
  const auto [row_pitch, slice_pitch] = pitches(a);
  // One layer of faces across the axis: face 0 of the domain is block 0's first own face, face n the last
  // block's face after its own cells.
  const auto layer = [&](int at) {
    std::array<cl::size_type, 3> origin{0, 0, 0},
        region{std::size_t(a.values(0)) * sizeof(float), std::size_t(a.values(1)), std::size_t(a.values(2))};
    origin[axis] = axis == 0 ? std::size_t(at) * sizeof(float) : std::size_t(at);
    region[axis] = axis == 0 ? sizeof(float) : 1;
    return std::pair{origin, region};
  };
  std::vector<float>& values = staging_[0];
  const std::size_t count = a.cells() / std::size_t(a.values(axis));
  values.resize(count);
  const std::array<cl::size_type, 3> host_origin{0, 0, 0};
  const auto host_pitches = [&](const std::array<cl::size_type, 3>& region) {
    return std::pair{region[0], region[0] * region[1]};
  };
  std::vector<MPI_Request> requests;
  requests.reserve(2);
  if (to >= 0) {
    const auto [origin, region] = layer(a.halo_low[axis]);
    const auto [host_row, host_slice] = host_pitches(region);
    cc_.queue().enqueueReadBufferRect(field, CL_TRUE, origin, host_origin, region, row_pitch, slice_pitch,
                                      host_row, host_slice, values.data());
    requests.emplace_back();
    MPI_Isend(values.data(), int(count), MPI_FLOAT, to, kSeamTag, world_.comm(), &requests.back());
  }
  std::vector<float>& received = staging_[2];
  received.resize(count);
  if (from >= 0) {
    requests.emplace_back();
    MPI_Irecv(received.data(), int(count), MPI_FLOAT, from, kSeamTag, world_.comm(), &requests.back());
  }
  MPI_Waitall(int(requests.size()), requests.data(), MPI_STATUSES_IGNORE);
  if (from >= 0) {
    const auto [origin, region] = layer(a.values(axis) - 1 - a.halo_high[axis]);
    const auto [host_row, host_slice] = host_pitches(region);
    cc_.queue().enqueueWriteBufferRect(field, CL_TRUE, origin, host_origin, region, row_pitch, slice_pitch,
                                       host_row, host_slice, received.data());
  }
}

void HaloExchange::exchange_axis(cl::Buffer& field, int axis) {
  const BlockArray& a = layout_;
  const int low_rank = a.neighbour_low[axis], high_rank = a.neighbour_high[axis];
  if (low_rank < 0 && high_rank < 0) return;
  const auto [row_pitch, slice_pitch] = pitches(a);
  // The strip along `axis` from `at`, `width` values wide, over the whole of the other axes.
  const auto strip = [&](int at, int width) {
    Box box{{0, 0, 0}, {std::size_t(a.values(0)), std::size_t(a.values(1)), std::size_t(a.values(2))}};
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
  // What each neighbour's halo holds: the own values next to the border, as deep as that halo. Across a
  // staggered axis the face on the border is both blocks' own: the strips start one face further out.
  const int n = a.values(axis), face = a.staggered == axis ? 1 : 0;
  const int low = a.halo_low[axis], high = a.halo_high[axis];
  const Box send_low = strip(low + face, low);
  const Box send_high = strip(n - face - 2 * high, high);
  const Box receive_low = strip(0, low);
  const Box receive_high = strip(n - high, high);

  std::vector<MPI_Request> requests;
  requests.reserve(4);
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
  if (low_rank >= 0) post(low_rank, send_low, receive_low, staging_[0], staging_[2], false);
  if (high_rank >= 0) post(high_rank, send_high, receive_high, staging_[1], staging_[3], true);
  MPI_Waitall(int(requests.size()), requests.data(), MPI_STATUSES_IGNORE);
  const auto store = [&](const Box& in, const std::vector<float>& received) {
    const std::size_t host_row = in.extent[0] * sizeof(float);
    cc_.queue().enqueueWriteBufferRect(field, CL_TRUE, rect(in), host_origin, region(in), row_pitch,
                                       slice_pitch, host_row, host_row * in.extent[1], received.data());
  };
  if (low_rank >= 0) store(receive_low, staging_[2]);
  if (high_rank >= 0) store(receive_high, staging_[3]);
}

}  // namespace fw::host
