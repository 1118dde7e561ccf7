// What a wind grid is made from (host/stages/WindGrid): the grid, the solver's settings, the inflow, the
// solids and the gusts, the ambient wind and its turbulence, the mean forcing. The whole grid's, over ranks
// too: each part cuts its block out of it through the RankSeam.
#pragma once

#include <array>
#include <cstdint>
#include <memory>
#include <vector>

#include "fluid/GridSpec.hpp"
#include "fluid/InflowProfile.hpp"
#include "fluid/TurbulenceBox.hpp"
#include "fluid/WindSettings.hpp"
#include "kernels/shared_types.h"

namespace fw::host {

/// Holds the horizontal mean wind of the reference-height layer at the ambient wind, for periodic domains
/// that have no inflow to drive them (canopy LES): a uniform body acceleration a = e / tau + (integral of e
/// dt) / tau^2 with e = ambient - layer mean. For a flow whose drag responds slowly this PI controller
/// settles like an oscillator of natural period 2 pi tau and damping ratio 1/2, and its integral part
/// converges to the mean pressure gradient that balances the drag.
struct MeanForcing {
  double relaxation_time = 0.0;  // tau, s; 0: off
};

struct WindGridSetup {
  fluid::GridSpec spec;
  fluid::WindSettings settings;
  fluid::InflowProfile profile;
  std::vector<std::uint8_t> solid;         // one byte a cell, non-zero = solid; empty = no solids
  std::vector<FwGust> gusts;               // travelling gust balls
  std::array<double, 3> ambient{0, 0, 0};  // ambient wind at the reference height, m/s
  /// Unit-sigma synthetic turbulence swept through the inflow faces at the ambient wind (Taylor's frozen
  /// turbulence) and added to the initial field; null: a laminar inflow. Its sigma is set_turbulence_sigma.
  std::shared_ptr<const fluid::TurbulenceBox> turbulence;
  MeanForcing forcing;
};

}  // namespace fw::host
