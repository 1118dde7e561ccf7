// host/bench/RanksBench: a rank's figures from its halo traffic, and the figures of a grid over ranks made
// of them (the step's wall time, the speedup and efficiency against the one-rank runs, the halo totals, the
// weak-scaling model's inputs). No device: the figures are given.
#include <catch2/catch.hpp>

#include "host/bench/RanksBench.hpp"

using namespace fw;

namespace {

// Tolerance: a few divisions of exact inputs, equal but for rounding.
constexpr double kRounding = 1e-12;

bench::RankStep step(double ms, double halo_ms, double bytes, int sides, double alone_ms) {
  bench::RankStep s;
  s.ms = ms;
  s.halo_ms = halo_ms;
  s.halo_copy_ms = halo_ms / 2;
  s.halo_bytes = bytes;
  s.halo_messages = 10.0 * sides;
  s.sides = sides;
  s.alone_ms = alone_ms;
  return s;
}

}  // namespace

TEST_CASE(
    "rank_step: per-step figures from the timed steps' halo traffic, and the block's sides with a "
    "neighbour",
    "[bench]") {
  host::HaloTraffic timed;
  timed.messages = 40;
  timed.bytes = 4000;
  timed.seconds = 0.02;
  timed.copy_seconds = 0.01;
  fluid::Block block;
  block.halo_low = {3, 0};
  block.halo_high = {3, 3};  // a neighbour on the west, the east and the north
  const bench::RankStep s = bench::rank_step(12.0, 20.0, timed, 4, block);
  CHECK(s.ms == 12.0);
  CHECK(s.alone_ms == 20.0);
  CHECK(s.halo_messages == 10.0);
  CHECK(s.halo_bytes == 1000.0);
  CHECK(s.halo_ms == Approx(5.0).epsilon(kRounding));
  CHECK(s.halo_copy_ms == Approx(2.5).epsilon(kRounding));
  CHECK(s.sides == 3);
}

TEST_CASE(
    "RanksCase: the step is the slowest rank's, the speedup is the mean one-rank step over it, and the "
    "halo adds up every rank's",
    "[bench]") {
  bench::RanksCase c;
  c.ranks = {step(10.0, 2.0, 1000.0, 1, 16.0), step(11.0, 1.0, 3000.0, 2, 20.0)};
  CHECK(c.ms_per_step() == 11.0);
  CHECK(c.alone_ms_per_step() == 18.0);
  CHECK(c.speedup() == Approx(18.0 / 11.0).epsilon(kRounding));
  CHECK(c.efficiency() == Approx(18.0 / 22.0).epsilon(kRounding));
  CHECK(c.halo_bytes() == 4000.0);
  CHECK(c.halo_ms_max() == 2.0);
  // The model's block: the slowest compute (11 - 1), and the costliest side of any rank.
  const bench::MeasuredBlock block = c.measured_block();
  CHECK(block.compute_ms == 10.0);
  CHECK(block.bytes_per_side == 1500.0);
  CHECK(block.messages_per_side == 10.0);
  CHECK(block.copy_ms_per_side == 1.0);
}

TEST_CASE("RanksCase: without every rank's one-rank run there is no speedup", "[bench]") {
  bench::RanksCase c;
  c.ranks = {step(10.0, 2.0, 1000.0, 1, 16.0), step(11.0, 1.0, 3000.0, 1, 0.0)};
  CHECK(c.alone_ms_per_step() == 0.0);
  CHECK(c.speedup() == 0.0);
  CHECK(c.efficiency() == 0.0);
}

TEST_CASE("gather_rank_steps: in one process, the one rank's figures", "[bench]") {
  const bench::RankStep mine = step(4.0, 0.0, 0.0, 0, 4.0);
  const auto all = bench::gather_rank_steps(host::Communicator::alone(), mine);
  REQUIRE(all.size() == 1);
  CHECK(all[0].ms == 4.0);
}
