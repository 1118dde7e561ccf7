// A number that is the whole of a piece of text, as the readers take one: locale independent
// (std::from_chars), a leading '+' allowed (YAML, CSV and ESRI ASCII grids may write one), nothing before
// or after it, no space. Every reader of numbers in text goes through here, so that "+-3", " 3" and "3m"
// are refused alike everywhere.
//
//   std::optional<double> h = fw::base::parse_number<double>("+2.5");   // 2.5
//   std::optional<int> n = fw::base::parse_number<int>("-3");           // -3; "3.0", "", "0x3": nullopt
//   std::optional<double> t = fw::base::parse_finite("1e400");          // nullopt: out of range
//   fw::base::parse_finite("nan");                                      // nullopt; parse_number<double>: NaN
#pragma once

#include <charconv>
#include <cmath>
#include <optional>
#include <string_view>
#include <system_error>
#include <type_traits>

namespace fw::base {

/// The integer or floating-point number that `text` is, whole, or nullopt: for anything else, and for a
/// value out of Number's range. Floating point takes "inf" and "nan" as from_chars does (parse_finite
/// refuses them).
template <typename Number>
std::optional<Number> parse_number(std::string_view text) {
  static_assert(std::is_arithmetic_v<Number> && !std::is_same_v<Number, bool>);
  // from_chars takes a leading '-' but not '+'; after a '+' a sign is one too many.
  if (!text.empty() && text.front() == '+') {
    text.remove_prefix(1);
    if (!text.empty() && (text.front() == '-' || text.front() == '+')) return std::nullopt;
  }
  if (text.empty()) return std::nullopt;
  Number value{};
  const auto [end, error] = std::from_chars(text.data(), text.data() + text.size(), value);
  if (error != std::errc() || end != text.data() + text.size()) return std::nullopt;
  return value;
}

/// A finite number that `text` is, whole (parse_number<double>), or nullopt.
inline std::optional<double> parse_finite(std::string_view text) {
  const std::optional<double> value = parse_number<double>(text);
  if (!value || !std::isfinite(*value)) return std::nullopt;
  return value;
}

}  // namespace fw::base
