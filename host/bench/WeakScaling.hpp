// A weak-scaling estimate of a step over many ranks, from a step measured over a few: each rank keeps the
// block it had, and an interior block of a layout cut along both axes has a neighbour on each of its four
// sides. Its step is the measured compute, plus the halo's device-host copies as measured (per side, times
// four), plus the messages on the interconnect: bytes / bandwidth + latency per message, nothing overlapped
// (HaloExchange waits for its messages before the next stage). What it leaves out is in docs/parallel.md,
// "Benchmarks over ranks".
//
//   fw::bench::MeasuredBlock block;   // measured: compute ms; per side: copy ms, bytes, messages
//   block.compute_ms = 12.0, block.bytes_per_side = 393216.0, block.messages_per_side = 40.0;
//   const auto e = fw::bench::estimate_weak_scaling(block, fw::bench::Interconnect{});
//   e.step_ms;  e.efficiency;         // at 64 ranks, 100 Gb/s, 2 us a message
#pragma once

namespace fw::bench {

/// The network of the estimate.
struct Interconnect {
  int ranks = 64;                   // the layout's size (8 x 8 blocks); its interior blocks have four sides
  double bits_per_s = 100e9;        // 100 Gb/s: InfiniBand HDR100 or 100 Gb Ethernet, one link a node
  double latency_s = 2e-6;          // per message: an MPI message's start-up over InfiniBand
  static constexpr int kSides = 4;  // an interior block's neighbours
};

/// One rank's measured step: its compute (the step without its halo exchanges) and what one side of its
/// block cost per step.
struct MeasuredBlock {
  double compute_ms = 0.0;
  double copy_ms_per_side = 0.0;
  double bytes_per_side = 0.0;
  double messages_per_side = 0.0;
};

struct WeakScalingEstimate {
  int ranks = 0;
  double bytes = 0.0;       // an interior rank's halo bytes per step
  double messages = 0.0;    // its messages per step
  double compute_ms = 0.0;  // as measured
  double copy_ms = 0.0;     // the four sides' device-host copies
  double network_ms = 0.0;  // bytes / bandwidth + messages x latency
  double step_ms = 0.0;     // compute + copies + network
  double efficiency = 0.0;  // compute / step: a block's step alone over its step among 64
};

WeakScalingEstimate estimate_weak_scaling(const MeasuredBlock& block, const Interconnect& net);

}  // namespace fw::bench
