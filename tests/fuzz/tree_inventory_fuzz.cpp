// Fuzz target: a forest inventory CSV (io/gis/TreeInventory), as `forest.inventory` will read it.
// Feeds: the bytes as scratch/trees.csv, the default column names, two species. Checks: every tree read has
// finite coordinates, a known species, a positive height and dbh, a positive crown width if any, an id no
// other tree has, and lines that increase.
// Clean refusals: base::SourceError naming the file ("FILE:LINE: COLUMN: ..."). Bugs: anything else: a
// crash, a sanitizer report, another exception, a hang, a huge allocation.
#include <cmath>
#include <cstdint>
#include <set>
#include <string>

#include "base/SourceError.hpp"
#include "io/gis/TreeInventory.hpp"
#include "tests/fuzz/FuzzSupport.hpp"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  const auto path = fw::fuzz::write_input("trees.csv", data, size);
  try {
    const fw::io::TreeInventory inventory =
        fw::io::read_tree_inventory(path, {}, {"Picea abies", "Fagus sylvatica"});
    std::set<std::string> ids;
    int last_line = 1;
    for (const fw::io::InventoryTree& t : inventory.trees) {
      if (!std::isfinite(t.x) || !std::isfinite(t.y)) fw::fuzz::fail("a tree at a coordinate not finite");
      if (t.species < 0 || t.species > 1) fw::fuzz::fail("a species outside the names given");
      if (!(t.height > 0.0) || !(t.dbh > 0.0) || !std::isfinite(t.height) || !std::isfinite(t.dbh))
        fw::fuzz::fail("a height or dbh not finite and positive");
      if (t.crown_width && !(*t.crown_width > 0.0)) fw::fuzz::fail("a crown width not positive");
      if (!ids.insert(t.id).second) fw::fuzz::fail("an id read twice");
      if (!(t.line > last_line)) fw::fuzz::fail("lines that do not increase");
      last_line = t.line;
    }
  } catch (const fw::base::SourceError& e) {
    fw::fuzz::expect_names_file(e, path);
  }
  return 0;
}
