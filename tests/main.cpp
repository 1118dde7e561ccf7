// The tests' main: Catch's, inside an MPI session, so that a test binary started by mpirun runs as ranks
// (tests/support/TestWorld.hpp) and one started alone runs as it always has.
#define CATCH_CONFIG_RUNNER
#include <catch2/catch.hpp>

#include "host/runtime/Communicator.hpp"
#include "host/runtime/Device.hpp"
#include "tests/support/TestWorld.hpp"

int main(int argc, char** argv) {
  fw::host::MpiSession mpi(argc, argv);
  fw::host::share_cpu_cores(mpi.world().node_size());
  fw::test::set_world(mpi.world());
  return Catch::Session().run(argc, argv);
}
