// Fuzz target: muparser expressions on their own (io::Expression, the numbers-or-formulas of a scenario).
// Feeds: the bytes as the expression's text, then evaluates it at a few times, through a copy too.
// Checks: a constant expression (is_constant()) gives the same bits at every time, and a copy gives the
// same bits as the original.
// Clean refusals: std::invalid_argument from parse() (muparser's message and position; the scenario loader
// adds FILE:LINE: KEY in front). Bugs: anything else: a crash, a sanitizer report, another exception
// (muparser's own ParserError escaping, length_error, bad_alloc), a hang.
#include <bit>
#include <cstdint>
#include <string>

#include "io/Expression.hpp"
#include "tests/fuzz/FuzzSupport.hpp"

namespace {

// Times a scenario evaluates at: the start, a fraction, an hour, a negative time (spin-up), a large one.
constexpr double kTimes[] = {0.0, 0.5, 3600.0, -20.0, 1.0e9};

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  const std::string text(reinterpret_cast<const char*>(data), size);
  try {
    const fw::io::Expression expression = fw::io::Expression::parse(text);
    const fw::io::Expression copy = expression;
    const auto at_start = std::bit_cast<std::uint64_t>(expression(0.0));
    for (double t : kTimes) {
      const auto bits = std::bit_cast<std::uint64_t>(expression(t));
      if (expression.is_constant() && bits != at_start)
        fw::fuzz::fail("a constant expression changed: " + text);
      if (std::bit_cast<std::uint64_t>(copy(t)) != bits) fw::fuzz::fail("a copy differs: " + text);
    }
  } catch (const std::invalid_argument&) {
    // parse() refused the text, saying why.
  }
  return 0;
}
