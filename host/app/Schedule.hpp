// Something the run loop does at a fixed interval of simulated time: frames, probe samples, checkpoints and
// the statistics' records.
//
//   fw::host::Schedule frames(1.0);          // due at t = 1, 2, 3, ... s
//   if (frames.due(report.wind.time)) ...   // the first step that reaches each multiple
#pragma once

namespace fw::host {

/// Simulated times closer than this fraction of an interval are the same time (sums of float dt): the run
/// loop's schedules of frames, probe samples and checkpoints, and the output size that counts them.
inline constexpr double kScheduleTolerance = 1e-9;

/// Due at the first step that reaches each multiple of the interval (0: every step).
class Schedule {
 public:
  explicit Schedule(double interval) : interval_(interval), next_(interval) {}
  /// The next due time, s (what a checkpoint keeps), and going on from one.
  double next() const { return next_; }
  void resume(double next) { next_ = next; }
  /// Whether time t (s) has reached the next due time (within the tolerance).
  bool reached(double t) const { return !(interval_ > 0.0) || t >= next_ - kScheduleTolerance * interval_; }
  /// Whether time t (s) has reached the next due time; if so, the next one moves past t.
  bool due(double t) {
    if (!reached(t)) return false;
    if (!(interval_ > 0.0)) return true;
    while (next_ <= t + kScheduleTolerance * interval_) next_ += interval_;
    return true;
  }

 private:
  double interval_, next_;
};

}  // namespace fw::host
