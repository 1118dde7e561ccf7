// What a run changes over time, as functions of the simulated time t (s). CoupledStep applies them itself:
// start() at t = 0, then every step() at the time the step starts, so that no caller repeats the feeding.
//
//   fw::host::TimeInputs inputs = fw::host::TimeInputs::steady({10, 0, 0});   // a constant west wind
//   inputs.turbulence_sigma = [](double t) { return 1.5; };                  // sigma_u of the inflow box
//   fw::host::CoupledStep coupled(cc, setup, forest, coupling, inputs);
#pragma once

#include <array>
#include <functional>

namespace fw::host {

struct TimeInputs {
  /// The ambient wind at the reference height, m/s, x east, y north. Required.
  std::function<std::array<double, 3>(double)> ambient_wind;
  /// sigma_u of the inflow turbulence box, m/s; empty without inflow turbulence.
  std::function<double(double)> turbulence_sigma;
  /// sigma_u / U of the trees' unresolved turbulence; empty without it.
  std::function<double(double)> unresolved_intensity;

  /// The same ambient wind at all times, and nothing else.
  static TimeInputs steady(const std::array<double, 3>& ambient) {
    TimeInputs inputs;
    inputs.ambient_wind = [ambient](double) { return ambient; };
    return inputs;
  }
};

}  // namespace fw::host
