#include <catch2/catch.hpp>

#include <filesystem>
#include <string>
#include <vector>

#include "io/DamageCsv.hpp"
#include "tests/support/RunFolders.hpp"
#include "tests/support/SourceErrors.hpp"
#include "tests/support/TempDir.hpp"
#include "viz/CsvText.hpp"
#include "viz/DamageTable.hpp"

namespace fs = std::filesystem;
using fw::trees::TreeState;
using fw::viz::read_damage_table;

namespace {

void read_file(const std::string& path) {
  read_damage_table(path);
}

// A damage.csv with one good standing tree on line 2 and `row` on line 3.
std::string with_row(const std::string& row) {
  return fw::test::damage_csv({"0,spruce,1,2,20,0.3,standing,,,,1e4,5e4,6e4,0.5", row});
}

}  // namespace

TEST_CASE("DamageTable: reads each state, leaves a standing tree's failure empty, ignores later columns",
          "[viz]") {
  fw::test::TempDir dir("fw_viz");
  const std::string text =
      "tree_id,species,x,y,height_m,dbh_m,state,time_s,break_height_m,top_wind_m_s,max_base_moment_Nm,"
      "critical_breakage_Nm,critical_overturning_Nm,max_utilisation,note\n"
      "2,norway spruce,10.5,-3,24.5,0.41,standing,,,,120000,350000,410000,0.62,a\n"
      "\n"
      "0,beech,+1,2,18,0.35,broken,12.25,7.5,21.3,380000,300000,500000,1.27,\n"
      "1,beech,3,4,18,0.35,overturned,30,0,25,510000,600000,500000,1.02,b";  // written whole: no line end
  const auto table = read_damage_table(dir.write("damage.csv", text));
  REQUIRE(table.trees.size() == 3);
  const auto& standing = table.trees[0];
  CHECK(standing.id == 2);
  CHECK(standing.species == "norway spruce");
  CHECK(standing.x == 10.5);
  CHECK(standing.y == -3.0);
  CHECK(standing.height == 24.5);
  CHECK(standing.dbh == 0.41);
  CHECK(standing.state == TreeState::standing);
  CHECK_FALSE(standing.time);
  CHECK_FALSE(standing.break_height);
  CHECK_FALSE(standing.top_wind);
  CHECK(standing.critical_breakage == 350000.0);
  CHECK(standing.max_utilisation == 0.62);
  CHECK(standing.line == 2);
  const auto& broken = table.trees[1];
  CHECK(broken.state == TreeState::broken);
  CHECK(broken.x == 1.0);
  CHECK(broken.time == 12.25);
  CHECK(broken.break_height == 7.5);
  CHECK(broken.top_wind == 21.3);
  CHECK(broken.max_base_moment == 380000.0);
  CHECK(broken.line == 4);
  const auto& overturned = table.trees[2];
  CHECK(overturned.state == TreeState::overturned);
  CHECK(overturned.break_height == 0.0);
  CHECK(overturned.critical_overturning == 500000.0);
  CHECK(overturned.max_utilisation == 1.02);
  // A header alone: a stand without trees.
  CHECK(read_damage_table(dir.write("empty.csv", fw::test::damage_csv({}))).trees.empty());
}

TEST_CASE("DamageTable: a bad row says FILE:LINE: COLUMN: what was expected, and what was there", "[viz]") {
  using fw::test::check_source_error;
  const std::string name = "damage.csv";
  // Line 3 of a file whose line 2 is a good standing tree 0: the row, its column, what is said.
  struct BadRow {
    const char *row, *column, *detail;
  };
  const BadRow bad_rows[] = {
      // A standing tree with a failure time is an error, not tolerated: the row contradicts itself.
      {"1,spruce,1,2,20,0.3,standing,12.5,,,1e4,5e4,6e4,0.5", "time_s",
       "expected no value for a standing tree, got '12.5'"},
      {"1,spruce,1,2,20,0.3,standing,,,3,1e4,5e4,6e4,0.5", "top_wind_m_s",
       "expected no value for a standing tree"},
      {"1,spruce,1,2,20,0.3,fallen,,,,1e4,5e4,6e4,0.5", "state",
       "expected standing, broken or overturned, got 'fallen'"},
      {"1,spruce,1,2,20,0.3,broken,,5,20,1e4,5e4,6e4,1.2", "time_s", "expected a number >= 0, got ''"},
      {"1,spruce,1,2,20,0.3,broken,4,21,20,1e4,5e4,6e4,1.2", "break_height_m",
       "expected a height up to the tree's, 20 m, got '21'"},
      {"1,spruce,1,2,20,0.3,overturned,4,2,20,1e4,5e4,6e4,1.2", "break_height_m",
       "expected 0 for an overturned tree, got '2'"},
      {"1,spruce,1,2,20,0.3,broken,4,5,,1e4,5e4,6e4,1.2", "top_wind_m_s", "expected a number >= 0"},
      {"1,spruce,1,2,20,0.3,broken,4,5,20,1e4,5e4,6e4,0.9", "max_utilisation",
       "expected a number >= 1 for a broken tree, got '0.9'"},
      {"0,spruce,1,2,20,0.3,standing,,,,1e4,5e4,6e4,0.5", "tree_id", "tree 0 is on line 2 already"},
      {"-1,spruce,1,2,20,0.3,standing,,,,1e4,5e4,6e4,0.5", "tree_id",
       "expected a whole number >= 0, got '-1'"},
      {"1.5,spruce,1,2,20,0.3,standing,,,,1e4,5e4,6e4,0.5", "tree_id", "expected a whole number >= 0"},
      {"1,,1,2,20,0.3,standing,,,,1e4,5e4,6e4,0.5", "species", "expected the species' name"},
      {"1,spruce,east,2,20,0.3,standing,,,,1e4,5e4,6e4,0.5", "x", "expected a number, got 'east'"},
      {"1,spruce,1,2,0,0.3,standing,,,,1e4,5e4,6e4,0.5", "height_m", "expected a number > 0, got '0'"},
      {"1,spruce,1,2,20,0.3,standing,,,,1e4,nan,6e4,0.5", "critical_breakage_Nm",
       "expected a number > 0, got 'nan'"},
      {"1,spruce,1,2,20,0.3,standing,,,,1e4,5e4,6e4", "row", "expected 14 values, got 13"},
  };
  for (const BadRow& bad : bad_rows)
    check_source_error(read_file, name, with_row(bad.row), 3, bad.column, bad.detail);
  // The header.
  check_source_error(read_file, name,
                     "tree_id,species,x,y,height,dbh_m,state,time_s,break_height_m,top_wind_m_s,"
                     "max_base_moment_Nm,critical_breakage_Nm,critical_overturning_Nm,max_utilisation\n",
                     1, "header", "expected column 5 'height_m'");
  check_source_error(
      read_file, name, "tree_id,species,x\n", 1, "header",
      "expected column 4 'y' (a forestwind damage.csv starts with tree_id,species,x,y,height_m");
  check_source_error(read_file, name, "", 1, "header", "got the end of the line");
  CHECK_THAT(fw::test::source_error(read_file, "/nonexistent/damage.csv"),
             Catch::StartsWith("/nonexistent/damage.csv: cannot open"));
}

TEST_CASE("DamageTable: a tree stands until its failure time, and the counts step at the failures", "[viz]") {
  fw::test::TempDir dir("fw_viz");
  const auto table = read_damage_table(
      dir.write("damage.csv", fw::test::damage_csv({"0,spruce,1,2,20,0.3,standing,,,,1e4,5e4,6e4,0.5",
                                                    "1,spruce,3,2,20,0.3,broken,2.5,6,20,1e5,5e4,6e4,2",
                                                    "2,spruce,5,2,20,0.3,overturned,4,0,24,1e5,5e4,6e4,1.5",
                                                    "3,spruce,7,2,20,0.3,broken,4,8,24,1e5,5e4,6e4,1.1",
                                                    "4,spruce,9,2,20,0.3,broken,9,8,24,1e5,5e4,6e4,1.1"})));
  const auto& broken = table.trees[1];
  CHECK(broken.state_at(2.4) == TreeState::standing);
  CHECK(broken.state_at(2.5) == TreeState::broken);
  CHECK(broken.state_at(2.5 - 1e-7) == TreeState::broken);  // the files' rounding
  CHECK(table.trees[2].state_at(100.0) == TreeState::overturned);
  CHECK(table.trees[0].state_at(100.0) == TreeState::standing);
  CHECK(table.counts_at(0.0) == std::array<int, 3>{5, 0, 0});
  CHECK(table.counts_at(3.0) == std::array<int, 3>{4, 1, 0});
  CHECK(table.counts_at(4.0) == std::array<int, 3>{2, 2, 1});
  // Over 1 .. 6 s: the start, each failure time once (two trees at 4 s), the end; tree 4 fails after it.
  const fw::viz::DamageCounts counts = table.counts_over(1.0, 6.0);
  CHECK(counts.time == std::vector<double>{1.0, 2.5, 4.0, 6.0});
  CHECK(counts.standing == std::vector<int>{5, 4, 2, 2});
  CHECK(counts.broken == std::vector<int>{0, 1, 2, 2});
  CHECK(counts.overturned == std::vector<int>{0, 0, 1, 1});
  // Failures before the start are in every point.
  CHECK(table.counts_over(3.0, 3.5).broken == std::vector<int>{1, 1});
}

TEST_CASE("DamageTable: an inventory id with a comma or a quote reads back whole, as damage.csv quotes it",
          "[viz]") {
  std::vector<fw::io::DamageTree> trees(2);
  // Sizes and strengths as a run gives them: the table checks them.
  for (fw::io::DamageTree& tree : trees) {
    tree.height = 20.0;
    tree.dbh = 0.3;
    tree.critical_breakage = 1e5;
    tree.critical_overturning = 8e4;
  }
  trees[0].species = "spruce";
  trees[0].inventory_id = "plot 3, tree 7";
  trees[1].id = 1;
  trees[1].species = "beech";
  trees[1].inventory_id = "the \"old\" one";
  std::vector<fw::trees::TreeDamageRecord> records(2);
  const std::string text = fw::io::damage_csv(trees, records);
  CHECK_THAT(text, Catch::Contains(",\"plot 3, tree 7\"\n") && Catch::Contains(",\"the \"\"old\"\" one\"\n"));
  const std::vector<std::string> lines = fw::viz::csv_lines(text, false);
  REQUIRE(lines.size() == 3);
  const std::vector<std::string> header = fw::viz::split_csv(lines[0], "damage.csv", 1);
  CHECK(header.back() == "inventory_id");
  CHECK(fw::viz::split_csv(lines[1], "damage.csv", 2).back() == "plot 3, tree 7");
  CHECK(fw::viz::split_csv(lines[2], "damage.csv", 3).back() == "the \"old\" one");
  CHECK(fw::viz::split_csv(lines[2], "damage.csv", 3).size() == header.size());
  fw::test::TempDir dir("fw_viz");
  const auto table = read_damage_table(dir.write("damage.csv", text));
  CHECK(table.trees.size() == 2);
}
