#include "host/stages/HaloExchange.hpp"

#include <algorithm>
#include <chrono>

namespace fw::host {
namespace {

using Clock = std::chrono::steady_clock;
double seconds_since(Clock::time_point start) {
  return std::chrono::duration<double>(Clock::now() - start).count();
}

// Message tags: the axis and the direction the data travels, so that two messages between the same two
// ranks (two blocks along a periodic axis are each other's low and high neighbour) stay apart.
int tag(int axis, bool towards_high) {
  return 2 * axis + (towards_high ? 1 : 0);
}
// The periodic seam's copy (copy_seam), apart from the halos' four tags.
constexpr int kSeamTag = 4;

}  // namespace

HaloTraffic& HaloTraffic::operator+=(const HaloTraffic& other) {
  messages += other.messages;
  bytes += other.bytes;
  seconds += other.seconds;
  copy_seconds += other.copy_seconds;
  return *this;
}

HaloTraffic HaloTraffic::operator-(const HaloTraffic& earlier) const {
  return {messages - earlier.messages, bytes - earlier.bytes, seconds - earlier.seconds,
          copy_seconds - earlier.copy_seconds};
}

HaloExchange::HaloExchange(ComputeContext& cc, const Communicator& world, const BlockArray& layout)
    : cc_(cc), world_(world), layout_(layout) {}

HaloExchange::Box HaloExchange::strip(int axis, int at, int width) const {
  Box box{{0, 0, 0},
          {std::size_t(layout_.values(0)), std::size_t(layout_.values(1)), std::size_t(layout_.values(2))}};
  box.first[std::size_t(axis)] = std::size_t(at);
  box.extent[std::size_t(axis)] = std::size_t(width);
  return box;
}

HaloExchange::Rect HaloExchange::rect(const Box& box) const {
  const std::size_t row = std::size_t(layout_.values(0)) * sizeof(float),
                    host_row = box.extent[0] * sizeof(float);
  return {{box.first[0] * sizeof(float), box.first[1], box.first[2]},
          {host_row, box.extent[1], box.extent[2]},
          row,
          row * std::size_t(layout_.values(1)),
          host_row,
          host_row * box.extent[1]};
}

void HaloExchange::read_box(cl::Buffer& field, const Box& box, std::vector<float>& host) {
  const auto start = Clock::now();
  host.resize(box.values());
  const Rect r = rect(box);
  cc_.queue().enqueueReadBufferRect(field, CL_TRUE, r.origin, {0, 0, 0}, r.region, r.row, r.slice, r.host_row,
                                    r.host_slice, host.data());
  traffic_.copy_seconds += seconds_since(start);
}

void HaloExchange::write_box(cl::Buffer& field, const Box& box, const std::vector<float>& host) {
  const auto start = Clock::now();
  const Rect r = rect(box);
  cc_.queue().enqueueWriteBufferRect(field, CL_TRUE, r.origin, {0, 0, 0}, r.region, r.row, r.slice,
                                     r.host_row, r.host_slice, host.data());
  traffic_.copy_seconds += seconds_since(start);
}

void HaloExchange::send(const std::vector<float>& values, int peer, int message_tag, MPI_Request& request) {
  MPI_Isend(values.data(), int(values.size()), MPI_FLOAT, peer, message_tag, world_.comm(), &request);
  ++traffic_.messages;
  traffic_.bytes += static_cast<long long>(values.size() * sizeof(float));
}

void HaloExchange::exchange(cl::Buffer& field, int depth) {
  if (!world_.uses_mpi() || world_.size() == 1) return;
  // The first halo read would wait for the kernels queued before it: they are the step's work, not the
  // exchange's, so they finish before the clock starts.
  cc_.finish();
  const auto start = Clock::now();
  exchange_axis(field, 0, depth);
  exchange_axis(field, 1, depth);
  traffic_.seconds += seconds_since(start);
}

void HaloExchange::copy_seam(cl::Buffer& field) {
  const BlockArray& a = layout_;
  const int axis = a.staggered;
  if (!world_.uses_mpi() || axis < 0 || axis > 1) return;
  const int to = a.seam_low[axis], from = a.seam_high[axis];
  if (to < 0 && from < 0) return;
  cc_.finish();  // as in exchange(): the kernels before are not the copy's
  const auto start = Clock::now();
  // One layer of faces across the axis: face 0 of the domain is block 0's first own face, face n the last
  // block's face after its own cells.
  const Box first = strip(axis, a.halo_low[axis], 1),
            last = strip(axis, a.values(axis) - 1 - a.halo_high[axis], 1);
  std::vector<float>&sent = staging_[0], &received = staging_[2];
  std::vector<MPI_Request> requests;
  requests.reserve(2);
  if (to >= 0) {
    read_box(field, first, sent);
    requests.emplace_back();
    send(sent, to, kSeamTag, requests.back());
  }
  if (from >= 0) {
    received.resize(last.values());
    requests.emplace_back();
    MPI_Irecv(received.data(), int(received.size()), MPI_FLOAT, from, kSeamTag, world_.comm(),
              &requests.back());
  }
  MPI_Waitall(int(requests.size()), requests.data(), MPI_STATUSES_IGNORE);
  if (from >= 0) write_box(field, last, received);
  traffic_.seconds += seconds_since(start);
}

void HaloExchange::exchange_axis(cl::Buffer& field, int axis, int depth) {
  const BlockArray& a = layout_;
  const int low_rank = a.neighbour_low[axis], high_rank = a.neighbour_high[axis];
  if (low_rank < 0 && high_rank < 0) return;
  // What each neighbour's halo holds: the own values next to the border, as deep as that halo (or `depth`).
  // Across a staggered axis the face on the border is both blocks' own: the strips start one face further
  // out.
  const int n = a.values(axis), face = a.staggered == axis ? 1 : 0;
  const int low = a.halo_low[axis], high = a.halo_high[axis];
  const int deep_low = std::min(low, depth), deep_high = std::min(high, depth);
  const Box send_low = strip(axis, low + face, deep_low),
            send_high = strip(axis, n - face - high - deep_high, deep_high);
  const Box receive_low = strip(axis, low - deep_low, deep_low),
            receive_high = strip(axis, n - high, deep_high);

  std::vector<MPI_Request> requests;
  requests.reserve(4);
  const auto post = [&](int peer, const Box& out, const Box& in, std::vector<float>& sent,
                        std::vector<float>& receive, bool towards_high) {
    read_box(field, out, sent);
    receive.resize(in.values());
    requests.emplace_back();
    MPI_Irecv(receive.data(), int(receive.size()), MPI_FLOAT, peer, tag(axis, !towards_high), world_.comm(),
              &requests.back());
    requests.emplace_back();
    send(sent, peer, tag(axis, towards_high), requests.back());
  };
  if (low_rank >= 0) post(low_rank, send_low, receive_low, staging_[0], staging_[2], false);
  if (high_rank >= 0) post(high_rank, send_high, receive_high, staging_[1], staging_[3], true);
  MPI_Waitall(int(requests.size()), requests.data(), MPI_STATUSES_IGNORE);
  if (low_rank >= 0) write_box(field, receive_low, staging_[2]);
  if (high_rank >= 0) write_box(field, receive_high, staging_[3]);
}

}  // namespace fw::host
