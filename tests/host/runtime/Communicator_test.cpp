// host/runtime/Communicator under mpirun -np 1, 2 and 4 (CTest runs this binary at each): sums over ranks
// equal the sum of the same terms in one process, bit for bit; maxima see every rank's NaN; gathers bring
// every rank's list, in rank order.
#include "host/runtime/Communicator.hpp"
#include "host/runtime/Device.hpp"

#include <catch2/catch.hpp>

#include <cmath>
#include <cstdlib>
#include <random>
#include <vector>

#include "tests/support/TestDevice.hpp"
#include "tests/support/TestWorld.hpp"

namespace {

// The same terms on every rank: floats over 40 decades, both signs.
std::vector<float> all_terms() {
  std::mt19937 rng(23);
  std::uniform_real_distribution<float> exponent(-20.0f, 20.0f), mantissa(-1.0f, 1.0f);
  std::vector<float> values(10007);
  for (auto& v : values) v = mantissa(rng) * std::pow(10.0f, exponent(rng));
  return values;
}

}  // namespace

TEST_CASE("Communicator: a sum over ranks is the one-process sum of the same terms, bit for bit", "[mpi]") {
  const auto& world = fw::test::world();
  const auto terms = all_terms();
  fw::base::ExactSum whole, mine;
  whole.add(terms);
  // Rank r takes every size-th term from r: interleaved, the hardest split for an ordered sum.
  for (std::size_t i = world.rank(); i < terms.size(); i += world.size()) mine.add(terms[i]);
  CHECK(world.sum(mine) == whole.value());
  CHECK(world.sum((long long)world.rank() + 1) == (long long)world.size() * (world.size() + 1) / 2);
}

TEST_CASE("Communicator: the maximum over ranks, NaN on any rank winning", "[mpi]") {
  const auto& world = fw::test::world();
  CHECK(world.max(double(world.rank())) == double(world.size() - 1));
  const double last_has_nan = world.rank() == world.size() - 1 ? std::nan("") : 1.0;
  CHECK(std::isnan(world.max(last_has_nan)));
}

TEST_CASE("Communicator: gather brings every rank's list to rank 0 only, gather_to_all to every rank",
          "[mpi]") {
  const auto& world = fw::test::world();
  // Rank r sends r + 1 values r * 100, r * 100 + 1, ...: lists of different lengths, one empty on no rank.
  std::vector<int> mine;
  for (int i = 0; i <= world.rank(); ++i) mine.push_back(world.rank() * 100 + i);
  const auto on_root = world.gather(mine);
  const auto on_all = world.gather_to_all(mine);
  REQUIRE(on_all.size() == std::size_t(world.size()));
  REQUIRE(on_root.size() == std::size_t(world.size()));
  for (int r = 0; r < world.size(); ++r) {
    std::vector<int> sent;
    for (int i = 0; i <= r; ++i) sent.push_back(r * 100 + i);
    CHECK(on_all[std::size_t(r)] == sent);
    CHECK(on_root[std::size_t(r)] == (world.rank() == 0 ? sent : std::vector<int>{}));
  }
}

TEST_CASE("Communicator: a process started without a launcher is one rank alone", "[mpi]") {
  const auto& alone = fw::host::Communicator::alone();
  CHECK(alone.size() == 1);
  CHECK(alone.rank() == 0);
  CHECK_FALSE(alone.uses_mpi());
  CHECK(fw::test::world().uses_mpi() == fw::host::launched_by_mpi());
}

TEST_CASE("Communicator: a machine's ranks share its cores under PoCL and take its devices in turn",
          "[mpi]") {
  const auto& world = fw::test::world();
  // The tests' main shared the cores before any OpenCL call: with several ranks on this machine PoCL runs
  // each on its share, unless the environment set one.
  if (world.node_size() > 1) {
    const char* share = std::getenv("POCL_MAX_PTHREAD_COUNT");
    REQUIRE(share != nullptr);
    CHECK(std::atoi(share) >= 1);
  }
  CHECK(fw::host::share_cpu_cores(1) == 0);  // one rank: nothing to share
  // Rank r of a machine takes the r-th of the devices the filter leaves, counted round.
  if (!fw::test::device_or_skip()) return;
  const auto devices = fw::host::list_devices();
  const auto first = fw::host::select_device("", 0);
  CHECK(first.device_name == fw::host::select_device("").device_name);
  std::size_t same_type = 0;
  for (const auto& d : devices) same_type += d.type == first.type;
  CHECK(fw::host::select_device("", int(same_type)).device_name == first.device_name);
}
