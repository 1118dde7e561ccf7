#include <catch2/catch.hpp>

#include <cmath>

#include "viz/ColourMap.hpp"

using fw::viz::ColourMap;
using fw::viz::Rgb;

namespace {

// Relative luminance (linear sRGB, Rec. 709 weights): what "getting lighter" means for a sequential map.
double luminance(const Rgb& c) {
  auto lin = [](double v) { return v <= 0.04045 ? v / 12.92 : std::pow((v + 0.055) / 1.055, 2.4); };
  return 0.2126 * lin(c.r) + 0.7152 * lin(c.g) + 0.0722 * lin(c.b);
}

}  // namespace

TEST_CASE("ColourMap: the ends are the first and last control colours", "[viz]") {
  const ColourMap map("two", {{0.0, {0.1, 0.2, 0.3}}, {1.0, {0.9, 0.8, 0.7}}}, {0.5, 0.5, 0.5});
  // Lab round trip in double: 1e-9 is far below an 8-bit step (1/255).
  CHECK(map.colour(0.0).r == Approx(0.1).margin(1e-9));
  CHECK(map.colour(0.0).b == Approx(0.3).margin(1e-9));
  CHECK(map.colour(1.0).g == Approx(0.8).margin(1e-9));
  CHECK(map.colour(-3.0).r == Approx(0.1).margin(1e-9));  // clamped below
  CHECK(map.colour(7.0).r == Approx(0.9).margin(1e-9));   // and above
  CHECK(map.colour(std::nan("")).r == 0.5);               // missing
  CHECK(map.colour(5.0, 0.0, 10.0).r == Approx(map.colour(0.5).r).margin(1e-12));
}

TEST_CASE("ColourMap: the sequential maps get lighter all the way up", "[viz]") {
  for (const char* name : {"wind", "displacement"}) {
    const ColourMap& map = ColourMap::named(name);
    double previous = -1.0;
    for (int n = 0; n <= 100; ++n) {
      const double y = luminance(map.colour(n / 100.0));
      INFO(name << " at " << n / 100.0);
      CHECK(y > previous);
      previous = y;
    }
  }
}

TEST_CASE("ColourMap: the diverging map is symmetric in lightness about its middle", "[viz]") {
  const ColourMap& map = ColourMap::named("diverging");
  // Moreland's end points are matched in lightness to within about 1% of luminance.
  for (double t : {0.0, 0.2, 0.4})
    CHECK(luminance(map.colour(t)) == Approx(luminance(map.colour(1 - t))).epsilon(0.05));
  CHECK(luminance(map.colour(0.5)) > luminance(map.colour(0.1)));
}

TEST_CASE("ColourMap: the utilisation map darkens in greys up to 1 and turns red from 1 on", "[viz]") {
  const ColourMap& map = ColourMap::named("utilisation");
  auto at = [&](double u) { return map.colour(u, 0.0, fw::viz::kUtilisationTop); };
  double previous = 2.0;
  for (int n = 0; n < 100; ++n) {  // 0 .. 0.99: greys, each darker
    const Rgb c = at(n / 100.0);
    INFO("utilisation " << n / 100.0);
    CHECK(std::abs(c.r - c.b) < 0.02);
    CHECK(std::abs(c.g - c.b) < 0.02);
    CHECK(luminance(c) < previous);
    previous = luminance(c);
  }
  previous = 2.0;
  for (int n = 100; n <= 150; ++n) {  // 1 .. 1.5: reds, each darker
    const Rgb c = at(n / 100.0);
    INFO("utilisation " << n / 100.0);
    CHECK(c.r - c.b > 0.25);
    CHECK(c.r - c.g > 0.4);
    CHECK(luminance(c) < previous);
    previous = luminance(c);
  }
  CHECK(at(1.0).r - at(0.999).r > 0.4);  // the step at failure
}

TEST_CASE("ColourMap: bad maps and names are refused with the class name", "[viz]") {
  CHECK_THROWS_WITH(ColourMap("x", {{0.0, {0, 0, 0}}}, {}), Catch::Contains("ColourMap: x"));
  CHECK_THROWS_WITH(ColourMap("x", {{0.0, {0, 0, 0}}, {0.5, {1, 1, 1}}}, {}), Catch::Contains("0 to 1"));
  CHECK_THROWS_WITH(ColourMap("x", {{0.0, {0, 0, 2}}, {1.0, {1, 1, 1}}}, {}),
                    Catch::Contains("outside 0..1"));
  CHECK_THROWS_WITH(ColourMap::named("jet"), Catch::Contains("wind, displacement, diverging"));
}
