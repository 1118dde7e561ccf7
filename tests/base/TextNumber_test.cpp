#include "base/TextNumber.hpp"

#include <catch2/catch.hpp>

#include <cmath>
#include <cstdint>
#include <limits>

using fw::base::parse_finite;
using fw::base::parse_number;

TEST_CASE("TextNumber: the whole text is the number, a leading plus allowed", "[base]") {
  CHECK(parse_number<double>("2.5") == 2.5);
  CHECK(parse_number<double>("+2.5") == 2.5);
  CHECK(parse_number<double>("-1e-3") == -1e-3);
  CHECK(parse_number<int>("+42") == 42);
  CHECK(parse_number<long long>("-7") == -7);
  CHECK(parse_number<std::uint64_t>("18446744073709551615") == std::numeric_limits<std::uint64_t>::max());
}

TEST_CASE("TextNumber: anything around the number, a second sign or another form is refused", "[base]") {
  for (const char* text : {"", "+", "-", "+-3", "++3", "-+3", " 3", "3 ", "3m", "0x3", "1,5", "3.0.1"}) {
    INFO("'" << text << "'");
    CHECK_FALSE(parse_number<double>(text));
    CHECK_FALSE(parse_number<long long>(text));
  }
  CHECK_FALSE(parse_number<int>("3.0"));  // a whole number has no point
  CHECK_FALSE(parse_number<std::uint64_t>("-1"));
}

TEST_CASE("TextNumber: a value past the type's range is refused, and parse_finite refuses inf and nan",
          "[base]") {
  CHECK_FALSE(parse_number<int>("2147483648"));
  CHECK_FALSE(parse_number<double>("1e400"));
  CHECK(std::isinf(*parse_number<double>("inf")));
  CHECK(std::isnan(*parse_number<double>("nan")));
  for (const char* text : {"inf", "-inf", "+inf", "nan", "1e400"}) {
    INFO(text);
    CHECK_FALSE(parse_finite(text));
  }
  CHECK(parse_finite("+1e300") == 1e300);
}
