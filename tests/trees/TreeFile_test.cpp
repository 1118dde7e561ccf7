#include "trees/TreeFile.hpp"

#include <catch2/catch.hpp>

#include "tests/support/SourceErrors.hpp"
#include "tests/support/TempDir.hpp"

#include <cmath>
#include <filesystem>
#include <random>
#include <stdexcept>
#include <string>
#include <vector>

using fw::test::TempDir;
using fw::trees::read_tree_file;
using fw::trees::Skeleton;
using fw::trees::SkeletonNode;
using fw::trees::write_tree_file;

namespace {

// Checks that reading `content` fails with a message that starts with "FILE:LINE: KEY: " and holds `detail`.
void check_error(const std::string& content, int line, const std::string& key, const std::string& detail) {
  fw::test::check_source_error(read_tree_file, "bad.tree", content, line, key, detail);
}

}  // namespace

TEST_CASE("TreeFile: write then read preserves every value exactly", "[trees][treefile]") {
  std::mt19937_64 random(42);
  std::uniform_real_distribution<double> coordinate(-50.0, 50.0);
  std::uniform_real_distribution<double> radius(1e-4, 0.5);
  std::vector<SkeletonNode> nodes;
  nodes.push_back({-1, {coordinate(random), coordinate(random), -0.0}, radius(random)});
  for (int i = 1; i < 200; ++i) {
    const int parent = int(random() % std::uint64_t(i));
    nodes.push_back({parent, {coordinate(random), coordinate(random), coordinate(random)}, radius(random)});
  }
  nodes.push_back({3, {1e-300, 1.0 / 3.0, 6.02214076e23}, 5e-320});  // extremes still round trip
  const auto skeleton = Skeleton::from_nodes(nodes);

  TempDir dir("fw_treefile");
  const auto path = dir.path() + "/round.tree";
  write_tree_file(skeleton, path);
  CHECK_FALSE(std::filesystem::exists(path + ".tmp"));
  const auto back = read_tree_file(path);
  REQUIRE(back.size() == skeleton.size());
  CHECK(back.root() == skeleton.root());
  for (int i = 0; i < skeleton.size(); ++i) {
    INFO("node " << i);
    CHECK(back.node(i).parent == skeleton.node(i).parent);
    CHECK(back.node(i).position.x() == skeleton.node(i).position.x());
    CHECK(back.node(i).position.y() == skeleton.node(i).position.y());
    CHECK(back.node(i).position.z() == skeleton.node(i).position.z());
    CHECK(back.node(i).radius == skeleton.node(i).radius);
  }
  CHECK(std::signbit(back.node(0).position.z()));

  // Writing over an existing file replaces it.
  write_tree_file(Skeleton::from_nodes({{-1, {0, 0, 0}, 0.1}}), path);
  CHECK(read_tree_file(path).size() == 1);
}

TEST_CASE("TreeFile: lines in any order, comments and blank lines", "[trees][treefile]") {
  TempDir dir("fw_treefile");
  const auto path = dir.write("order.tree",
                              "# a small tree, metres\n"
                              "\n"
                              "3 1 0.5 0 3 0.05   # a branch\n"
                              "   \t\n"
                              "1 0 0 0 2 0.15\r\n"
                              "0 -1 0 0 0 0.2\n"
                              "  # only a comment\n"
                              "2\t1\t0\t0\t+4.5\t1.5e-1\n"
                              "4 3 1e0 0 3.5 0.02");  // no final newline
  const auto skeleton = read_tree_file(path);
  REQUIRE(skeleton.size() == 5);
  CHECK(skeleton.root() == 0);
  CHECK(skeleton.node(1).parent == 0);
  CHECK(skeleton.node(2).parent == 1);
  CHECK(skeleton.node(2).position.z() == 4.5);
  CHECK(skeleton.node(2).radius == 0.15);
  CHECK(skeleton.node(3).parent == 1);
  CHECK(skeleton.node(3).position.x() == 0.5);
  CHECK(skeleton.node(4).parent == 3);
  CHECK(skeleton.node(4).position.x() == 1.0);
  CHECK(skeleton.height() == 4.5);
}

TEST_CASE("TreeFile: malformed structure names the offending line", "[trees][treefile]") {
  SECTION("a cycle") {
    check_error(
        "0 -1 0 0 0 0.2\n"
        "1 0 0 0 1 0.1\n"
        "2 3 0 0 2 0.1\n"  // 2 -> 3 -> 2
        "3 2 0 0 3 0.1\n",
        3, "parent", "cycle");
  }
  SECTION("two roots") {
    check_error(
        "0 -1 0 0 0 0.2\n"
        "1 0 0 0 1 0.1\n"
        "2 -1 5 0 0 0.2\n",
        3, "parent", "expected exactly one root");
  }
  SECTION("no root") {
    check_error(
        "0 1 0 0 0 0.2\n"
        "1 0 0 0 1 0.1\n",
        1, "parent", "found none");
  }
  SECTION("a missing parent") {
    check_error(
        "0 -1 0 0 0 0.2\n"
        "1 0 0 0 1 0.1\n"
        "2 7 0 0 2 0.1\n",
        3, "parent", "existing node in 0..2, got '7'");
  }
  SECTION("a parent below -1") {
    check_error("0 -1 0 0 0 0.2\n1 -2 0 0 1 0.1\n", 2, "parent", "got '-2'");
  }
  SECTION("a node that is its own parent") {
    check_error("0 -1 0 0 0 0.2\n1 1 0 0 1 0.1\n", 2, "parent", "other than the node itself");
  }
  SECTION("a zero-length element") {
    check_error(
        "# header\n"
        "0 -1 0 0 0 0.2\n"
        "1 0 0 0 1 0.1\n"
        "2 1 0 0 1.0 0.05\n",
        4, "x y z", "(a zero-length element), got '0 0 1.0'");
  }
}

TEST_CASE("TreeFile: malformed fields name the line and the column", "[trees][treefile]") {
  SECTION("a negative radius") {
    check_error("0 -1 0 0 0 0.2\n\n1 0 0 0 1 -0.1\n", 3, "radius",
                "expected a positive radius in metres, got '-0.1'");
  }
  SECTION("a zero radius") {
    check_error("0 -1 0 0 0 0.2\n1 0 0 0 1 0\n", 2, "radius", "got '0'");
  }
  SECTION("a non-numeric field") {
    check_error("0 -1 0 0 0 0.2\n1 0 0 abc 1 0.1\n", 2, "y", "expected a finite number in metres, got 'abc'");
    check_error("0 -1 0 0 0 0.2\n1 0 0 0 1 0.1x\n", 2, "radius", "got '0.1x'");
    check_error("0 -1 0 0 0 0.2\n1 0 0 0 nan 0.1\n", 2, "z", "got 'nan'");
    check_error("0 -1 0 0 0 0.2\n1 0 0 0 1e999 0.1\n", 2, "z", "got '1e999'");
    check_error("zero -1 0 0 0 0.2\n", 1, "id", "expected an integer node id, got 'zero'");
    check_error("0 -1 0 0 0 0.2\n1 0.5 0 0 1 0.1\n", 2, "parent", "got '0.5'");
  }
  SECTION("a missing field") {
    check_error("0 -1 0 0 0 0.2\n1 0 0 0 1\n", 2, "radius",
                "expected a value (6 fields: id parent x y z radius)");
    check_error("0 -1 0 0 0 0.2\n1 0 0 # 0 1 0.1\n", 2, "y", "got end of line");
  }
  SECTION("an extra field") {
    check_error("0 -1 0 0 0 0.2 7\n", 1, "radius", "expected end of line after the radius");
  }
  SECTION("a duplicate id") {
    check_error("0 -1 0 0 0 0.2\n1 0 0 0 1 0.1\n1 0 0 0 2 0.1\n", 3, "id", "already on line 2), got '1'");
  }
  SECTION("an id outside 0..n-1") {
    check_error("0 -1 0 0 0 0.2\n1 0 0 0 1 0.1\n5 1 0 0 2 0.1\n", 3, "id", "expected an id in 0..2");
    check_error("0 -1 0 0 0 0.2\n-1 0 0 0 1 0.1\n", 2, "id", "got '-1'");
  }
  SECTION("no nodes") {
    check_error("# nothing but a comment\n\n", 2, "id", "expected at least one node line");
  }
  SECTION("odd bytes are escaped") {
    check_error("0 -1 0 0 0 0.2\n1 0 0 \x01' 1 0.1\n", 2, "y", "got '\\x01\\x27'");
  }
}

TEST_CASE("TreeFile: unreadable or unwritable paths name the file", "[trees][treefile]") {
  TempDir dir("fw_treefile");
  const auto missing = dir.path() + "/missing.tree";
  const auto message = fw::test::source_error(read_tree_file, missing);
  CHECK(message.rfind(missing + ": cannot open", 0) == 0);

  const auto skeleton = Skeleton::from_nodes({{-1, {0, 0, 0}, 0.1}});
  const auto nowhere = dir.path() + "/no/such/dir/out.tree";
  CHECK_THROWS_AS(write_tree_file(skeleton, nowhere), std::runtime_error);
}
