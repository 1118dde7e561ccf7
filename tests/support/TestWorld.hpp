// The ranks a test binary runs as: all of mpirun's when it started the binary, else one alone.
//
//   TEST_CASE("halo: ...", "[mpi]") {
//     const fw::host::Communicator& world = fw::test::world();
//     if (world.size() == 1) WARN("one rank: nothing crosses a block border");
//   }
#pragma once

#include <array>
#include <vector>

#include "host/runtime/Communicator.hpp"

namespace fw::test {

const host::Communicator& world();
/// Called once by the tests' main.
void set_world(const host::Communicator& world);

/// Every split {px, py} of `ranks` into x-y blocks, px rising.
std::vector<std::array<int, 2>> splits(int ranks);

}  // namespace fw::test
