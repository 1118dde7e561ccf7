// The wall time of each stage of the wind step, for benchmarks: off by default, when it costs nothing.
//
//   fw::host::StageClock clock(cc);
//   clock.set_on(true);
//   clock.time("advect", [&] { advection.advect(fields, dt); });
//   clock.ms().at("advect");                     // ms so far
//
// A stage ends with a queue finish, so its time is its kernels'. A stage timed inside another (upwind5's
// stage projections inside "advect") counts for itself only.
#pragma once

#include <chrono>
#include <map>
#include <string>

#include "host/runtime/ComputeContext.hpp"

namespace fw::host {

class StageClock {
 public:
  explicit StageClock(ComputeContext& cc) : cc_(cc) {}

  void set_on(bool on) { on_ = on; }
  const std::map<std::string, double>& ms() const { return ms_; }
  void reset() { ms_.clear(); }

  template <typename F>
  void time(const char* stage, F&& work) {
    if (!on_) {
      work();
      return;
    }
    const double nested_before = nested_ms_;
    cc_.finish();  // what the enclosing stage enqueued before this one is the enclosing stage's
    const auto start = std::chrono::steady_clock::now();
    work();
    cc_.finish();
    const double total =
        std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - start).count();
    ms_[stage] += total - (nested_ms_ - nested_before);
    nested_ms_ = nested_before + total;
  }

 private:
  ComputeContext& cc_;
  bool on_ = false;
  std::map<std::string, double> ms_;
  double nested_ms_ = 0.0;  // the stages timed so far, for the stages timed inside others
};

}  // namespace fw::host
