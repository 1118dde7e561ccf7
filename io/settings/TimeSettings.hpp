// The time section of a scenario (docs/scenario.md, "time"): the run's end, its step and the wind's spin-up.
// Defaults are the schema's (io/schema/TimeKeys.hpp).
//
//   fw::io::TimeSettings time;   // time.cfl == 0.8, time.dt == nullopt (auto)
#pragma once

#include <optional>

#include "io/schema/TimeKeys.hpp"

namespace fw::io {

struct TimeSettings {
  double end = 0.0;          ///< s, > 0: the run covers [0, end]
  std::optional<double> dt;  ///< s, > 0: fixed step; nullopt for "auto"
  /// > 0, used with auto: dt = cfl * h / max|u|
  double cfl = schema::key(schema::kTimeKeys, "time.cfl").number;
  /// s, >= 0: the wind steps from -spin_up to 0 before the run (trees held in equilibrium); 0: none
  double spin_up = schema::key(schema::kTimeKeys, "time.spin_up").number;
  /// The lines of end, dt and spin_up in the file (of the time map where not given), for the planner's
  /// messages about them (their steps, dt's stability).
  int end_line = 0, dt_line = 0, spin_up_line = 0;
};

}  // namespace fw::io
