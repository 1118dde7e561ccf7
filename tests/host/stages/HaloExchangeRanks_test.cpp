// host/stages/HaloExchange's traffic over MPI ranks (CTest runs this binary at 1, 2 and 4 ranks): the bytes
// and messages an exchange counts are the halo the block layout implies, for every split, and nothing in one
// process; the wind grid adds up its exchanges. Behaviour only: no time is asserted beyond its sign.
#include <catch2/catch.hpp>

#include <algorithm>
#include <optional>
#include <string>
#include <vector>

#include "fluid/Decomposition.hpp"
#include "host/stages/BlockGrid.hpp"
#include "host/stages/HaloExchange.hpp"
#include "host/stages/SavedShare.hpp"
#include "host/stages/WindGrid.hpp"
#include "tests/support/Fields.hpp"
#include "tests/support/TestDevice.hpp"
#include "tests/support/TestWorld.hpp"
#include "tests/support/Tunnels.hpp"

using namespace fw;
using B = fluid::BoundaryType;

namespace {

constexpr int kHalo = 3;  // cells, upwind5's reach and the smallest halo a run takes
constexpr long long kFloatBytes = sizeof(float);

// 32 x 16 x 6 cells, periodic along y, so that a cut y axis sends across the wrap too.
fluid::GridSpec channel_spec() {
  fluid::GridSpec spec;
  spec.nx = 32, spec.ny = 16, spec.nz = 6, spec.h = 1.0;
  spec.boundary = {B::inflow, B::outflow, B::periodic, B::periodic, B::no_slip, B::slip};
  return spec;
}

// The sides of a block with a neighbour: one message each per exchange.
int neighbour_sides(const fluid::Block& b) {
  int sides = 0;
  for (int a = 0; a < 2; ++a) sides += (b.halo_low[a] > 0 ? 1 : 0) + (b.halo_high[a] > 0 ? 1 : 0);
  return sides;
}

// What one exchange of a field on block b sends, from the block alone: along each axis, the halo's width on
// its sides with a neighbour, times the values across that axis (the other axis's cells with their halo, one
// more where the field is staggered along it), times the values up z (one more for w), 4 bytes a float.
// staggered: the axis of a velocity component's faces, -1 for cells.
long long halo_bytes(const fluid::Block& b, int staggered, int nz) {
  const long long z_values = nz + (staggered == 2 ? 1 : 0);
  long long bytes = 0;
  for (int a = 0; a < 2; ++a) {
    const int other = 1 - a;
    const long long across = b.extent(other) + (staggered == other ? 1 : 0);
    bytes += (b.halo_low[a] + b.halo_high[a]) * across * z_values * kFloatBytes;
  }
  return bytes;
}

}  // namespace

TEST_CASE(
    "HaloExchange: each rank sends its halo width x the values across each cut side x the values up z, "
    "4 bytes each, for cells and each velocity component",
    "[mpi]") {
  auto* cc = test::device_or_skip();
  if (!cc) return;
  const host::Communicator& world = test::world();
  const fluid::GridSpec spec = channel_spec();
  for (const auto blocks : test::splits(world.size())) {
    const fluid::Decomposition d = fluid::Decomposition::make(spec, world.size(), blocks, kHalo);
    const fluid::Block block = d.block(world.rank());
    const host::BlockArray cells = host::block_array(d, world.rank(), 0, spec.nz, kHalo);
    for (int staggered = -1; staggered < 3; ++staggered) {
      INFO((staggered < 0 ? "cells" : "faces across axis " + std::to_string(staggered))
           << ", " << blocks[0] << " x " << blocks[1] << " blocks on " << world.size() << " ranks");
      const host::BlockArray layout = staggered < 0 ? cells : host::face_array(cells, staggered);
      host::HaloExchange halo(*cc, world, layout);
      cl::Buffer field = cc->zero_floats(layout.cells());
      halo.exchange(field);
      const host::HaloTraffic first = halo.traffic();
      CHECK(first.bytes == halo_bytes(block, staggered, spec.nz));
      CHECK(first.messages == neighbour_sides(block));
      CHECK(first.seconds >= first.copy_seconds);
      CHECK(first.copy_seconds >= 0.0);
      // The counters add up: a second exchange counts as much again.
      halo.exchange(field);
      const host::HaloTraffic second = halo.traffic() - first;
      CHECK(second.bytes == first.bytes);
      CHECK(second.messages == first.messages);
    }
  }
}

TEST_CASE(
    "HaloExchange: the ranks send the decomposition's halo cells, and the corners of blocks cut along x "
    "and y once more",
    "[mpi]") {
  auto* cc = test::device_or_skip();
  if (!cc) return;
  const host::Communicator& world = test::world();
  const fluid::GridSpec spec = channel_spec();
  for (const auto blocks : test::splits(world.size())) {
    INFO(blocks[0] << " x " << blocks[1] << " blocks on " << world.size() << " ranks");
    const fluid::Decomposition d = fluid::Decomposition::make(spec, world.size(), blocks, kHalo);
    const host::BlockArray layout = host::block_array(d, world.rank(), 0, spec.nz, kHalo);
    host::HaloExchange halo(*cc, world, layout);
    cl::Buffer field = cc->zero_floats(layout.cells());
    halo.exchange(field);
    // The x phase sends whole columns, the y halo's rows included, and the y phase then sends those corners
    // again (with the values the x phase brought): a block's corners travel twice.
    const fluid::Block b = d.block(world.rank());
    const long long corners =
        (long long)(b.halo_low[0] + b.halo_high[0]) * (b.halo_low[1] + b.halo_high[1]) * spec.nz;
    CHECK(world.sum(halo.traffic().bytes) == (d.halo_cells() + world.sum(corners)) * kFloatBytes);
    if (world.size() == 1) CHECK(halo.traffic().bytes == 0);
  }
}

TEST_CASE(
    "HaloExchange: one cell deep it fills the halo cells next to the block from their owners and leaves the "
    "rest",
    "[mpi]") {
  auto* cc = test::device_or_skip();
  if (!cc) return;
  const host::Communicator& world = test::world();
  const fluid::GridSpec spec = channel_spec();
  constexpr float kUntouched = -1.0f;
  // A cell's value names it: 1 + its domain index (y wrapped, the axis being periodic); the halo starts
  // untouched.
  const auto value_of = [&](int gi, int gj, int k) {
    gj = (gj % spec.ny + spec.ny) % spec.ny;
    return float(1 + gi + spec.nx * (gj + spec.ny * k));
  };
  for (const auto blocks : test::splits(world.size())) {
    INFO(blocks[0] << " x " << blocks[1] << " blocks on " << world.size() << " ranks");
    const fluid::Decomposition d = fluid::Decomposition::make(spec, world.size(), blocks, kHalo);
    const host::BlockArray a = host::block_array(d, world.rank(), 0, spec.nz, kHalo);
    const host::OwnColumns own = host::own_columns(a);
    // How far outside the own columns cell (i, j) of the block lies, along the axis it lies furthest.
    const auto depth = [&](int i, int j) {
      const int gi = a.origin[0] + i, gj = a.origin[1] + j;
      const int dx = std::max({own.lo[0] - gi, gi - (own.hi[0] - 1), 0});
      const int dy = std::max({own.lo[1] - gj, gj - (own.hi[1] - 1), 0});
      return std::max(dx, dy);
    };
    std::vector<float> values(a.cells());
    for (int k = 0; k < spec.nz; ++k)
      for (int j = 0; j < a.extent[1]; ++j)
        for (int i = 0; i < a.extent[0]; ++i)
          values[std::size_t(i + a.extent[0] * (j + a.extent[1] * k))] =
              depth(i, j) == 0 ? value_of(a.origin[0] + i, a.origin[1] + j, k) : kUntouched;
    cl::Buffer field = cc->upload(values);
    host::HaloExchange halo(*cc, world, a);
    halo.exchange(field, 1);
    const std::vector<float> after = test::download(*cc, field, values.size());
    long long wrong = 0;
    for (int k = 0; k < spec.nz; ++k)
      for (int j = 0; j < a.extent[1]; ++j)
        for (int i = 0; i < a.extent[0]; ++i) {
          const float expected =
              depth(i, j) <= 1 ? value_of(a.origin[0] + i, a.origin[1] + j, k) : kUntouched;
          wrong += after[std::size_t(i + a.extent[0] * (j + a.extent[1] * k))] != expected;
        }
    CHECK(wrong == 0);
  }
}

TEST_CASE("WindGrid: its halo traffic adds up its exchanges over ranks and is zero in one process", "[mpi]") {
  auto* cc = test::device_or_skip();
  if (!cc) return;
  const host::Communicator& world = test::world();
  const host::WindGridSetup setup = test::tunnel(fluid::AdvectionScheme::semi_lagrangian);
  host::WindGrid alone(*cc, setup);
  alone.initialise_ambient();
  alone.step();
  CHECK(alone.halo_traffic().bytes == 0);
  CHECK(alone.halo_traffic().messages == 0);
  CHECK(alone.halo_traffic().seconds == 0.0);

  const host::WindBlocks blocks{
      &world, fluid::Decomposition::make(
                  setup.spec, world.size(), std::nullopt,
                  host::advection_method(setup.settings.advection).halo_cells(setup.settings.cfl))};
  host::WindGrid wind(*cc, setup, &blocks);
  wind.initialise_ambient();
  const host::HaloTraffic before = wind.halo_traffic();
  wind.step();
  const host::HaloTraffic step = wind.halo_traffic() - before;
  if (world.size() == 1) {
    CHECK(step.bytes == 0);
    return;
  }
  // A step exchanges at least the velocity's three components once; each sends a whole face array's halo.
  long long velocity_once = 0;
  for (int c = 0; c < 3; ++c)
    velocity_once += halo_bytes(blocks.decomposition.block(world.rank()), c, setup.spec.nz);
  CHECK(step.bytes > velocity_once);
  CHECK(step.messages > 0);
  CHECK(step.seconds >= step.copy_seconds);
}
