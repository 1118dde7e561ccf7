// A small coupled run with leaves, for the tests of leaves in the coupled step (one process and over ranks).
//
//   const fw::test::LeafRun setup(16.0);   // m/s
//   fw::host::CoupledStep coupled(cc, setup.wind, setup.forest, setup.coupling,
//                                 fw::host::TimeInputs::steady(setup.wind.ambient));
#pragma once

#include "fluid/WindSettings.hpp"
#include "host/app/CouplingSettings.hpp"
#include "host/stages/WindGrid.hpp"
#include "trees/Forest.hpp"

namespace fw::test {

/// 48 x 16 x 16 cells of 1 m: inflow west at `speed` (m/s), outflow east, periodic sides, a no-slip ground
/// and a 4 m high block downwind of two small broadleaf trees in leaf (a few thousand big leaves each, whose
/// median petiole gives way near 12 m/s).
struct LeafRun {
  host::WindGridSetup wind;
  trees::Forest forest;
  host::CouplingSettings coupling;

  explicit LeafRun(double speed, fluid::AdvectionScheme advection = fluid::AdvectionScheme::semi_lagrangian);
};

}  // namespace fw::test
