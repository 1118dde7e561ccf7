// host/bench/WeakScaling: the weak-scaling estimate of a step over 64 ranks from a measured block.
#include <catch2/catch.hpp>

#include "host/bench/WeakScaling.hpp"

using namespace fw;

TEST_CASE(
    "estimate_weak_scaling: four sides' bytes over the bandwidth plus a latency a message, on top of "
    "the compute and the four sides' copies",
    "[bench]") {
  bench::MeasuredBlock block;
  block.compute_ms = 10.0;
  block.copy_ms_per_side = 0.5;
  block.bytes_per_side = 1.25e6;    // 4 sides: 5 MB = 40 Mbit, 0.4 ms at 100 Gb/s
  block.messages_per_side = 100.0;  // 4 sides: 400 messages, 0.8 ms at 2 us
  const bench::WeakScalingEstimate e = bench::estimate_weak_scaling(block, bench::Interconnect{});
  // Tolerance: the sums of a few doubles, exact but for rounding.
  constexpr double kRounding = 1e-12;
  CHECK(e.ranks == 64);
  CHECK(e.bytes == Approx(5e6).epsilon(kRounding));
  CHECK(e.messages == Approx(400.0).epsilon(kRounding));
  CHECK(e.copy_ms == Approx(2.0).epsilon(kRounding));
  CHECK(e.network_ms == Approx(0.4 + 0.8).epsilon(kRounding));
  CHECK(e.step_ms == Approx(10.0 + 2.0 + 1.2).epsilon(kRounding));
  CHECK(e.efficiency == Approx(10.0 / 13.2).epsilon(kRounding));
}

TEST_CASE("estimate_weak_scaling: a block with no halo scales perfectly", "[bench]") {
  bench::MeasuredBlock block;
  block.compute_ms = 3.0;
  const bench::WeakScalingEstimate e = bench::estimate_weak_scaling(block, bench::Interconnect{});
  CHECK(e.step_ms == 3.0);
  CHECK(e.efficiency == 1.0);
}
