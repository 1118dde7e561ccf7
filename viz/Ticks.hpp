// Tick marks for axes and colour bars: round numbers (1, 2 or 5 times a power of ten) that a reader can
// interpolate between, and their labels.
//
//   std::vector<double> ticks = fw::viz::nice_ticks(0.0, 23.7, 5);   // 0, 5, 10, 15, 20
//   std::string label = fw::viz::tick_label(12.5, 2.5);              // "12.5"
#pragma once

#include <string>
#include <vector>

namespace fw::viz {

/// Round tick values inside [lo, hi], about `target` of them (step 1, 2 or 5 x 10^n). lo == hi gives {lo};
/// lo > hi is swapped.
std::vector<double> nice_ticks(double lo, double hi, int target);
/// The powers of ten inside [lo, hi] (lo > 0), for a log axis; when fewer than two fit, 2 and 5 times
/// them are added.
std::vector<double> log_ticks(double lo, double hi);
/// The spacing of a list from nice_ticks (1 for a single tick).
double tick_step(const std::vector<double>& ticks);
/// `value` with as many decimals as `step` needs (12.5 with step 2.5 -> "12.5", 10 with step 5 -> "10").
std::string tick_label(double value, double step);

}  // namespace fw::viz
