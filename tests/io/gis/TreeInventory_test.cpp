// io/gis/TreeInventory: a tree list as lidR, R's write.csv and a spreadsheet write it reads with its columns
// mapped, and each bad row or header is refused as FILE:LINE: COLUMN: what was expected, got what.
#include "io/gis/TreeInventory.hpp"

#include <catch2/catch.hpp>

#include <string>
#include <vector>

#include "base/SourceError.hpp"
#include "tests/support/TempDir.hpp"

using fw::io::InventoryColumns;
using fw::io::read_tree_inventory;

namespace {

const std::vector<std::string> kSpecies = {"Picea abies", "Fagus sylvatica"};

// The message read_tree_inventory throws for `content` (empty when it reads).
std::string error_of(const std::string& content, const InventoryColumns& columns = {}) {
  const fw::test::TempDir dir("fw_inventory");
  try {
    read_tree_inventory(dir.write("trees.csv", content), columns, kSpecies);
  } catch (const fw::base::SourceError& e) {
    const std::string message = e.what();
    return message.substr(message.find("trees.csv"));  // from the file's name on
  }
  return "";
}

}  // namespace

TEST_CASE("TreeInventory: an R-written table reads with its columns mapped, quotes, CRLF and a BOM", "[io]") {
  const fw::test::TempDir dir("fw_inventory");
  // As R's write.csv(row.names = FALSE) writes lidR's crown metrics, saved from Windows with a BOM: quoted
  // names, CRLF, an extra column (ZTOP) the mapping ignores, a crown width left empty.
  const std::string path =
      dir.write("trees.csv",
                "\xEF\xBB\xBF\"treeID\",\"X\",\"Y\",\"Z\",\"DBH\",\"species\",\"cw\",\"ZTOP\"\r\n"
                "\"a-1\",500012.25,5400031.5,21.5,0.31,\"Picea abies\",4.2,22\r\n"
                "\r\n"
                "\"b \"\"2\"\"\",500020,5400040.75,+18,0.275,\"Fagus sylvatica\",,19\r\n");
  const InventoryColumns columns{.x = "X",
                                 .y = "Y",
                                 .species = "species",
                                 .height = "Z",
                                 .dbh = "DBH",
                                 .crown_width = "cw",
                                 .id = "treeID"};
  const fw::io::TreeInventory inventory = read_tree_inventory(path, columns, kSpecies);
  REQUIRE(inventory.trees.size() == 2);
  const fw::io::InventoryTree& a = inventory.trees[0];
  CHECK(a.id == "a-1");
  CHECK(a.x == 500012.25);  // every digit of a UTM easting and northing: read as double
  CHECK(a.y == 5400031.5);
  CHECK(a.species == 0);
  CHECK(a.height == 21.5);
  CHECK(a.dbh == 0.31);
  CHECK(a.crown_width == 4.2);
  CHECK(a.line == 2);
  const fw::io::InventoryTree& b = inventory.trees[1];
  CHECK(b.id == "b \"2\"");  // "" inside quotes is one quote
  CHECK(b.species == 1);
  CHECK(b.height == 18.0);
  CHECK_FALSE(b.crown_width.has_value());
  CHECK(b.line == 4);  // the blank line 3 is skipped, and counted
  // Without an id column, a tree's id is its line.
  const fw::io::TreeInventory plain = read_tree_inventory(
      dir.write("plain.csv", "x,y,species,height,dbh\n1,2,Picea abies,20,0.3\n3,4,Picea abies,21,0.32\n"), {},
      kSpecies);
  CHECK(plain.trees[1].id == "3");
}

TEST_CASE("TreeInventory: each error the issue names reads FILE:LINE: COLUMN: what was expected", "[io]") {
  CHECK(error_of("x,y,species,height,dbh\n"
                 "1,2,Picea abies,20,0.3\n3,4,Quercus robur,18,0.4\n") ==
        "trees.csv:3: species: one of the scenario's species (Picea abies, Fagus sylvatica), got \"Quercus "
        "robur\"");
  CHECK(error_of("x,y,species,height\n1,2,Picea abies,20\n") ==
        "trees.csv:1: dbh: a column named dbh, got the header x, y, species, height");
  CHECK(error_of("x,y,species,height,dbh\n"
                 "1,2,Picea abies,tall,0.3\n") == "trees.csv:2: height: a number > 0 (m), got \"tall\"");
  CHECK(error_of("x,y,species,height,dbh\n"
                 "1,north,Picea abies,20,0.3\n") ==
        "trees.csv:2: y: a number (m, the site's CRS), got \"north\"");
  CHECK(error_of("x,y,species,height,dbh\n"
                 "1,2,Picea abies,0,0.3\n") == "trees.csv:2: height: a number > 0 (m), got 0");
  CHECK(error_of("x,y,species,height,dbh\n"
                 "1,2,Picea abies,20,-0.3\n") == "trees.csv:2: dbh: a number > 0 (m), got -0.3");
  // A mapped name is the one the message gives: the file's own.
  const InventoryColumns lidr{.height = "Z"};
  CHECK(error_of("x,y,species,Z,dbh\n1,2,Picea abies,nan,0.3\n", lidr) ==
        "trees.csv:2: Z: a number > 0 (m), got \"nan\"");
}

TEST_CASE("TreeInventory: rows, quotes, ids and empty files that do not fit are refused at their line",
          "[io]") {
  CHECK(error_of("id,x,y,species,height,dbh,crown_width\n"
                 "t1,1,2,Picea abies,20,0.3\n") == "trees.csv:2: row: 7 fields, as the header has, got 6");
  CHECK(error_of("id,x,y,species,height,dbh,crown_width\n"
                 "t1,1,2,Picea abies,20,0.3,3\nt1,5,6,Picea abies,20,0.3,3\n") ==
        "trees.csv:3: id: an id no other row has (line 2 has it), got \"t1\"");
  CHECK(error_of("id,x,y,species,height,dbh,crown_width\n"
                 ",1,2,Picea abies,20,0.3,3\n") ==
        "trees.csv:2: id: an id (any text, unique), got an empty field");
  CHECK(error_of("id,x,y,species,height,dbh,crown_width\n"
                 "t1,1,2,Picea abies,20,0.3,-1\n") == "trees.csv:2: crown_width: a number > 0 (m), got -1");
  CHECK(error_of("id,x,y,species,height,dbh,crown_width\n"
                 "t1,1,2,\"Picea abies,20,0.3,3\n") ==
        "trees.csv:2: field 4: a closing quote before the line ends (a field does not span lines)");
  CHECK(error_of("id,x,y,species,height,dbh,crown_width\n"
                 "t1,1,2,\"Picea\" abies,20,0.3,3\n") ==
        "trees.csv:2: field 4: a comma after a closing quote, got  ");
  CHECK(error_of("x,y,x,species,height,dbh\n") == "trees.csv:1: x: each column named once, got it twice");
  CHECK(error_of("") == "trees.csv: empty: a header and a row per tree expected");
  CHECK(error_of("id,x,y,species,height,dbh,crown_width\n") ==
        "trees.csv: a row per tree expected, found none");
  CHECK_THROWS_WITH(read_tree_inventory("/nonexistent/trees.csv", {}, kSpecies),
                    Catch::Matchers::Contains("/nonexistent/trees.csv: cannot open"));
}
