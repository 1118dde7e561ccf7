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

std::vector<std::array<int, 2>> splits(int ranks) {
  std::vector<std::array<int, 2>> all;
  for (int px = 1; px <= ranks; ++px)
    if (ranks % px == 0) all.push_back({px, ranks / px});
  return all;
}

}  // namespace fw::test
