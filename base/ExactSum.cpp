#include "base/ExactSum.hpp"

#include <bit>
#include <cmath>
#include <limits>

namespace fw::base {
namespace {

constexpr std::uint32_t kMantissaBits = 23;
constexpr std::uint32_t kMantissaMask = (1u << kMantissaBits) - 1;
constexpr std::uint32_t kExponentMask = 0xff;
constexpr std::uint32_t kNonFiniteExponent = 0xff;
// A float of biased exponent e (>= 1) and 24-bit integer significand m is m * 2^(e - kExponentOffset).
constexpr int kExponentOffset = 150;

}  // namespace

void ExactSum::add(float value) {
  const auto bits = std::bit_cast<std::uint32_t>(value);
  const std::uint32_t exponent = (bits >> kMantissaBits) & kExponentMask;
  const std::uint32_t fraction = bits & kMantissaMask;
  const bool negative = (bits >> 31) != 0;
  if (exponent == kNonFiniteExponent) {
    ++slots_[fraction != 0 ? kNanSlot : (negative ? kNegativeInfinitySlot : kPositiveInfinitySlot)];
    return;
  }
  // Normal: the hidden bit joins the fraction. Subnormal: the fraction alone, on the scale of exponent 1.
  const std::int64_t magnitude = exponent == 0 ? fraction : (fraction | (1u << kMantissaBits));
  slots_[exponent == 0 ? 1 : exponent] += negative ? -magnitude : magnitude;
}

ExactSum& ExactSum::operator+=(const ExactSum& other) {
  for (int s = 0; s < kSlots; ++s) slots_[s] += other.slots_[s];
  return *this;
}

double ExactSum::value() const {
  if (slots_[kNanSlot] > 0 || (slots_[kPositiveInfinitySlot] > 0 && slots_[kNegativeInfinitySlot] > 0))
    return std::numeric_limits<double>::quiet_NaN();
  if (slots_[kPositiveInfinitySlot] > 0) return std::numeric_limits<double>::infinity();
  if (slots_[kNegativeInfinitySlot] > 0) return -std::numeric_limits<double>::infinity();
  // Carry each bin's whole pairs into the next (floor division, so every bin below the top ends as 0 or 1
  // and the top one takes the sign): the same exact sum as one signed binary number. Adding its digits from
  // the top down in double then rounds it only where 53 bits run out.
  std::array<std::int64_t, kBins + 1> digits{};
  for (int e = 0; e < kBins; ++e) digits[e] = slots_[e];
  for (int e = 1; e < kBins; ++e) {
    const std::int64_t carry = digits[e] >> 1;  // arithmetic shift: floor(digits / 2)
    digits[e] -= 2 * carry;
    digits[e + 1] += carry;
  }
  double sum = std::ldexp(double(digits[kBins]), kBins - kExponentOffset);
  for (int e = kBins - 1; e >= 1; --e)
    if (digits[e] != 0) sum += std::ldexp(1.0, e - kExponentOffset);
  return sum;
}

}  // namespace fw::base
