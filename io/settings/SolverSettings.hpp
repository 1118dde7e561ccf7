// The solver section of a scenario (docs/scenario.md, "solver"): the pressure solver, the advection scheme
// and the subgrid model. Defaults are the schema's (io/schema/SolverKeys.hpp), which are fluid::WindSettings'
// own.
//
//   fw::io::SolverSettings solver;   // cg to a relative residual of fluid::kDefaultPressureTolerance
#pragma once

#include "fluid/WindSettings.hpp"
#include "io/schema/SolverKeys.hpp"

namespace fw::io {

struct SolverSettings {
  fluid::PressureSolverType pressure =
      schema::value_of(schema::kPressureWords, schema::kPressureSolvers,
                       schema::key(schema::kSolverKeys, "solver.pressure").word);
  /// relative residual (multigrid, cg), > 0
  double tolerance = schema::key(schema::kSolverKeys, "solver.tolerance").number;
  /// >= 1 (multigrid, cg)
  int max_iterations = int(schema::key(schema::kSolverKeys, "solver.max_iterations").number);
  /// >= 1 (jacobi)
  int jacobi_iterations = int(schema::key(schema::kSolverKeys, "solver.jacobi_iterations").number);
  fluid::AdvectionScheme advection =
      schema::value_of(schema::kAdvectionWords, schema::kAdvectionSchemes,
                       schema::key(schema::kSolverKeys, "solver.advection").word);
  fluid::StageProjection stage_projection =
      schema::value_of(schema::kStageProjectionWords, schema::kStageProjections,
                       schema::key(schema::kSolverKeys, "solver.stage_projection").word);
  /// epsilon, dimensionless, >= 0 (0: off)
  double vorticity_confinement = schema::key(schema::kSolverKeys, "solver.vorticity_confinement").number;
  /// The subgrid stress's model (smagorinsky: on while smagorinsky_constant > 0)
  fluid::SubgridModel subgrid = schema::value_of(schema::kSubgridWords, schema::kSubgridModels,
                                                 schema::key(schema::kSolverKeys, "solver.subgrid").word);
  /// C_s of the eddy viscosity (C_s h)^2 |S|, dimensionless, in [0, 1) (0: off); not given with tke
  double smagorinsky_constant = schema::key(schema::kSolverKeys, "solver.smagorinsky_constant").number;
};

}  // namespace fw::io
