// An item of a scenario's events (docs/scenario.md, "events"): a gust. Its keys are
// io/schema/EventKeys.hpp's, none with a default.
//
//   fw::io::GustEvent gust{.start = 30, .duration = 8, .peak_speed = 12, .center = {200, 100, 20}, .radius =
//   40};
#pragma once

#include <array>

namespace fw::io {

/// A gust: a Gaussian ball of extra wind with a 1-cos envelope over [start, start + duration].
struct GustEvent {
  double start = 0.0;              ///< s, >= 0
  double duration = 0.0;           ///< s, > 0
  double peak_speed = 0.0;         ///< m/s, >= 0, at the envelope's peak and the ball's centre
  std::array<double, 3> center{};  ///< m, at `start`
  double radius = 0.0;             ///< m, > 0
  bool travel_with_wind = true;    ///< `travel: with_wind` in the file
  std::array<double, 3> travel{};  ///< m/s; with_wind: wind_vector(start), resolved at load
};

}  // namespace fw::io
