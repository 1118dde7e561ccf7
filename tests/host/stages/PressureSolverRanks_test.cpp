// host/stages/PressureSolver over MPI ranks (CTest runs this binary at 1, 2 and 4 ranks): every split of the
// ranks into x-y blocks solves to the bits of one process, a box straddling the blocks' borders and a
// periodic axis cut between them included.
#include <catch2/catch.hpp>

#include <vector>

#include "fluid/Decomposition.hpp"
#include "fluid/PressureLevels.hpp"
#include "host/stages/HaloExchange.hpp"
#include "host/stages/PressureSolver.hpp"
#include "tests/support/Fields.hpp"
#include "tests/support/TestDevice.hpp"
#include "tests/support/TestWorld.hpp"

using namespace fw;

namespace {

// The velocity's halo, which the fine level shares: upwind5's reach.
constexpr int kFineHalo = FW_PAD;

}  // namespace

TEST_CASE("PressureSolver over ranks: every split solves to the bits of one process", "[mpi]") {
  auto* cc = test::device_or_skip();
  if (!cc) return;
  const host::Communicator& world = test::world();
  const fluid::GridSpec spec = test::mixed_boundary_spec();  // 24 x 16 x 12, periodic along y
  const std::vector<std::uint8_t> solid = test::box_solid(spec);
  const auto levels = fluid::build_pressure_levels(spec, solid);
  const auto b = test::random_cells(spec.cell_count(), 1.0, 29);

  struct Case {
    const char* name;
    fluid::PressureSolverType solver;
    fluid::MultigridSmoother smoother;
  };
  const Case cases[] = {
      {"cg, red-black", fluid::PressureSolverType::cg, fluid::MultigridSmoother::red_black},
      {"V-cycles, red-black", fluid::PressureSolverType::multigrid, fluid::MultigridSmoother::red_black},
      {"cg, Jacobi", fluid::PressureSolverType::cg, fluid::MultigridSmoother::jacobi}};
  for (const Case& c : cases) {
    fluid::PressureSettings settings;
    settings.solver = c.solver;
    settings.smoother = c.smoother;
    settings.tolerance = 1e-5;  // near the float floor: many iterations, each of them must agree
    host::PressureSolver alone(*cc, spec, levels, settings);
    test::upload(*cc, b, alone.rhs());
    const host::PressureSolveStatus expected = alone.solve();
    const auto phi = test::download(*cc, alone.solution(), spec.cell_count());

    // The default keeps small levels whole on every rank; 0 splits every level the cuts divide.
    for (const auto blocks : test::splits(world.size()))
      for (const long long min_split_cells : {host::kSplitLevelCells, 0LL}) {
        INFO(c.name << ", " << blocks[0] << " x " << blocks[1] << " blocks on " << world.size() << " ranks, "
                    << "levels split down to " << min_split_cells << " cells a block");
        const host::PressureBlocks split{&world,
                                         fluid::Decomposition::make(spec, world.size(), blocks, kFineHalo),
                                         kFineHalo, min_split_cells};
        const host::BlockArray a =
            host::block_array(split.decomposition, world.rank(), 0, spec.nz, kFineHalo);
        host::PressureSolver solver(*cc, spec, levels, settings, &split);
        test::upload(*cc, host::block_of(b, spec.nx, spec.ny, a), solver.rhs());
        const host::PressureSolveStatus status = solver.solve();
        CHECK(status.iterations == expected.iterations);
        CHECK(status.relative_residual == expected.relative_residual);
        // The block's own cells, bit for bit (the halo is the neighbours' to own).
        const auto mine = test::download(*cc, solver.solution(), a.cells());
        const auto reference = host::block_of(phi, spec.nx, spec.ny, a);
        long differing = 0;
        for (int k = 0; k < a.extent[2]; ++k)
          for (int j = a.halo_low[1]; j < a.extent[1] - a.halo_high[1]; ++j)
            for (int i = a.halo_low[0]; i < a.extent[0] - a.halo_high[0]; ++i) {
              const std::size_t at = i + std::size_t(a.extent[0]) * (j + std::size_t(a.extent[1]) * k);
              differing += mine[at] != reference[at];
            }
        CHECK(differing == 0);
        // And the halo holds the neighbours' values after the solve, as the gradient will read them.
        long stale = 0;
        for (std::size_t at = 0; at < a.cells(); ++at) stale += mine[at] != reference[at];
        CHECK(stale == 0);
      }
  }
}
