// Fuzz target: the PGM terrain reader, P2 and P5 (fluid/Heightmap), chosen from content.
// Feeds: the bytes as scratch/terrain, read with the cell size and height of scenarios/hills.pgm's use.
// Checks: a terrain it reads has finite heights at its corners and centre.
// Clean refusals: std::runtime_error whose message names the file ("FILE:LINE: ...", the header comment's
// contract). Bugs: anything else: a crash, a sanitizer report, another exception (length_error,
// bad_alloc, invalid_argument from the in-memory constructor), a hang, a huge allocation.
#include <cmath>
#include <cstdint>
#include <stdexcept>

#include "fluid/Heightmap.hpp"
#include "tests/fuzz/FuzzSupport.hpp"

namespace {

constexpr double kCellSizeM = 8.0;    // metres per pixel, as scenarios/storm.yaml reads hills.pgm
constexpr double kMaxHeightM = 20.0;  // metres for the brightest pixel, likewise

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  const auto path = fw::fuzz::write_input("terrain", data, size);
  try {
    const auto terrain = fw::fluid::Heightmap::read(path.string(), kCellSizeM, kMaxHeightM);
    const auto [x0, y0] = terrain.sw_centre();
    const double width = terrain.cell_size() * (terrain.columns() - 1);
    const double depth = terrain.cell_size() * (terrain.rows() - 1);
    for (double fx : {0.0, 0.5, 1.0})
      for (double fy : {0.0, 0.5, 1.0})
        if (!std::isfinite(terrain.height_at(x0 + fx * width, y0 + fy * depth)))
          fw::fuzz::fail("a terrain read with a height that is not finite");
  } catch (const std::runtime_error& e) {
    fw::fuzz::expect_names_file(e, path);
  }
  return 0;
}
