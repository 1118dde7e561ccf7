// The ranks a test binary runs as: all of mpirun's when it started the binary, else one alone.
//
//   TEST_CASE("halo: ...", "[mpi]") {
//     const fw::host::Communicator& world = fw::test::world();
//     if (world.size() == 1) WARN("one rank: nothing crosses a block border");
//   }
#pragma once

#include "host/runtime/Communicator.hpp"

namespace fw::test {

const host::Communicator& world();
/// Called once by the tests' main.
void set_world(const host::Communicator& world);

}  // namespace fw::test
