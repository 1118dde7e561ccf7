#include "trees/LSystem.hpp"

#include <catch2/catch.hpp>

#include <cmath>
#include <cstdint>
#include <stdexcept>
#include <string>
#include <vector>

using fw::trees::BranchSegment;
using fw::trees::interpret;
using fw::trees::LSystem;
using fw::trees::Module;
using fw::trees::parse_word;
using fw::trees::to_string;
using fw::trees::TurtleSettings;

namespace {

// Geometry of the turtle is exact up to a few rounding errors of cos/sin.
constexpr double kGeometryTolerance = 1e-12;

bool near(const Eigen::Vector3d& a, const Eigen::Vector3d& b) {
  return (a - b).norm() < kGeometryTolerance;
}

std::vector<BranchSegment> draw(const std::string& word, const TurtleSettings& settings) {
  const std::vector<Module> modules = parse_word(word);
  return interpret(modules, settings);
}

TurtleSettings right_angles() {
  TurtleSettings settings;
  settings.angle_deg = 90.0;
  return settings;
}

}  // namespace

TEST_CASE("LSystem: deterministic rewriting gives the expected word", "[lsystem]") {
  // Lindenmayer's algae: the word lengths are the Fibonacci numbers.
  LSystem algae("A");
  algae.add_rule('A', "AB");
  algae.add_rule('B', "A");
  CHECK(to_string(algae.derive(0, 1)) == "A");
  CHECK(to_string(algae.derive(1, 1)) == "AB");
  CHECK(to_string(algae.derive(3, 1)) == "ABAAB");
  CHECK(to_string(algae.derive(5, 1)) == "ABAABABAABAAB");
}

TEST_CASE("LSystem: parametric successors scale the predecessor's parameter", "[lsystem]") {
  LSystem plant("A(2)");
  plant.add_rule('A', "F(p) [ +(30) A(p*0.5) ] A(0.5*p)");
  CHECK(to_string(plant.derive(1, 7)) == "F(2)[+(30)A(1)]A(1)");
  CHECK(to_string(plant.derive(2, 7)) == "F(2)[+(30)F(1)[+(30)A(0.5)]A(0.5)]F(1)[+(30)A(0.5)]A(0.5)");
  // Symbols without rules (F, +, brackets) are copied; a predecessor without a parameter gives p = 1.
  LSystem bare("XA");
  bare.add_rule('A', "F(p*3)");
  CHECK(to_string(bare.derive(1, 7)) == "XF(3)");
}

TEST_CASE("LSystem: jitter stays within its relative range and averages out", "[lsystem]") {
  LSystem growth("A");
  growth.add_rule('A', "F(10~0.2)A");
  const std::vector<Module> word = growth.derive(2000, 5);
  REQUIRE(word.size() == 2001);
  double sum = 0.0;
  for (std::size_t i = 0; i + 1 < word.size(); ++i) {
    REQUIRE(word[i].symbol == 'F');
    CHECK(word[i].parameter >= 8.0);  // 10 * (1 - 0.2)
    CHECK(word[i].parameter < 12.0);  // 10 * (1 + 0.2), exclusive
    sum += word[i].parameter;
  }
  // Uniform on [8, 12): standard deviation 4/sqrt(12) = 1.15, so the mean of 2000 has sd 0.026; 0.13 is 5 sd.
  CHECK(sum / 2000.0 == Approx(10.0).margin(0.13));
}

TEST_CASE("LSystem: stochastic alternatives are chosen in proportion to their weights", "[lsystem]") {
  LSystem coin(std::string(500, 'A'));
  coin.add_rule('A', "B", 1.0);
  coin.add_rule('A', "C", 3.0);
  coin.add_rule('A', "D", 0.5);
  int b = 0, c = 0, d = 0;
  for (std::uint64_t seed = 1; seed <= 40; ++seed) {
    for (const Module& m : coin.derive(1, seed)) {
      b += m.symbol == 'B';
      c += m.symbol == 'C';
      d += m.symbol == 'D';
    }
  }
  const double n = 500.0 * 40.0;
  REQUIRE(b + c + d == int(n));
  // Expected 1/4.5, 3/4.5, 0.5/4.5; binomial sd at n = 20000 is at most 0.0035, so 0.015 is over 4 sd.
  CHECK(b / n == Approx(1.0 / 4.5).margin(0.015));
  CHECK(c / n == Approx(3.0 / 4.5).margin(0.015));
  CHECK(d / n == Approx(0.5 / 4.5).margin(0.015));
}

TEST_CASE("LSystem: the same seed gives the same word and another seed a different one", "[lsystem]") {
  LSystem bush("A");
  bush.add_rule('A', "F(1~0.3)[+(30~0.5)A]A", 1.0);
  bush.add_rule('A', "F(1~0.3)A", 1.0);
  const auto first = bush.derive(8, 123);
  CHECK(bush.derive(8, 123) == first);
  CHECK_FALSE(bush.derive(8, 124) == first);
}

TEST_CASE("LSystem: unit_interval maps 64 random bits onto 0 <= u < 1", "[lsystem]") {
  CHECK(fw::trees::unit_interval(0) == 0.0);
  CHECK(fw::trees::unit_interval(~std::uint64_t(0)) == 1.0 - 0x1.0p-53);
  CHECK(fw::trees::unit_interval(std::uint64_t(1) << 63) == 0.5);
}

TEST_CASE("LSystem: malformed grammars are rejected", "[lsystem]") {
  CHECK_THROWS_AS(LSystem("F[+F"), std::invalid_argument);
  CHECK_THROWS_AS(LSystem("F]"), std::invalid_argument);
  CHECK_THROWS_AS(LSystem("A(p)"), std::invalid_argument);  // no predecessor in the axiom
  CHECK_THROWS_AS(LSystem("F(abc)"), std::invalid_argument);
  LSystem grammar("A");
  CHECK_THROWS_AS(grammar.add_rule('A', "F(1~1.0)"), std::invalid_argument);  // jitter must be < 1
  CHECK_THROWS_AS(grammar.add_rule('A', "F(p*)"), std::invalid_argument);
  CHECK_THROWS_AS(grammar.add_rule('A', "F(1", 1.0), std::invalid_argument);
  CHECK_THROWS_AS(grammar.add_rule('A', "F", 0.0), std::invalid_argument);
  CHECK_THROWS_AS(grammar.add_rule('A', "F", std::nan("")), std::invalid_argument);
  CHECK_THROWS_AS(grammar.add_rule('[', "F"), std::invalid_argument);
  CHECK_THROWS_AS(grammar.derive(-1, 1), std::invalid_argument);
  CHECK_THROWS_AS(parse_word("F(p)"), std::invalid_argument);
  try {
    grammar.add_rule('A', "F(x)");
    FAIL("expected an exception");
  } catch (const std::invalid_argument& e) {
    CHECK_THAT(e.what(), Catch::Matches("LSystem: .*x.*"));
  }
}

TEST_CASE("LSystem: the turtle draws F[+F]F with right angles as expected", "[lsystem]") {
  const auto segments = draw("F[+F]F", right_angles());
  REQUIRE(segments.size() == 3);
  // The turtle starts at the origin heading +z with left = -y: + turns the heading toward -y.
  CHECK(segments[0].id == 0);
  CHECK(segments[0].parent == -1);
  CHECK(segments[0].order == 0);
  CHECK(near(segments[0].start, {0, 0, 0}));
  CHECK(near(segments[0].end, {0, 0, 1}));
  CHECK(segments[1].parent == 0);
  CHECK(segments[1].order == 1);
  CHECK(near(segments[1].start, {0, 0, 1}));
  CHECK(near(segments[1].end, {0, -1, 1}));
  CHECK(segments[2].parent == 0);  // after ']' the turtle continues from the end of segment 0
  CHECK(segments[2].order == 0);
  CHECK(near(segments[2].start, {0, 0, 1}));
  CHECK(near(segments[2].end, {0, 0, 2}));
}

TEST_CASE("LSystem: pitch, roll and turn-around move the heading as documented", "[lsystem]") {
  const TurtleSettings settings = right_angles();
  CHECK(near(draw("&F", settings)[0].end, {-1, 0, 0}));          // toward -U = -x
  CHECK(near(draw("^F", settings)[0].end, {1, 0, 0}));           // toward +U
  CHECK(near(draw("\\(90)&F", settings)[0].end, {0, -1, 0}));    // roll left: U becomes +y
  CHECK(near(draw("/(90)&F", settings)[0].end, {0, 1, 0}));      // roll right: U becomes -y
  CHECK(near(draw("+(90)-(90)F", settings)[0].end, {0, 0, 1}));  // + and - cancel
  CHECK(near(draw("|F", settings)[0].end, {0, 0, -1}));          // no ground by default
  CHECK(near(draw("F(2.5)", settings)[0].end, {0, 0, 2.5}));     // the parameter is the length
  CHECK(near(draw("+(45)F(2)", settings)[0].end, {0, -std::sqrt(2.0), std::sqrt(2.0)}));
  CHECK(draw("F(0)", settings).empty());  // a zero-length F draws nothing
}

TEST_CASE("LSystem: $ levels the turtle so that a yaw stays horizontal", "[lsystem]") {
  const auto segments = draw("&(30)/(50)$+(90)F", TurtleSettings{});
  REQUIRE(segments.size() == 1);
  CHECK(std::abs(segments[0].end.z()) < kGeometryTolerance);
  CHECK(segments[0].length() == Approx(1.0).epsilon(1e-12));
}

TEST_CASE("LSystem: tropism bends branches toward its direction and never past it", "[lsystem]") {
  TurtleSettings settings;
  settings.tropism_direction = {0.0, 0.0, -1.0};
  std::string word = "&(90)T(0.3)";
  for (int i = 0; i < 60; ++i) word += "F";
  const auto segments = draw(word, settings);
  REQUIRE(segments.size() == 60);
  // The first F is bent by 0.3 rad (|H x T| = 1 for a horizontal heading) before it moves.
  const Eigen::Vector3d first = segments[0].end - segments[0].start;
  CHECK(first.z() == Approx(-std::sin(0.3)).epsilon(1e-12));
  double previous_z = 0.0;
  for (const BranchSegment& s : segments) {
    const Eigen::Vector3d d = s.end - s.start;
    CHECK(d.z() < previous_z + kGeometryTolerance);  // ever steeper
    CHECK(d.x() <= kGeometryTolerance);              // never swings past the vertical
    previous_z = d.z();
  }
  const Eigen::Vector3d last = segments.back().end - segments.back().start;
  CHECK(last.z() < -0.999);  // 60 steps hang it almost straight down
  // A branch along the tropism direction is not bent at all.
  CHECK(near(draw("|T(0.5)FF", settings)[1].end, {0, 0, -2}));
}

TEST_CASE("LSystem: a branch that would grow into the ground stops", "[lsystem]") {
  TurtleSettings settings;
  settings.ground_z = 0.0;
  const auto segments = draw("[&(120)F[+F]F]F", settings);
  REQUIRE(segments.size() == 1);  // the whole first bracket is dead after its first F
  CHECK(segments[0].parent == -1);
  CHECK(near(segments[0].end, {0, 0, 1}));
}

TEST_CASE("LSystem: the turtle rejects unbalanced words and bad parameters", "[lsystem]") {
  const std::vector<Module> unclosed = {{'['}, {'F'}};
  CHECK_THROWS_AS(interpret(unclosed), std::invalid_argument);
  const std::vector<Module> unopened = {{'F'}, {']'}};
  CHECK_THROWS_AS(interpret(unopened), std::invalid_argument);
  const std::vector<Module> infinite = {{'+', INFINITY}, {'F'}};
  CHECK_THROWS_AS(interpret(infinite), std::invalid_argument);
  TurtleSettings no_direction;
  no_direction.tropism_direction = Eigen::Vector3d::Zero();
  CHECK_THROWS_AS(interpret(parse_word("F"), no_direction), std::invalid_argument);
}
