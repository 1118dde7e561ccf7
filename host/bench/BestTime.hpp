// The best of a few timed launches, as STREAM reports its best run: the machine's other load only ever slows
// a launch down. Shared by the roofline probes (STREAM triad, gather rate, FMA peak).
//
//   const double seconds = fw::bench::best_seconds(cc, 10, [&] { kernel.enqueue(cc, range); });
#pragma once

#include <algorithm>
#include <chrono>

#include "host/runtime/ComputeContext.hpp"

namespace fw::bench {

/// Runs `launch` once untimed (first touch, lazy builds), then `repetitions` times, each to completion
/// (cc.finish()); returns the shortest, in seconds.
template <class Launch>
double best_seconds(host::ComputeContext& cc, int repetitions, Launch&& launch) {
  launch();
  cc.finish();
  double best = 1e30;
  for (int r = 0; r < repetitions; ++r) {
    const auto start = std::chrono::steady_clock::now();
    launch();
    cc.finish();
    best = std::min(best, std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count());
  }
  return best;
}

}  // namespace fw::bench
