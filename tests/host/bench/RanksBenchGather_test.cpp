// host/bench/RanksBench over MPI ranks (CTest runs this binary at 1, 2 and 4 ranks): rank 0 gathers every
// rank's figures, in rank order, and the others get none.
#include <catch2/catch.hpp>

#include "host/bench/RanksBench.hpp"
#include "tests/support/TestWorld.hpp"

using namespace fw;

TEST_CASE("gather_rank_steps: rank 0 receives every rank's figures in rank order, the others none", "[mpi]") {
  const host::Communicator& world = test::world();
  bench::RankStep mine;
  mine.ms = 100.0 + world.rank();  // a figure that names its rank
  mine.sides = world.rank();
  const auto all = bench::gather_rank_steps(world, mine);
  if (world.rank() != 0) {
    CHECK(all.empty());
    return;
  }
  REQUIRE(all.size() == std::size_t(world.size()));
  for (int r = 0; r < world.size(); ++r) {
    CHECK(all[std::size_t(r)].ms == 100.0 + r);
    CHECK(all[std::size_t(r)].sides == r);
  }
}
