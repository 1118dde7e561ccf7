// host/app/CoupledStep over MPI ranks (CTest runs this file at 1, 2, 3 and 4 ranks): trees whose crowns
// straddle the blocks' borders get the modal state of one process, and points anywhere are sampled to the
// bits of one process by the rank that holds them (host/stages/PointWindAcrossRanks).
#include <catch2/catch.hpp>

#include <array>
#include <vector>

#include "host/app/CoupledStep.hpp"
#include "host/stages/PointWindAcrossRanks.hpp"
#include "host/stages/PointWindReadback.hpp"
#include "tests/support/SmallSpecies.hpp"
#include "tests/support/TestDevice.hpp"
#include "tests/support/TestWorld.hpp"
#include "tests/support/Tunnels.hpp"

using namespace fw;

namespace {

// Six 6 m broadleaves whose roots lie within a cell or two of the cuts of every split of up to 4 ranks (x at
// 8, 16, 24 cells; y at 4, 8, 12), clear of the tunnel's solids. The last one's top samples lie 0.2 m past
// the cuts at x = 12 m and y = 6 m (cells 16 and 4), in another block than its root in every split.
trees::Forest forest_across_cuts() {
  std::vector<trees::SpeciesBasis> species = {test::small_species("broadleaf", 6.0, 3, 4, 6, 12)};
  std::vector<trees::TreeInstance> instances = {
      {0, {3.8, 9.9, 0.0}, 0.3, 1.0},  {0, {19.9, 10.2, 0.0}, 1.1, 0.9}, {0, {6.1, 13.8, 0.0}, 2.0, 1.1},
      {0, {-1.2, 5.7, 0.0}, 0.0, 1.0}, {0, {24.5, 14.2, 0.0}, 4.0, 1.2}, {0, {11.95, 6.1, 0.0}, 0.0, 1.0}};
  return trees::Forest(std::move(species), std::move(instances));
}

host::CouplingSettings coupling(const fluid::GridSpec& spec) {
  host::CouplingSettings c;
  c.drag_density = test::tunnel_canopy(spec);
  c.unresolved.enabled = true;  // its series is seeded per tree: by the whole forest's index
  c.unresolved.series_length = 1 << 12;
  c.unresolved.intensity = 0.2;
  return c;
}

constexpr int kSteps = 6;

// Two broadleaves and their canopy in the tunnel's south-west corner (cells x 1-6, y 0-3): in a row of 3 or
// 4 blocks, along x or y, the far blocks hold no tree and no canopy and border no block that holds a tree.
trees::Forest forest_in_a_corner() {
  std::vector<trees::SpeciesBasis> species = {test::small_species("broadleaf", 6.0, 3, 4, 6, 12)};
  std::vector<trees::TreeInstance> instances = {{0, {-1.0, 3.5, 0.0}, 0.4, 1.0},
                                                {0, {1.5, 4.5, 0.0}, 2.5, 0.9}};
  return trees::Forest(std::move(species), std::move(instances));
}

// Points over the whole domain and just outside it (clamped), a different share on every rank.
std::vector<float> points_of_rank(int rank) {
  std::vector<float> points;
  for (int n = 0; n < 24; ++n) {
    if ((n + rank) % 3 == 0) continue;
    points.insert(points.end(), {-4.5f + 1.37f * float(n), 2.0f + 0.71f * float(n), 0.3f + 0.33f * float(n)});
  }
  return points;
}

}  // namespace

TEST_CASE("CoupledStep over ranks: trees across the blocks' borders step to the modal state of one process",
          "[mpi]") {
  auto* cc = test::device_or_skip();
  if (!cc) return;
  const host::Communicator& world = test::world();
  const host::WindGridSetup setup = test::turbulent_tunnel();
  const trees::Forest forest = forest_across_cuts();
  const auto inputs = host::TimeInputs::steady(setup.ambient);

  host::CoupledStep alone(*cc, setup, forest, coupling(setup.spec), inputs);
  alone.start();
  for (int n = 0; n < kSteps; ++n) alone.step();
  const host::ModalState expected = alone.trees().download_modal_state();
  const std::vector<float> expected_wind = alone.trees().download_sampled_wind();

  for (const auto blocks : test::splits(world.size())) {
    INFO(blocks[0] << " x " << blocks[1] << " blocks on " << world.size() << " ranks");
    const host::WindBlocks split = test::blocks_of(setup, blocks, world);
    host::CoupledStep coupled(*cc, setup, forest, coupling(setup.spec), inputs, &split);
    coupled.start();
    for (int n = 0; n < kSteps; ++n) {
      const host::CoupledStepReport report = coupled.step();
      CHECK(report.wind.step == n + 1);
    }
    // Every tree is some rank's, and one rank's only.
    const trees::Forest& mine = coupled.own_forest();
    CHECK(world.sum(static_cast<long long>(mine.instance_count())) == forest.instance_count());
    // Split at 2 or 4 ranks, the crowns reach into other blocks (the forest lies around those cuts), so
    // samples travel; the cuts of 3 ranks fall elsewhere.
    if (world.size() == 2 || world.size() == 4)
      CHECK(world.sum(static_cast<long long>(coupled.trees().remote_samples())) > 0);
    const host::ModalState state = coupled.trees().download_modal_state();
    const std::vector<float> wind = coupled.trees().download_sampled_wind();
    for (int k = 0; k < mine.instance_count(); ++k) {
      const int id = mine.id(k);
      INFO("tree " << id);
      for (int i = 0; i < forest.species_of(id).modes().mode_count(); ++i) {
        CHECK(state.q[std::size_t(mine.mode_offset(k) + i)] ==
              expected.q[std::size_t(forest.mode_offset(id) + i)]);
        CHECK(state.qdot[std::size_t(mine.mode_offset(k) + i)] ==
              expected.qdot[std::size_t(forest.mode_offset(id) + i)]);
      }
      for (int s = 0; s < 3 * forest.species_of(id).wind().sample_count(); ++s)
        CHECK(wind[std::size_t(3 * mine.sample_offset(k) + s)] ==
              expected_wind[std::size_t(3 * forest.sample_offset(id) + s)]);
    }
  }
}

TEST_CASE("PointWindAcrossRanks: each point is sampled by the rank that holds it, to the bits of one process",
          "[mpi]") {
  auto* cc = test::device_or_skip();
  if (!cc) return;
  const host::Communicator& world = test::world();
  const host::WindGridSetup setup = test::turbulent_tunnel();
  host::WindGrid alone(*cc, setup);
  alone.set_turbulence_sigma(1.0);
  alone.initialise_ambient();
  for (int n = 0; n < kSteps; ++n) alone.step();
  const std::vector<float> points = points_of_rank(world.rank());
  host::PointWindReadback whole(*cc, setup.spec, points);
  const std::vector<float> expected = whole.sample_flat(alone.velocity());

  const host::WindBlocks split{
      &world, fluid::Decomposition::make(
                  setup.spec, world.size(), std::nullopt,
                  host::advection_method(setup.settings.advection).halo_cells(setup.settings.cfl))};
  host::WindGrid wind(*cc, setup, &split);
  wind.set_turbulence_sigma(1.0);
  wind.initialise_ambient();
  for (int n = 0; n < kSteps; ++n) wind.step();
  host::PointWindAcrossRanks exchange(*cc, wind.local_spec(), &split, points);
  CHECK(exchange.point_count() == int(points.size() / 3));
  const std::vector<float> sampled = exchange.exchange(wind.velocity());
  REQUIRE(sampled.size() == expected.size());
  for (std::size_t n = 0; n < sampled.size(); ++n) {
    INFO("value " << n);
    CHECK(sampled[n] == expected[n]);
  }
}

// A block without trees or canopy still takes part in every exchange its neighbours make: the canopy's drag
// step exchanged halos only on the ranks whose block had some drag, and a row of 3 or 4 ranks then paired
// its messages with the wrong exchanges (a hang, MPI_ERR_TRUNCATE or a corrupted heap).
TEST_CASE("CoupledStep over ranks: a forest in one corner steps to the bits of one process in every split",
          "[mpi]") {
  auto* cc = test::device_or_skip();
  if (!cc) return;
  const host::Communicator& world = test::world();
  const host::WindGridSetup setup = test::turbulent_tunnel();
  const trees::Forest forest = forest_in_a_corner();
  const auto inputs = host::TimeInputs::steady(setup.ambient);
  host::CouplingSettings corner;
  corner.drag_density = test::canopy_in_cells(setup.spec, {1, 0, 0}, {7, 4, 5}, 0.3f);

  host::CoupledStep alone(*cc, setup, forest, corner, inputs);
  alone.start();
  for (int n = 0; n < kSteps; ++n) alone.step();
  const host::ModalState expected = alone.trees().download_modal_state();
  const std::vector<float> points = points_of_rank(world.rank());
  const std::vector<float> expected_wind =
      host::PointWindReadback(*cc, setup.spec, points).sample_flat(alone.wind().velocity());

  for (const auto blocks : test::splits(world.size())) {
    INFO(blocks[0] << " x " << blocks[1] << " blocks on " << world.size() << " ranks");
    const host::WindBlocks split = test::blocks_of(setup, blocks, world);
    host::CoupledStep coupled(*cc, setup, forest, corner, inputs, &split);
    CHECK(coupled.wind().canopy_enabled());  // on every rank, with or without drag in its block
    coupled.start();
    for (int n = 0; n < kSteps; ++n) coupled.step();
    const trees::Forest& mine = coupled.own_forest();
    CHECK(world.sum(static_cast<long long>(mine.instance_count())) == forest.instance_count());
    // Wind everywhere, trees or not, is one process's.
    host::PointWindAcrossRanks exchange(*cc, coupled.wind().local_spec(), &split, points);
    const std::vector<float> wind = exchange.exchange(coupled.wind().velocity());
    REQUIRE(wind.size() == expected_wind.size());
    for (std::size_t n = 0; n < wind.size(); ++n) {
      INFO("value " << n);
      CHECK(wind[n] == expected_wind[n]);
    }
    const host::ModalState state = coupled.trees().download_modal_state();
    for (int k = 0; k < mine.instance_count(); ++k) {
      const int id = mine.id(k);
      INFO("tree " << id);
      for (int i = 0; i < forest.species_of(id).modes().mode_count(); ++i)
        CHECK(state.q[std::size_t(mine.mode_offset(k) + i)] ==
              expected.q[std::size_t(forest.mode_offset(id) + i)]);
    }
  }
}
