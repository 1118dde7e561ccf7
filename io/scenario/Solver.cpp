// solver: the pressure solver, advection and the subgrid models.
#include "io/scenario/Solver.hpp"

#include <fmt/format.h>

namespace fw::io::reader {

void read_solver(const Loader& loader, const Field& field, SolverSettings& solver) {
  const Section<schema::kSolverKeys, "solver"> map(loader, field);
  if (const auto pressure = map.get<"pressure">())
    solver.pressure = value(schema::kPressureWords, schema::kPressureSolvers, loader.word(*pressure));
  if (const auto tolerance = map.get<"tolerance">()) solver.tolerance = loader.number(*tolerance);
  if (const auto iterations = map.get<"max_iterations">())
    solver.max_iterations = loader.integer(*iterations);
  if (const auto iterations = map.get<"jacobi_iterations">())
    solver.jacobi_iterations = loader.integer(*iterations);
  if (const auto advection = map.get<"advection">())
    solver.advection = value(schema::kAdvectionWords, schema::kAdvectionSchemes, loader.word(*advection));
  if (const auto projection = map.get<"stage_projection">())
    solver.stage_projection =
        value(schema::kStageProjectionWords, schema::kStageProjections, loader.word(*projection));
  if (const auto epsilon = map.get<"vorticity_confinement">())
    solver.vorticity_confinement = loader.number(*epsilon);
  if (const auto subgrid = map.get<"subgrid">())
    solver.subgrid = value(schema::kSubgridWords, schema::kSubgridModels, loader.word(*subgrid));
  if (const auto smagorinsky = map.get<"smagorinsky_constant">()) {
    // Strict: a constant the tke model would ignore is more likely a forgotten switch than a wish.
    if (solver.subgrid != fluid::SubgridModel::smagorinsky)
      loader.expected(*smagorinsky, fmt::format("nothing unless solver.subgrid is smagorinsky (it is '{}': "
                                                "its eddy viscosity comes from the subgrid energy)",
                                                fluid::to_string(solver.subgrid)));
    solver.smagorinsky_constant = loader.number(*smagorinsky);
  } else if (solver.advection == fluid::AdvectionScheme::upwind5 &&
             solver.subgrid == fluid::SubgridModel::smagorinsky) {
    // The less dissipative scheme needs a subgrid model to drain the cascade; the other two drain it
    // themselves.
    solver.smagorinsky_constant = fluid::WindSettings::kUpwind5SmagorinskyConstant;
  }
}

}  // namespace fw::io::reader
