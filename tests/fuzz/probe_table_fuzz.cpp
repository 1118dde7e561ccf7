// Fuzz target: probes.csv read back for `forestwind plot` (viz/ProbeTable).
// Feeds: the bytes as scratch/probes.csv. Checks: every series of a table it reads has one sample per
// time, and the magnitudes come out with the same count.
// Clean refusals: std::invalid_argument naming the file ("FILE:LINE: ..."). Bugs: anything else: a crash,
// a sanitizer report, another exception, a hang, a huge allocation.
#include <cstdint>
#include <stdexcept>

#include "tests/fuzz/FuzzSupport.hpp"
#include "viz/ProbeTable.hpp"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  const auto path = fw::fuzz::write_input("probes.csv", data, size);
  try {
    const fw::viz::ProbeTable table = fw::viz::read_probe_table(path);
    for (const auto* series : {&table.probes, &table.tips})
      for (const auto& s : *series)
        if (s.xyz.size() != table.time.size() || s.magnitude().size() != table.time.size())
          fw::fuzz::fail("a series with another sample count than the times");
  } catch (const std::invalid_argument& e) {
    fw::fuzz::expect_names_file(e, path);
  }
  return 0;
}
