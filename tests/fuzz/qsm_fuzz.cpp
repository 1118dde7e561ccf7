// Fuzz target: the TreeQSM cylinder table reader (trees/QsmImport).
// Feeds: the bytes as scratch/input_cyl.txt. Checks: a skeleton it reads has one node more than the
// cylinders it counted.
// Clean refusals: base::SourceError naming the file ("FILE:LINE: COLUMN: ..."). Bugs: anything else: a
// crash, a sanitizer report, another exception, a hang, a huge allocation.
#include <cstdint>

#include "base/SourceError.hpp"
#include "tests/fuzz/FuzzSupport.hpp"
#include "trees/QsmImport.hpp"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  const auto path = fw::fuzz::write_input("input_cyl.txt", data, size);
  try {
    fw::trees::QsmImportInfo info;
    const fw::trees::Skeleton skeleton = fw::trees::read_qsm_cylinders(path.string(), &info);
    if (skeleton.size() != info.cylinders + 1) fw::fuzz::fail("nodes are not cylinders + 1");
  } catch (const fw::base::SourceError& e) {
    fw::fuzz::expect_names_file(e, path);
  }
  return 0;
}
