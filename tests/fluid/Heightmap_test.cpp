#include "fluid/Heightmap.hpp"

#include <fmt/format.h>
#include <catch2/catch.hpp>

#include "tests/support/TempDir.hpp"

#include <cstdint>
#include <filesystem>
#include <fstream>
#include <limits>
#include <random>
#include <stdexcept>
#include <string>
#include <string_view>
#include <vector>

using fw::fluid::Heightmap;

namespace {

using fw::test::TempDir;

std::string bytes(std::initializer_list<int> values) {
  std::string out;
  for (int v : values) out += static_cast<char>(v);
  return out;
}

// The message of the std::runtime_error that reading the file throws, or "" when it reads fine.
std::string read_error(const std::string& path) {
  try {
    Heightmap::read(path, 2.0, 8.0);
  } catch (const std::runtime_error& e) {
    return e.what();
  }
  return "";
}

// A 3 x 2 image, north row first: heights 0, 4, 8 m along the north edge, flat 0 along the south.
constexpr std::string_view kP2 =
    "P2\n"
    "# north row first\n"
    "3 2\n"
    "10\n"
    "0 5 10\n"
    "0 0 0\n";

void check_p2_heights(const Heightmap& map) {
  REQUIRE(map.columns() == 3);
  REQUIRE(map.rows() == 2);
  CHECK(map.cell_size() == 2.0);
  CHECK(map.sw_centre()[0] == 1.0);
  CHECK(map.sw_centre()[1] == 1.0);
  // Row 0 is south.
  CHECK(map.sample(0, 0) == 0.0);
  CHECK(map.sample(2, 0) == 0.0);
  CHECK(map.sample(1, 1) == Approx(4.0));
  CHECK(map.sample(2, 1) == Approx(8.0));
  CHECK(map.max_height() == Approx(8.0));
  // Pixel centres at x = 1, 3, 5 and y = 1 (south), 3 (north).
  CHECK(map.height_at(5.0, 3.0) == Approx(8.0));
  CHECK(map.height_at(4.0, 3.0) == Approx(6.0));
  CHECK(map.height_at(4.0, 2.0) == Approx(3.0));
  CHECK(map.height_at(5.0, 1.0) == Approx(0.0));
}

}  // namespace

TEST_CASE("Heightmap: bilinear interpolation gives the mean of the four samples at their midpoint") {
  // 2 x 2 samples 4 m apart, south-west centre at (12, 22); rows south to north.
  const Heightmap map(2, 2, 4.0, {12.0, 22.0}, {1.0, 5.0, 3.0, 0.0});
  CHECK(map.height_at(14.0, 24.0) == Approx((1.0 + 5.0 + 3.0 + 0.0) / 4.0));
  CHECK(map.height_at(12.0, 22.0) == Approx(1.0));
  CHECK(map.height_at(14.0, 22.0) == Approx(3.0));  // midway along the south edge
  CHECK(map.height_at(13.0, 22.0) == Approx(2.0));  // a quarter of the way
  CHECK(map.height_at(16.0, 24.0) == Approx(2.5));  // midway along the east edge
}

TEST_CASE("Heightmap: outside the sample centres the nearest edge value holds") {
  const Heightmap map(2, 2, 4.0, {12.0, 22.0}, {1.0, 5.0, 3.0, 0.0});
  CHECK(map.height_at(0.0, 0.0) == Approx(1.0));
  CHECK(map.height_at(100.0, 22.0) == Approx(5.0));
  CHECK(map.height_at(100.0, 100.0) == Approx(0.0));
  CHECK(map.height_at(12.0, 100.0) == Approx(3.0));
  CHECK(map.height_at(-1e300, 24.0) == Approx(2.0));  // midway between 1 (south) and 3 (north)
}

TEST_CASE("Heightmap: a single sample is flat everywhere") {
  const Heightmap map(1, 1, 1.0, {0.5, 0.5}, {7.0});
  CHECK(map.height_at(-3.0, 40.0) == 7.0);
  CHECK(map.height_at(0.5, 0.5) == 7.0);
}

TEST_CASE("Heightmap: the in-memory constructor rejects inconsistent samples") {
  CHECK_THROWS_AS(Heightmap(2, 2, 1.0, {0, 0}, {1.0, 2.0, 3.0}), std::invalid_argument);
  CHECK_THROWS_AS(Heightmap(0, 2, 1.0, {0, 0}, {}), std::invalid_argument);
  CHECK_THROWS_AS(Heightmap(1, 1, 0.0, {0, 0}, {1.0}), std::invalid_argument);
  CHECK_THROWS_AS(Heightmap(1, 1, 1.0, {0, 0}, {std::numeric_limits<double>::infinity()}),
                  std::invalid_argument);
}

TEST_CASE("Heightmap: a P2 PGM maps pixel values to heights with the first row at the north edge") {
  TempDir dir;
  check_p2_heights(Heightmap::read(dir.write("hills.pgm", kP2), 2.0, 8.0));
}

TEST_CASE("Heightmap: P5 PGMs, 8-bit and 16-bit big-endian, read the same heights as the P2 file") {
  TempDir dir;
  SECTION("8-bit") {
    const std::string data = "P5\n3 2\n10\n" + bytes({0, 5, 10, 0, 0, 0});
    check_p2_heights(Heightmap::read(dir.write("hills8.pgm", data), 2.0, 8.0));
  }
  SECTION("16-bit, with a header comment") {
    // 500 = 0x01F4, 1000 = 0x03E8 of maxval 1000.
    const std::string data =
        "P5 # 16 bit\n3 2 1000\n" + bytes({0, 0, 0x01, 0xF4, 0x03, 0xE8, 0, 0, 0, 0, 0, 0});
    check_p2_heights(Heightmap::read(dir.write("hills16.pgm", data), 2.0, 8.0));
  }
}

TEST_CASE("Heightmap: the format comes from the content, not the extension") {
  TempDir dir;
  check_p2_heights(Heightmap::read(dir.write("looks_like.asc", kP2), 2.0, 8.0));
  // An ESRI grid is GDAL's to read (terrain.raster, tests/io/gis/GeoRaster_test.cpp): refused here, pointing
  // there, whatever its extension.
  const std::string message =
      read_error(dir.write("looks_like.pgm", "ncols 1\nnrows 1\nxllcorner 0\nyllcorner 0\ncellsize 3\n42\n"));
  CHECK_THAT(message, Catch::Contains("looks_like.pgm:1: ") && Catch::Contains("terrain.raster"));
}

TEST_CASE("Heightmap: each malformed PGM gives an error naming the file and the line") {
  struct Case {
    const char* name;
    const char* content;
    int line;              // 1-based line the message must name
    const char* expected;  // a part of the message
  };
  const std::vector<Case> cases{
      {"big_maxval.pgm", "P2\n# made by hand\n2 2\n70000\n1 2\n3 4\n", 4,
       "maxval: expected an integer in 1..65535"},
      {"zero_maxval.pgm", "P2\n2 2\n0\n0 0\n0 0\n", 3, "maxval"},
      {"bad_width.pgm", "P2\n-2 2\n255\n", 2, "width: expected a positive integer, got '-2'"},
      {"header_ends.pgm", "P2\n2 2\n", 2, "maxval: expected an integer in 1..65535, got end of file"},
      {"pixel_too_big.pgm", "P2\n2 2\n255\n1 2\n3 256\n", 5,
       "pixel value: expected an integer in 0..255, got '256'"},
      {"pixel_not_a_number.pgm", "P2\n2 2\n255\n# comment\n1 2\n3 4.5\n", 6, "pixel value"},
      {"short.pgm", "P2\n2 2\n255\n1 2\n3\n", 5, "truncated data"},
      {"long.pgm", "P2\n2 2\n255\n1 2\n3 4\n\n5\n", 7, "wrong number of values"},
      {"unknown.txt", "hello world\n", 1, "terrain.raster), got 'hello'"},
      {"colour.ppm", "\nP6\n2 2\n255\n", 2, "terrain.raster), got 'P6'"},
      {"empty.pgm", "", 1, "expected a PGM image (P2/P5"},
  };
  TempDir dir;
  for (const Case& c : cases) {
    const std::string message = read_error(dir.write(c.name, c.content));
    INFO(c.name << ": " << message);
    CHECK_THAT(message, Catch::Contains(fmt::format("{}:{}: ", c.name, c.line)));
    CHECK_THAT(message, Catch::Contains(c.expected));
  }
}

TEST_CASE("Heightmap: malformed P5 pixel data gives an error naming the file and the binary data") {
  struct Case {
    const char* name;
    std::string content;
    const char* expected;
  };
  const std::vector<Case> cases{
      {"short8.pgm", "P5\n2 2\n255\n" + bytes({1, 2, 3}), "truncated"},
      {"short16.pgm", "P5\n2 2\n1000\n" + bytes({0, 1, 0, 2, 0, 3, 0}), "truncated"},
      {"long8.pgm", "P5\n2 2\n255\n" + bytes({1, 2, 3, 4, 5}), "wrong number of values"},
      {"too_big.pgm", "P5\n2 2\n100\n" + bytes({1, 2, 200, 4}), "expected a value in 0..100, got 200"},
  };
  TempDir dir;
  for (const Case& c : cases) {
    const std::string message = read_error(dir.write(c.name, c.content));
    INFO(c.name << ": " << message);
    CHECK_THAT(message, Catch::Contains(fmt::format("{}: binary data: ", c.name)));
    CHECK_THAT(message, Catch::Contains(c.expected));
  }
}

TEST_CASE("Heightmap: a missing file or a bad PGM scale gives an error naming the file") {
  TempDir dir;
  CHECK_THAT(read_error(dir.write("gone.pgm", "") + ".missing"),
             Catch::Contains("gone.pgm.missing: cannot open"));
  const std::string path = dir.write("hills.pgm", kP2);
  CHECK_THROWS_WITH(Heightmap::read(path, 0.0, 8.0), Catch::Contains("hills.pgm: cell_size"));
  CHECK_THROWS_WITH(Heightmap::read(path, 2.0, -1.0), Catch::Contains("hills.pgm: max_height"));
}

TEST_CASE("Heightmap: a header that promises more samples than the file holds is refused as truncated") {
  // 16384 x 16384 samples (2 GiB of heights) promised by files of a few bytes: found by the heightmap fuzz
  // target (tests/fuzz), which timed out while the reader filled the heights before reading the data.
  TempDir dir;
  for (const auto& [name, content] :
       {std::pair<const char*, std::string>{"p2.pgm", "P2\n16384 16384\n255\n1 2 3\n"},
        {"p5.pgm", "P5\n16384 16384\n255\n" + bytes({1, 2, 3})}}) {
    const std::string message = read_error(dir.write(name, content));
    INFO(message);
    CHECK_THAT(message, Catch::Contains(name) && Catch::Contains("truncated data"));
  }
}
