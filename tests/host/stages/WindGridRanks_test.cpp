// host/stages/WindGrid over MPI ranks (CTest runs this binary at 1, 2 and 4 ranks): every split of the
// ranks steps the wind to the bits of one process, with obstacles across the blocks' borders, under each
// advection scheme, on a periodic channel held by the mean forcing, and with every stage of a forest's wind.
#include <catch2/catch.hpp>

#include <algorithm>
#include <memory>
#include <numbers>
#include <vector>

#include "fluid/SolidMap.hpp"
#include "fluid/TurbulenceBox.hpp"
#include "host/stages/WindGrid.hpp"
#include "tests/support/TestDevice.hpp"
#include "tests/support/TestWorld.hpp"
#include "tests/support/Tunnels.hpp"

using namespace fw;
using B = fluid::BoundaryType;

namespace {

constexpr int kSteps = 8;

// Steps `setup` alone and over the ranks in every split (with `canopy`, a whole grid's drag density, unless
// empty), and compares each rank's block of the velocity, halo included, bit for bit; and the steps' dt and
// pressure iterations.
void check_equal_to_one_process(const host::WindGridSetup& setup, const std::vector<float>& canopy = {}) {
  auto* cc = test::device_or_skip();
  if (!cc) return;
  const host::Communicator& world = test::world();
  host::WindGrid alone(*cc, setup);
  if (setup.turbulence) alone.set_turbulence_sigma(1.0);
  if (!canopy.empty()) alone.set_canopy(canopy);
  alone.initialise_ambient();
  std::vector<host::WindStepReport> expected;
  for (int n = 0; n < kSteps; ++n) expected.push_back(alone.step());
  const fluid::MacVelocity whole = alone.download_velocity();

  for (const auto blocks : test::splits(world.size())) {
    INFO(blocks[0] << " x " << blocks[1] << " blocks on " << world.size() << " ranks");
    const host::WindBlocks split = test::blocks_of(setup, blocks, world);
    host::WindGrid wind(*cc, setup, &split);
    if (setup.turbulence) wind.set_turbulence_sigma(1.0);
    if (!canopy.empty()) wind.set_canopy(canopy);  // the whole grid's; each rank takes its block
    wind.initialise_ambient();
    for (int n = 0; n < kSteps; ++n) {
      INFO("step " << n + 1);
      const host::WindStepReport report = wind.step();
      CHECK(report.dt == expected[n].dt);
      CHECK(report.pressure.iterations == expected[n].pressure.iterations);
    }
    const fluid::MacVelocity mine = wind.download_velocity();
    for (int c = 0; c < 3; ++c) {
      INFO("component " << c);
      const host::BlockArray faces = host::face_array(wind.block(), c);
      const auto reference =
          host::block_of(whole.component(c), setup.spec.nx + (c == 0), setup.spec.ny + (c == 1), faces);
      // Where they part first, to say which stage to look at.
      long differing = 0;
      std::size_t first = reference.size();
      for (std::size_t at = 0; at < reference.size(); ++at)
        if (mine.component(c)[at] != reference[at]) {
          first = std::min(first, at);
          ++differing;
        }
      const std::size_t ex = std::size_t(faces.values(0)), ey = std::size_t(faces.values(1));
      if (differing > 0)
        UNSCOPED_INFO("first differing face ("
                      << first % ex << ", " << first / ex % ey << ", " << first / (ex * ey)
                      << ") of the block: " << mine.component(c)[first] << " against " << reference[first]);
      CHECK(differing == 0);
    }
  }
}

}  // namespace

TEST_CASE("WindGrid over ranks: a tunnel with obstacles steps to the bits of one process, semi-Lagrangian",
          "[mpi]") {
  check_equal_to_one_process(test::tunnel(fluid::AdvectionScheme::semi_lagrangian));
}

TEST_CASE("WindGrid over ranks: a tunnel with obstacles steps to the bits of one process, MacCormack",
          "[mpi]") {
  check_equal_to_one_process(test::tunnel(fluid::AdvectionScheme::maccormack));
}

TEST_CASE("WindGrid over ranks: a tunnel with obstacles steps to the bits of one process, upwind5", "[mpi]") {
  check_equal_to_one_process(test::tunnel(fluid::AdvectionScheme::upwind5));
}

TEST_CASE(
    "WindGrid over ranks: a periodic channel with mean forcing, a gust, Smagorinsky and vorticity "
    "confinement, bit for bit",
    "[mpi]") {
  check_equal_to_one_process(test::periodic_channel());
}

TEST_CASE(
    "WindGrid over ranks: a periodic channel over a rough floor, whose wall stress reaches across the "
    "periodic seams, bit for bit",
    "[mpi]") {
  host::WindGridSetup setup = test::tunnel(fluid::AdvectionScheme::semi_lagrangian);
  setup.solid.clear();
  setup.spec.boundary = {B::inflow, B::outflow, B::periodic, B::periodic, B::slip, B::slip};
  setup.settings.wall_roughness_length = 0.1;
  check_equal_to_one_process(setup);
}

TEST_CASE(
    "WindGrid over ranks: inflow turbulence, a canopy, the tke model, a rough floor and vorticity "
    "confinement, bit for bit",
    "[mpi]") {
  const host::WindGridSetup setup = test::turbulent_tunnel();
  check_equal_to_one_process(setup, test::tunnel_canopy(setup.spec));
}

TEST_CASE("WindGrid over ranks: a patchy canopy across both periodic seams, under the tke model, bit for bit",
          "[mpi]") {
  // The seam's face is face 0 and face n at once: its drag takes the cells on both sides of it, and the
  // subgrid energy diffuses across it, in one process as in a block cut there.
  host::WindGridSetup setup = test::periodic_channel();
  setup.settings.subgrid = fluid::SubgridModel::tke;
  setup.settings.smagorinsky_constant = 0.0;  // the Smagorinsky model's alone
  setup.gusts.clear();
  std::vector<float> canopy(setup.spec.cell_count(), 0.0f);
  for (int k = 0; k < 4; ++k)
    for (int j = 0; j < setup.spec.ny; ++j)
      for (int i = 0; i < setup.spec.nx; ++i)  // densities that differ from cell to cell, seams included
        canopy[i + std::size_t(setup.spec.nx) * (j + std::size_t(setup.spec.ny) * k)] =
            0.05f * float(1 + (3 * i + 5 * j + 7 * k) % 11);
  check_equal_to_one_process(setup, canopy);
}

TEST_CASE("WindGrid over ranks: a step whose back-trace would outrun the halo stops, naming the step",
          "[mpi]") {
  auto* cc = test::device_or_skip();
  if (!cc) return;
  const host::Communicator& world = test::world();
  // 6 m/s across 1 m cells at dt = 1 s: a back-trace of 6 cells, which needs a halo of 8; the ranks
  // exchange 3.
  host::WindGridSetup setup = test::tunnel(fluid::AdvectionScheme::semi_lagrangian);
  setup.settings.cfl = 0.0;
  setup.settings.dt = 1.0;
  const host::WindBlocks split{
      &world, fluid::Decomposition::make(setup.spec, world.size(), std::nullopt,
                                         host::advection_method(setup.settings.advection).halo_cells(0.8))};
  host::WindGrid wind(*cc, setup, &split);
  wind.initialise_ambient();
  if (world.size() == 1) {
    CHECK_NOTHROW(wind.step());  // one process reads its ghosts as ever: nothing to outrun
    return;
  }
  CHECK_THROWS_WITH(wind.step(), Catch::Contains("step 1:") && Catch::Contains("past the 3 cells of halo"));
}
