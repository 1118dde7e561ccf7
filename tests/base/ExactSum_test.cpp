// base/ExactSum: the sum is exact, and the same bits for any order of the terms and any split of them.
#include "base/ExactSum.hpp"

#include <catch2/catch.hpp>

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <limits>
#include <random>
#include <vector>

namespace {

// Floats over 60 decades, both signs: the spread of a residual's squares across a solve and then some.
std::vector<float> wide_range_values(std::size_t count, std::uint32_t seed) {
  std::mt19937 rng(seed);
  std::uniform_real_distribution<float> exponent(-30.0f, 30.0f), mantissa(-1.0f, 1.0f);
  std::vector<float> values(count);
  for (auto& v : values) v = mantissa(rng) * std::pow(10.0f, exponent(rng));
  return values;
}

double sum_of(const std::vector<float>& values) {
  fw::base::ExactSum sum;
  sum.add(values);
  return sum.value();
}

}  // namespace

TEST_CASE("ExactSum: any order of the terms gives the same bits", "[base]") {
  auto values = wide_range_values(20000, 7);
  const double first = sum_of(values);
  std::mt19937 rng(11);
  for (int trial = 0; trial < 5; ++trial) {
    std::shuffle(values.begin(), values.end(), rng);
    CHECK(sum_of(values) == first);  // bitwise: == on doubles that are not NaN
  }
  std::reverse(values.begin(), values.end());
  CHECK(sum_of(values) == first);
}

TEST_CASE("ExactSum: sums of parts merged with += equal the sum of the whole", "[base]") {
  const auto values = wide_range_values(10000, 3);
  const double whole = sum_of(values);
  for (std::size_t parts : {2u, 3u, 7u, 64u}) {
    fw::base::ExactSum merged;
    const std::size_t per = (values.size() + parts - 1) / parts;
    for (std::size_t p = 0; p < parts; ++p) {
      fw::base::ExactSum part;
      for (std::size_t i = p * per; i < std::min(values.size(), (p + 1) * per); ++i) part.add(values[i]);
      merged += part;
    }
    CHECK(merged.value() == whole);
  }
}

TEST_CASE("ExactSum: terms that cancel leave exactly what a float sum loses", "[base]") {
  // 1e30 + 1 - 1e30 is 0 in float and in double; the exact sum keeps the 1.
  CHECK(sum_of({1e30f, 1.0f, -1e30f}) == 1.0);
  CHECK(sum_of({1e30f, 3.0f, -1e30f, 0.25f}) == 3.25);
  // The smallest subnormal, twice, is exactly twice it.
  const float tiny = std::numeric_limits<float>::denorm_min();
  CHECK(sum_of({tiny, tiny}) == 2.0 * double(tiny));
  CHECK(sum_of({}) == 0.0);
  CHECK(sum_of({-2.5f, -0.5f}) == -3.0);
}

TEST_CASE("ExactSum: the value is the exact sum rounded to double", "[base]") {
  // Integers scaled by 2^-20 and kept below 2^40 in magnitude: their sum is exact in a 128-bit integer, so it
  // can be rounded once and compared with no tolerance but double's own half unit.
  std::mt19937 rng(5);
  std::uniform_int_distribution<std::int32_t> m(-(1 << 23), 1 << 23);
  std::uniform_int_distribution<int> shift(0, 16);
  __int128 exact = 0;  // in units of 2^-20
  std::vector<float> values;
  for (int n = 0; n < 50000; ++n) {
    const std::int64_t units = std::int64_t(m(rng)) << shift(rng);
    exact += units;
    values.push_back(std::ldexp(float(units), -20));
  }
  const double expected = std::ldexp(double(exact), -20);  // |exact| < 2^60: one rounding
  CHECK(sum_of(values) == expected);
}

TEST_CASE("ExactSum: NaN and infinities are counted, not lost", "[base]") {
  const float inf = std::numeric_limits<float>::infinity();
  CHECK(std::isnan(sum_of({1.0f, std::numeric_limits<float>::quiet_NaN(), 2.0f})));
  CHECK(sum_of({1.0f, inf}) == std::numeric_limits<double>::infinity());
  CHECK(sum_of({-inf, 5.0f}) == -std::numeric_limits<double>::infinity());
  CHECK(std::isnan(sum_of({inf, -inf})));
}
