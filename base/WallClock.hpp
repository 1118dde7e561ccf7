// Wall time for the timings that runs and benchmarks report: a steady clock, and the milliseconds since a
// moment of it.
//
//   const auto start = fw::base::WallClock::now();
//   ...
//   double ms = fw::base::ms_since(start);
#pragma once

#include <chrono>

namespace fw::base {

using WallClock = std::chrono::steady_clock;

/// Milliseconds of wall time since `start`.
inline double ms_since(WallClock::time_point start) {
  return std::chrono::duration<double, std::milli>(WallClock::now() - start).count();
}

}  // namespace fw::base
