// host/stages/PlaneStatistics over MPI ranks (CTest runs this binary at 1, 2 and 4 ranks): every split gives
// one process's profiles, bit for bit, for the whole plane and for regions across the cuts and beside them.
#include <catch2/catch.hpp>

#include <vector>

#include "host/stages/PlaneStatistics.hpp"
#include "host/stages/WindGrid.hpp"
#include "tests/support/TestDevice.hpp"
#include "tests/support/TestWorld.hpp"
#include "tests/support/Tunnels.hpp"

using namespace fw;

namespace {

constexpr int kSteps = 4;

// The ranks tests' periodic channel (Smagorinsky, a gust) with the gust on the corner of both seams: every
// plane is uneven there, and the strain's differences wrap across them.
host::WindGridSetup periodic_channel() {
  host::WindGridSetup setup = test::periodic_channel();
  setup.gusts[0].center[0] = 1.0f, setup.gusts[0].center[1] = 15.0f;
  return setup;
}

// The profiles after kSteps steps of `setup` (with `canopy`), over `region`: alone, or over `blocks`.
fluid::PlaneProfiles profiles_after_steps(host::ComputeContext& cc, const host::WindGridSetup& setup,
                                          const std::vector<float>& canopy, const host::PlaneRegion& region,
                                          const host::WindBlocks* blocks) {
  host::WindGrid wind(cc, setup, blocks);
  if (setup.turbulence) wind.set_turbulence_sigma(1.0);
  if (!canopy.empty()) wind.set_canopy(canopy);
  wind.initialise_ambient();
  for (int n = 0; n < kSteps; ++n) wind.step();
  const host::Communicator& world = blocks ? *blocks->world : host::Communicator::alone();
  host::PlaneStatistics statistics(cc, wind.spec(), wind.local_spec(), wind.block(), world);
  return statistics.sample(wind.statistics_fields(), wind.max_speed_components()[0], region);
}

void check_equal_to_one_process(const host::WindGridSetup& setup, const std::vector<float>& canopy) {
  auto* cc = test::device_or_skip();
  if (!cc) return;
  const host::Communicator& world = test::world();
  // The whole plane, a region whose edges fall inside the blocks of every split, and a corner that most
  // blocks do not reach (their ranks add nothing, and still take part).
  for (const host::PlaneRegion region :
       {host::PlaneRegion{}, host::PlaneRegion{{5, 3}, {27, 11}}, host::PlaneRegion{{1, 1}, {6, 5}}}) {
    INFO("region x " << region.first[0] << ".." << region.end[0] << ", y " << region.first[1] << ".."
                     << region.end[1]);
    const fluid::PlaneProfiles alone = profiles_after_steps(*cc, setup, canopy, region, nullptr);
    for (const auto blocks : test::splits(world.size())) {
      INFO(blocks[0] << " x " << blocks[1] << " blocks on " << world.size() << " ranks");
      const host::WindBlocks split = test::blocks_of(setup, blocks, world);
      const fluid::PlaneProfiles mine = profiles_after_steps(*cc, setup, canopy, region, &split);
      for (int p = 0; p < fluid::kProfileCount; ++p)
        for (int k = 0; k < alone.nz; ++k) {
          INFO(fluid::profile_variables()[std::size_t(p)].name << " at height " << k);
          CHECK(mine.at(fluid::Profile(p), k) == alone.at(fluid::Profile(p), k));
        }
    }
  }
}

}  // namespace

TEST_CASE("PlaneStatistics over ranks: a periodic channel's profiles are one process's, bit for bit",
          "[mpi]") {
  check_equal_to_one_process(periodic_channel(), {});
}

TEST_CASE(
    "PlaneStatistics over ranks: a tunnel's with solids, a canopy and the tke model are one process's, bit "
    "for bit",
    "[mpi]") {
  const host::WindGridSetup setup = test::turbulent_tunnel();
  check_equal_to_one_process(setup, test::tunnel_canopy(setup.spec));
}
