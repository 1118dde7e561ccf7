#include "viz/Ticks.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <cmath>

namespace fw::viz {

std::vector<double> nice_ticks(double lo, double hi, int target) {
  if (lo > hi) std::swap(lo, hi);
  if (!(hi > lo) || target < 1) return {lo};
  const double raw = (hi - lo) / target;
  const double decade = std::pow(10.0, std::floor(std::log10(raw)));
  double step = decade;
  for (double factor : {1.0, 2.0, 5.0, 10.0})
    if (factor * decade >= raw) {
      step = factor * decade;
      break;
    }
  std::vector<double> ticks;
  // A tick within a millionth of a step of an end counts as inside (rounding of lo / step).
  const double slack = 1e-6 * step;
  for (double t = std::ceil((lo - slack) / step) * step; t <= hi + slack; t += step)
    ticks.push_back(std::abs(t) < slack ? 0.0 : t);
  return ticks;
}

std::vector<double> log_ticks(double lo, double hi) {
  std::vector<double> ticks;
  if (!(lo > 0.0) || !(hi > lo)) return ticks;
  const int first = int(std::ceil(std::log10(lo) - 1e-9)), last = int(std::floor(std::log10(hi) + 1e-9));
  for (int e = first; e <= last; ++e) ticks.push_back(std::pow(10.0, e));
  if (ticks.size() < 2)
    for (int e = first - 1; e <= last; ++e)
      for (double m : {2.0, 5.0})
        if (const double t = m * std::pow(10.0, e); t >= lo && t <= hi) ticks.push_back(t);
  std::sort(ticks.begin(), ticks.end());
  return ticks;
}

double tick_step(const std::vector<double>& ticks) {
  return ticks.size() > 1 ? ticks[1] - ticks[0] : 1.0;
}

std::string tick_label(double value, double step) {
  const int decimals = step > 0.0 ? std::max(0, int(std::ceil(-std::log10(step) - 1e-9))) : 2;
  // A step like 2.5 needs one more decimal than its power of ten says.
  const double scaled = step * std::pow(10.0, decimals);
  const int extra = std::abs(scaled - std::round(scaled)) > 1e-6 ? 1 : 0;
  if (std::abs(value) >= 1e5 || (std::abs(value) < 1e-3 && value != 0.0)) return fmt::format("{:.3g}", value);
  return fmt::format("{:.{}f}", value, decimals + extra);
}

}  // namespace fw::viz
