#include "trees/QsmImport.hpp"

#include <catch2/catch.hpp>

#include "tests/support/SourceErrors.hpp"
#include "tests/support/TempDir.hpp"

#include <cmath>
#include <stdexcept>
#include <string>

using fw::test::TempDir;
using fw::trees::QsmImportInfo;
using fw::trees::read_qsm_cylinders;

namespace {

void check_error(const std::string& content, int line, const std::string& column, const std::string& detail) {
  const auto read = [](const std::string& path) { return read_qsm_cylinders(path); };
  fw::test::check_source_error(read, "cyl.txt", content, line, column, detail);
}

bool near(const Eigen::Vector3d& a, const Eigen::Vector3d& b) {
  return (a - b).norm() < 1e-12;
}

// A stem of two cylinders and one branch from the first stem cylinder's end, with three ignored columns.
const char* kThreeCylinders =
    "radius length start_x start_y start_z axis_x axis_y axis_z parent extension added UnmodRadius\n"
    "0.15 2.0 1 2 0  0 0 1  0 2 0 0.15\n"
    "0.10 1.5 1 2 2  0 0 2  1 0 0 0.10\n"  // the axis need not be a unit vector
    "0.05 1.0 1 2 2  3 0 4  1 0 1 0.05\n";

}  // namespace

TEST_CASE("QsmImport: three cylinders give four nodes", "[trees][qsm]") {
  TempDir dir("fw_qsm");
  QsmImportInfo info;
  const auto skeleton = read_qsm_cylinders(dir.write("cyl.txt", kThreeCylinders), &info);
  REQUIRE(skeleton.size() == 4);
  CHECK(skeleton.root() == 0);
  CHECK(skeleton.node(0).parent == -1);
  CHECK(skeleton.node(1).parent == 0);
  CHECK(skeleton.node(2).parent == 1);
  CHECK(skeleton.node(3).parent == 1);
  CHECK(near(skeleton.node(0).position, {1, 2, 0}));
  CHECK(near(skeleton.node(1).position, {1, 2, 2}));
  CHECK(near(skeleton.node(2).position, {1, 2, 3.5}));
  CHECK(near(skeleton.node(3).position, {1.6, 2, 2.8}));  // 1.0 m along (3, 0, 4) / 5
  CHECK(skeleton.node(0).radius == 0.15);
  CHECK(skeleton.node(1).radius == 0.15);
  CHECK(skeleton.node(2).radius == 0.10);
  CHECK(skeleton.node(3).radius == 0.05);
  CHECK(info.cylinders == 3);
  CHECK(info.gaps == 0);
}

TEST_CASE("QsmImport: comma-separated rows without a header", "[trees][qsm]") {
  TempDir dir("fw_qsm");
  const auto skeleton = read_qsm_cylinders(dir.write("cyl.csv",
                                                     "0.15, 2.0, 1, 2, 0, 0, 0, 1, 0, 7\r\n"
                                                     "0.10, 1.5, 1, 2, 2, 0, 0, 1, 1.0,\r\n"));
  REQUIRE(skeleton.size() == 3);
  CHECK(skeleton.node(2).parent == 1);
  CHECK(near(skeleton.node(2).position, {1, 2, 3.5}));
}

TEST_CASE("QsmImport: the base cylinder need not be the first row", "[trees][qsm]") {
  TempDir dir("fw_qsm");
  const auto skeleton = read_qsm_cylinders(dir.write("cyl.txt",
                                                     "0.10 1.5 0 0 2 0 0 1 2\n"
                                                     "0.15 2.0 0 0 0 0 0 1 0\n"));
  REQUIRE(skeleton.size() == 3);
  CHECK(skeleton.node(1).parent == 2);
  CHECK(skeleton.node(2).parent == 0);
  CHECK(near(skeleton.node(0).position, {0, 0, 0}));
  CHECK(skeleton.node(0).radius == 0.10);  // the first row's radius
}

TEST_CASE("QsmImport: a gap between a cylinder and its parent is attached, not an error", "[trees][qsm]") {
  TempDir dir("fw_qsm");
  QsmImportInfo info;
  const auto skeleton =
      read_qsm_cylinders(dir.write("cyl.txt",
                                   "0.15 2.0 0 0 0 0 0 1 0\n"
                                   "0.10 1.0 0 0 2.05 0 0 1 1\n"   // 5 cm: within 10 cm + 1 mm
                                   "0.05 1.0 0.5 0 2 1 0 0 1\n"),  // 50 cm: a gap
                         &info);
  REQUIRE(skeleton.size() == 4);
  CHECK(skeleton.node(3).parent == 1);
  CHECK(near(skeleton.node(3).position, {1.5, 0, 2}));
  CHECK(info.gaps == 1);
  CHECK(info.largest_gap == Approx(0.5));
  CHECK(info.largest_gap_line == 3);
}

TEST_CASE("QsmImport: malformed tables name the line and the column", "[trees][qsm]") {
  SECTION("a bad number") {
    check_error("0.15 2.0 0 0 0 0 0 1 0\n0.10 1.5 0 0 2 0 zero 1 1\n", 2, "axis y",
                "expected a finite number, got 'zero'");
  }
  SECTION("a non-numeric row after the first is not a header") {
    check_error("radius length ...\nfoo 2.0 0 0 0 0 0 1 0\n", 2, "radius", "got 'foo'");
  }
  SECTION("too few columns") {
    check_error("0.15 2.0 0 0 0 0 0 1 0\n0.10 1.5 0 0 2 0 0 1\n", 2, "parent", "at least 9 columns");
    check_error("0.15,2.0,0,0,0,,0,1,0\n", 1, "axis x", "got ''");
  }
  SECTION("a parent out of range") {
    check_error("0.15 2.0 0 0 0 0 0 1 0\n0.10 1.5 0 0 2 0 0 1 3\n", 2, "parent",
                "in 1..2, or 0 for none, got '3'");
    check_error("0.15 2.0 0 0 0 0 0 1 0\n0.10 1.5 0 0 2 0 0 1 -1\n", 2, "parent", "got '-1'");
    check_error("0.15 2.0 0 0 0 0 0 1 0\n0.10 1.5 0 0 2 0 0 1 1.5\n", 2, "parent", "got '1.5'");
  }
  SECTION("two or no parentless cylinders") {
    check_error("0.15 2.0 0 0 0 0 0 1 0\n0.10 1.5 5 0 0 0 0 1 0\n", 2, "parent",
                "cylinder 1 on line 1 already");
    check_error("h\n0.15 2.0 0 0 0 0 0 1 2\n0.10 1.5 0 0 2 0 0 1 1\n", 2, "parent", "found none");
  }
  SECTION("a cycle of parents") {
    check_error(
        "0.15 2.0 0 0 0 0 0 1 0\n"
        "0.10 1.5 0 0 2 0 0 1 3\n"
        "0.10 1.5 0 0 3 0 0 1 2\n",
        2, "parent", "2 -> 3 -> 2");
  }
  SECTION("a cylinder that is its own parent") {
    check_error("0.15 2.0 0 0 0 0 0 1 0\n0.10 1.5 0 0 2 0 0 1 2\n", 2, "parent",
                "other than the node itself");
  }
  SECTION("a non-positive radius or length") {
    check_error("0.15 2.0 0 0 0 0 0 1 0\n-0.1 1.5 0 0 2 0 0 1 1\n", 2, "radius", "got '-0.1'");
    check_error("0 2.0 0 0 0 0 0 1 0\n", 1, "radius", "expected a positive radius");
    check_error("0.15 0 0 0 0 0 0 1 0\n", 1, "length", "expected a positive length in metres, got '0'");
  }
  SECTION("a zero axis") {
    check_error("0.15 2.0 0 0 0 0 0 0 0\n", 1, "axis x y z",
                "expected a non-zero axis direction, got '0 0 0'");
  }
  SECTION("an end point on its parent's end") {
    check_error("0.15 2.0 0 0 0 0 0 1 0\n0.10 1.0 0 0 1 0 0 1 1\n", 2, "length", "zero-length element");
  }
  SECTION("no rows") {
    check_error("radius length\n", 1, "radius", "expected at least one cylinder row");
  }
}
