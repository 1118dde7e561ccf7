#include "host/bench/WeakScaling.hpp"

namespace fw::bench {
namespace {
constexpr double kBitsPerByte = 8.0;
constexpr double kMsPerSecond = 1e3;
}  // namespace

WeakScalingEstimate estimate_weak_scaling(const MeasuredBlock& block, const Interconnect& net) {
  WeakScalingEstimate e;
  e.ranks = net.ranks;
  e.bytes = Interconnect::kSides * block.bytes_per_side;
  e.messages = Interconnect::kSides * block.messages_per_side;
  e.compute_ms = block.compute_ms;
  e.copy_ms = Interconnect::kSides * block.copy_ms_per_side;
  e.network_ms = (e.bytes * kBitsPerByte / net.bits_per_s + e.messages * net.latency_s) * kMsPerSecond;
  e.step_ms = e.compute_ms + e.copy_ms + e.network_ms;
  e.efficiency = e.step_ms > 0.0 ? e.compute_ms / e.step_ms : 0.0;
  return e;
}

}  // namespace fw::bench
