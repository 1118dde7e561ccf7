// forest.inventory: a CSV's trees, read at load, local to the site, and the ones outside the domain kept
// apart (io/scenario/Forest.cpp, docs/gis.md).
#include <catch2/catch.hpp>

#include <string>

#include "base/SourceError.hpp"
#include "io/Scenario.hpp"
#include "tests/support/TempDir.hpp"

namespace {

// Without a terrain raster there is no site: the inventory's x and y are the run's coordinates.
std::string scenario(const std::string& inventory) {
  return "scenario: inventory\n"
         "time: {end: 1.0}\n"
         "domain: {origin: [100, 200, 0], size: [40, 20, 16], cell_size: 2.0}\n"
         "wind: {speed: 5.0, direction: 270}\n"
         "forest:\n"
         "  species:\n"
         "    - {name: spruce, skeleton: {generate: {preset: conifer, height: 10, seed: 1}}}\n"
         "    - {name: beech, skeleton: {generate: {preset: broadleaf, height: 10, seed: 1}}}\n"
         "  inventory: " +
         inventory + "\n";
}

}  // namespace

TEST_CASE("inventory: trees inside the domain are read in file order, the ones outside counted apart",
          "[scenario]") {
  fw::test::TempDir dir("fw_inventory");
  dir.write("survey.csv",
            "Tree,E,N,Art,Z,BHD\n"
            "a1,110,205,spruce,21.5,0.31\n"
            "a2,150,205,beech,18,0.29\n"  // x 150: east of the domain's 100 .. 140
            "a3,139.5,219,beech,17.25,0.27\n");
  const fw::io::Scenario s = fw::io::load_scenario(dir.write(
      "mapped.yaml",
      scenario("{file: survey.csv, columns: {id: Tree, x: E, y: N, species: Art, height: Z, dbh: BHD}}")));
  REQUIRE(s.forest.inventory.has_value());
  const fw::io::InventorySettings& inventory = *s.forest.inventory;
  CHECK(inventory.rows() == 3);
  REQUIRE(inventory.trees.size() == 2);
  CHECK(inventory.trees[0].id == "a1");
  CHECK(inventory.trees[0].species == 0);
  CHECK(inventory.trees[0].height == 21.5);
  CHECK(inventory.trees[1].id == "a3");
  CHECK(inventory.trees[1].species == 1);
  CHECK(inventory.trees[1].x == 139.5);
  REQUIRE(inventory.outside.size() == 1);
  CHECK(inventory.outside[0].id == "a2");
  CHECK(inventory.outside[0].line == 3);
}

TEST_CASE("inventory: the file's errors name its line and column as its header spells it", "[scenario]") {
  fw::test::TempDir dir("fw_inventory");
  dir.write("bad.csv", "id,x,y,species,height,dbh\nb1,110,205,oak,20,0.3\n");
  try {
    fw::io::load_scenario(dir.write("bad.yaml", scenario("{file: bad.csv}")));
    FAIL("load_scenario accepted an unknown species");
  } catch (const fw::base::SourceError& error) {
    const std::string what = error.what();
    INFO(what);
    CHECK_THAT(what, Catch::Contains("bad.csv:2: species: ") && Catch::Contains("spruce, beech"));
  }
}
