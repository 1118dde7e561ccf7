// The wind's part of a scenario: the wind at a time, the grid it gives, the solver settings. Reading a file
// into it is io/scenario/ (load_scenario: io/scenario/Load.cpp).
#include "io/WindScenario.hpp"

namespace fw::io {

std::array<double, 3> WindScenario::wind_vector(double t) const {
  return io::wind_vector(wind, t);
}

fluid::GridSpec WindScenario::grid_spec(double t) const {
  fluid::GridSpec spec;
  spec.nx = domain.cells[0];
  spec.ny = domain.cells[1];
  spec.nz = domain.cells[2];
  spec.h = domain.cell_size;
  spec.origin = domain.origin;
  const std::array<double, 3> wind_now = wind_vector(t);
  for (int face = 0; face < 6; ++face) {
    switch (boundaries[face]) {
      case BoundaryChoice::automatic: {
        // The wind enters through a minimum face when it points along +axis, through a maximum face when
        // -axis.
        const double along = wind_now[face / 2];
        const bool enters = face % 2 == 0 ? along > 0.0 : along < 0.0;
        spec.boundary[face] = enters ? fluid::BoundaryType::inflow : fluid::BoundaryType::outflow;
        break;
      }
      case BoundaryChoice::inflow:
        spec.boundary[face] = fluid::BoundaryType::inflow;
        break;
      case BoundaryChoice::outflow:
        spec.boundary[face] = fluid::BoundaryType::outflow;
        break;
      case BoundaryChoice::slip:
        spec.boundary[face] = fluid::BoundaryType::slip;
        break;
      case BoundaryChoice::no_slip:
        spec.boundary[face] = fluid::BoundaryType::no_slip;
        break;
      case BoundaryChoice::periodic:
        spec.boundary[face] = fluid::BoundaryType::periodic;
        break;
      case BoundaryChoice::rough:  // a slip wall; the log-law wall stress is a stage of its own
        spec.boundary[face] = fluid::BoundaryType::slip;
        break;
    }
  }
  return spec;
}

fluid::WindSettings WindScenario::wind_settings() const {
  fluid::WindSettings settings;
  settings.advection = solver.advection;
  settings.stage_projection = solver.stage_projection;
  settings.pressure.solver = solver.pressure;
  settings.pressure.tolerance = solver.tolerance;
  settings.pressure.max_iterations = solver.max_iterations;
  settings.pressure.jacobi_iterations = solver.jacobi_iterations;
  settings.vorticity_confinement = solver.vorticity_confinement;
  settings.subgrid = solver.subgrid;
  settings.smagorinsky_constant = solver.smagorinsky_constant;
  settings.wall_roughness_length = ground_roughness_length;
  if (time.dt) {
    settings.dt = *time.dt;
    settings.cfl = 0.0;
  } else {
    settings.cfl = time.cfl;
  }
  return settings;
}

}  // namespace fw::io
