#include "tests/support/TestWorld.hpp"

namespace fw::test {
namespace {
const host::Communicator* the_world = nullptr;
}

const host::Communicator& world() {
  return the_world ? *the_world : host::Communicator::alone();
}

void set_world(const host::Communicator& world) {
  the_world = &world;
}

}  // namespace fw::test
