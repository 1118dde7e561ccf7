#include "io/Expression.hpp"

#include <catch2/catch.hpp>

#include <atomic>
#include <cmath>
#include <numbers>
#include <stdexcept>
#include <string>
#include <thread>
#include <utility>
#include <vector>

using Catch::Matchers::Contains;
using fw::io::Expression;

namespace {

// The what() of the std::invalid_argument that parse(text) throws; fails the test when it does not throw.
std::string parse_error(const std::string& text) {
  INFO("expression: '" << text << "'");
  try {
    Expression::parse(text);
  } catch (const std::invalid_argument& error) {
    return error.what();
  }
  FAIL("parse accepted the text");
  return {};
}

}  // namespace

TEST_CASE("Expression: the default is the constant 0", "[expression]") {
  const Expression zero;
  CHECK(zero.is_constant());
  CHECK(zero.text() == "0");
  CHECK(zero(0.0) == 0.0);
  CHECK(zero(1e6) == 0.0);
}

TEST_CASE("Expression::constant: the value at every t, and a text that reads back as the same double",
          "[expression]") {
  for (const double value : {0.1, 1.0 / 3.0, -2.5e-7, 12.0, 6.02214076e23, -0.0}) {
    INFO("value " << value);
    const Expression expression = Expression::constant(value);
    CHECK(expression.is_constant());
    // Exact: a constant is returned as stored, whatever t.
    CHECK(expression(0.0) == value);
    CHECK(expression(-5.0) == value);
    CHECK(expression(1e9) == value);
    // Exact: the text is the shortest decimal that reads back as the same bits.
    CHECK(std::stod(expression.text()) == value);
    // ... and muparser reads it to the same value too.
    CHECK(Expression::parse(expression.text())(0.0) == value);
  }
  CHECK(Expression::constant(0.1).text() == "0.1");  // shortest, not 0.1000000000000000055511151231257827
}

TEST_CASE("Expression::parse: numbers and formulas of constants are constant and keep their text",
          "[expression]") {
  const Expression twelve = Expression::parse("12");
  CHECK(twelve.is_constant());
  CHECK(twelve.text() == "12");
  CHECK(twelve(0.0) == 12.0);
  CHECK(twelve(1000.0) == 12.0);

  // The text is kept as given, not reformatted.
  const Expression spaced = Expression::parse(" 2.50e1 ");
  CHECK(spaced.text() == " 2.50e1 ");
  CHECK(spaced(3.0) == 25.0);

  // Tolerance: one rounding in _pi and each operation, relative 1e-15.
  const Expression formula = Expression::parse("2*_pi + sqrt(16) - _e^0");
  CHECK(formula.is_constant());
  CHECK(formula(0.0) == Approx(2.0 * std::numbers::pi + 3.0).epsilon(1e-15));
  CHECK(formula(7.0) == formula(0.0));

  // Exact: _pi and _e are the nearest doubles to pi and e (muparser's own _pi stops at 3.141592653589).
  CHECK(Expression::parse("_pi")(0.0) == std::numbers::pi);
  CHECK(Expression::parse("_e")(0.0) == std::numbers::e);
  // Tolerance: sin near a multiple of pi is the rounding of pi, about 1.2e-16.
  CHECK(std::abs(Expression::parse("sin(_pi)")(0.0)) < 1e-15);

  // Operator precedence as muparser defines it: ^ binds right to left.
  CHECK(Expression::parse("2^3^2")(0.0) == 512.0);
  CHECK(Expression::parse("1 + 2*3 - 8/4")(0.0) == 5.0);
  CHECK(Expression::parse("(1 + 2)*3")(0.0) == 9.0);
}

TEST_CASE("Expression::parse: arithmetic of t at several times", "[expression]") {
  // The ramp of the header and of docs/design.md: 12 m/s until t = 20 s, then up to 22 m/s at t = 60 s.
  const Expression ramp = Expression::parse("12 + 10*min(1, max(0, (t-20)/40))");
  CHECK_FALSE(ramp.is_constant());
  CHECK(ramp.text() == "12 + 10*min(1, max(0, (t-20)/40))");
  // Exact: every intermediate value is a small binary fraction.
  CHECK(ramp(0.0) == 12.0);
  CHECK(ramp(20.0) == 12.0);
  CHECK(ramp(40.0) == 17.0);
  CHECK(ramp(50.0) == 19.5);
  CHECK(ramp(60.0) == 22.0);
  CHECK(ramp(600.0) == 22.0);

  const Expression quadratic = Expression::parse("3*t^2 - t/4 + 1");
  CHECK_FALSE(quadratic.is_constant());
  // Exact: binary fractions again.
  CHECK(quadratic(0.0) == 1.0);
  CHECK(quadratic(1.0) == 3.75);
  CHECK(quadratic(2.5) == 19.125);
  CHECK(quadratic(-2.0) == 13.5);

  // t read only inside a branch still makes the expression time-dependent.
  const Expression step = Expression::parse("t < 10 ? 4 : 8");
  CHECK_FALSE(step.is_constant());
  CHECK(step(9.5) == 4.0);
  CHECK(step(10.0) == 8.0);

  // Comparisons and && || give 1 or 0.
  const Expression window = Expression::parse("t >= 2 && t < 4 || t == 7");
  CHECK(window(1.0) == 0.0);
  CHECK(window(2.0) == 1.0);
  CHECK(window(3.9) == 1.0);
  CHECK(window(4.0) == 0.0);
  CHECK(window(7.0) == 1.0);

  // Deterministic: the same t gives the same bits, before and after other times.
  const Expression wobble = Expression::parse("250 + 20*sin(0.3*t) * exp(-t/90)");
  const double first = wobble(17.3);
  wobble(3.0);
  CHECK(wobble(17.3) == first);
}

TEST_CASE("Expression::parse: functions of t against hand-computed values", "[expression]") {
  const double pi = std::numbers::pi;
  struct Case {
    const char* text;
    double t;
    double expected;
  };
  const std::vector<Case> cases = {
      {"sin(t)", pi / 6.0, 0.5},
      {"sin(t)", pi / 2.0, 1.0},
      {"cos(2*t)", pi / 6.0, 0.5},
      {"cos(t)", pi, -1.0},
      {"tan(t)", pi / 4.0, 1.0},
      {"asin(t)", 0.5, pi / 6.0},
      {"acos(t)", 0.5, pi / 3.0},
      {"atan(t)", 1.0, pi / 4.0},
      {"atan2(t, 1)", 1.0, pi / 4.0},
      {"sinh(t)", std::log(2.0), 0.75},  // (2 - 1/2) / 2
      {"cosh(t)", std::log(2.0), 1.25},  // (2 + 1/2) / 2
      {"tanh(t)", std::log(2.0), 0.6},   // 0.75 / 1.25
      {"asinh(t)", 0.75, std::log(2.0)},
      {"acosh(t)", 1.25, std::log(2.0)},
      {"atanh(t)", 0.6, std::log(2.0)},
      {"log(t)", std::exp(3.0), 3.0},  // log is the natural logarithm
      {"ln(t)", std::exp(-2.0), -2.0},
      {"log2(t)", 0.125, -3.0},
      {"log10(t)", 1000.0, 3.0},
      {"exp(t)", std::log(2.0), 2.0},
      {"sqrt(t)", 2.25, 1.5},
      {"abs(t)", -4.0, 4.0},
      {"sign(t)", -0.3, -1.0},
      {"sign(t)", 0.3, 1.0},
      {"rint(t)", 2.6, 3.0},
      {"rint(t)", -2.6, -3.0},
      {"min(t, 3, 1.5)", 2.0, 1.5},
      {"max(t, 3, 1.5)", 4.0, 4.0},
      {"sum(t, 1, 2)", 6.0, 9.0},
      {"avg(t, 2, 4)", 6.0, 4.0},
      {"_pi*t", 2.0, 2.0 * pi},
      {"_e^t", 1.0, std::exp(1.0)},
  };
  for (const Case& c : cases) {
    INFO(c.text << " at t = " << c.t);
    const Expression expression = Expression::parse(c.text);
    CHECK_FALSE(expression.is_constant());
    // Tolerance: the libm functions and the argument t are within a few ulp; 1e-14 absolute near 0.
    CHECK(expression(c.t) == Approx(c.expected).epsilon(1e-13).margin(1e-14));
  }
}

TEST_CASE("Expression::parse: a syntax error throws invalid_argument naming the text and where",
          "[expression]") {
  const std::string unclosed = parse_error("5 + (t");
  CHECK_THAT(unclosed, Contains("expression \"5 + (t\"") && Contains("parenthesis") && Contains("position"));

  const std::string cut = parse_error("sin(");
  CHECK_THAT(cut, Contains("expression \"sin(\"") && Contains("end of expression") && Contains("position"));

  const std::string doubled = parse_error("3 +* t");
  CHECK_THAT(doubled, Contains("expression \"3 +* t\"") && Contains("position"));

  const std::string dangling = parse_error("t 2");
  CHECK_THAT(dangling, Contains("expression \"t 2\"") && Contains("position"));
}

TEST_CASE("Expression::parse: a variable other than t is rejected by name", "[expression]") {
  const std::string x = parse_error("x + 1");
  CHECK_THAT(x, Contains("expression \"x + 1\"") && Contains("position 0") &&
                    Contains("unknown variable or function \"x\"") && Contains("the only variable is t"));

  // The position is the 0-based character offset of the unknown name.
  const std::string y = parse_error("2*t + y");
  CHECK_THAT(y, Contains("position 6") && Contains("\"y\""));

  // Names are case sensitive: T is not t.
  CHECK_THAT(parse_error("T*2"), Contains("unknown variable or function \"T\""));
  CHECK_THAT(parse_error("time/2"), Contains("unknown variable or function \"time\""));
  // An unknown function is refused the same way.
  CHECK_THAT(parse_error("gust(t)"), Contains("unknown variable or function \"gust\""));
}

TEST_CASE("Expression::parse: an empty text and a comma list are rejected", "[expression]") {
  CHECK_THAT(parse_error(""), Contains("expression \"\"") && Contains("empty"));
  CHECK_THAT(parse_error("1, 2"),
             Contains("expression \"1, 2\"") && Contains("one value expected, got a list of 2"));
  CHECK_THAT(parse_error("t, 2*t, 3"), Contains("one value expected, got a list of 3"));
  // A comma inside a function's arguments is not a list.
  CHECK(Expression::parse("max(1, 2)")(0.0) == 2.0);
}

TEST_CASE("Expression: inf and NaN come through where the formula gives them", "[expression]") {
  const Expression root = Expression::parse("sqrt(-1)");  // parses: the value is the formula's business
  CHECK(root.is_constant());
  CHECK(std::isnan(root(0.0)));

  const Expression inverse = Expression::parse("1/t");
  CHECK_FALSE(inverse.is_constant());
  CHECK(std::isinf(inverse(0.0)));
  CHECK(inverse(4.0) == 0.25);
  CHECK(std::isnan(Expression::parse("log(t)")(-1.0)));
}

TEST_CASE("Expression: copies and moves each evaluate their own formula with their own t", "[expression]") {
  Expression original = Expression::parse("2*t + 1");
  Expression copy(original);
  CHECK_FALSE(copy.is_constant());
  CHECK(copy.text() == "2*t + 1");
  // Interleaved: neither reads the other's t.
  CHECK(original(1.0) == 3.0);
  CHECK(copy(10.0) == 21.0);
  CHECK(original(2.0) == 5.0);
  CHECK(copy(-1.0) == -1.0);

  // Copy assignment replaces the formula; the source stays usable.
  Expression assigned = Expression::parse("t*t");
  assigned = original;
  CHECK(assigned.text() == "2*t + 1");
  CHECK(assigned(3.0) == 7.0);
  CHECK(original(4.0) == 9.0);
  const Expression& same = assigned;
  assigned = same;  // self-assignment keeps it
  CHECK(assigned(5.0) == 11.0);

  // A constant assigned over a formula is constant afterwards.
  assigned = Expression::constant(4.5);
  CHECK(assigned.is_constant());
  CHECK(assigned(100.0) == 4.5);

  // Moving keeps the parser's binding to t valid in the new owner.
  Expression moved(std::move(copy));
  CHECK(moved(6.0) == 13.0);
  Expression target;
  target = std::move(moved);
  CHECK(target(0.5) == 2.0);
  CHECK(target.text() == "2*t + 1");

  // Copies inside a growing vector (moved on reallocation) still evaluate correctly.
  std::vector<Expression> many;
  for (int i = 0; i < 20; ++i) many.push_back(Expression::parse("t + " + std::to_string(i)));
  for (int i = 0; i < 20; ++i) CHECK(many[std::size_t(i)](100.0) == 100.0 + i);
}

TEST_CASE("Expression: concurrent calls on one expression each get the value of their own t",
          "[expression]") {
  const Expression expression = Expression::parse("1000*t + 0.5");
  std::atomic<int> wrong{0};
  std::vector<std::thread> threads;
  for (int thread = 0; thread < 4; ++thread) {
    threads.emplace_back([&, thread] {
      for (int i = 0; i < 5000; ++i) {
        const double t = thread * 10000 + i;
        // Exact: integers and a half, well below 2^53.
        if (expression(t) != 1000.0 * t + 0.5) ++wrong;
      }
    });
  }
  for (std::thread& thread : threads) thread.join();
  CHECK(wrong.load() == 0);
}
