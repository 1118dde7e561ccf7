// Fuzz target: the `.tree` skeleton reader (trees/TreeFile).
// Feeds: the bytes as scratch/input.tree. Checks: a skeleton it reads is written back (write_tree_file)
// and read again to the same node count (the format's exact round trip).
// Clean refusals: base::SourceError naming the file ("FILE:LINE: KEY: ..."). Bugs: anything else: a crash,
// a sanitizer report, another exception, a hang, a huge allocation.
#include <cstdint>

#include "base/SourceError.hpp"
#include "tests/fuzz/FuzzSupport.hpp"
#include "trees/TreeFile.hpp"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  const auto path = fw::fuzz::write_input("input.tree", data, size);
  try {
    const fw::trees::Skeleton skeleton = fw::trees::read_tree_file(path.string());
    const auto copy = fw::fuzz::scratch_folder() / "copy.tree";
    fw::trees::write_tree_file(skeleton, copy.string());
    if (fw::trees::read_tree_file(copy.string()).size() != skeleton.size())
      fw::fuzz::fail("a skeleton read back has another node count");
  } catch (const fw::base::SourceError& e) {
    fw::fuzz::expect_names_file(e, path);
  }
  return 0;
}
