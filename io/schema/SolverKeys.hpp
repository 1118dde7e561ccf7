// The keys of a scenario's solver section: the pressure solver and its tolerance, the advection scheme, the
// projection of its stages, vorticity confinement and the subgrid model. Their defaults are
// fluid::WindSettings' own.
//
//   schema::key(schema::kSolverKeys, "solver.tolerance").number;   // fluid::kDefaultPressureTolerance
//
// Each map's keys stand in the order the loader's messages and the docs list them. Each key's prose is in
// SolverKeys.cpp (solver_docs).
#pragma once

#include <span>
#include <string_view>

#include "fluid/WindSettings.hpp"
#include "io/schema/Bounds.hpp"
#include "io/schema/Key.hpp"

namespace fw::io::schema {

inline constexpr std::string_view kPressureWords[] = {"multigrid", "cg", "jacobi"};
inline constexpr fluid::PressureSolverType kPressureSolvers[] = {
    fluid::PressureSolverType::multigrid, fluid::PressureSolverType::cg, fluid::PressureSolverType::jacobi};

inline constexpr std::string_view kAdvectionWords[] = {"semi_lagrangian", "maccormack", "upwind5"};
inline constexpr fluid::AdvectionScheme kAdvectionSchemes[] = {fluid::AdvectionScheme::semi_lagrangian,
                                                               fluid::AdvectionScheme::maccormack,
                                                               fluid::AdvectionScheme::upwind5};
inline constexpr std::string_view kStageProjectionWords[] = {"final_stage", "every_stage"};
inline constexpr fluid::StageProjection kStageProjections[] = {fluid::StageProjection::final_stage,
                                                               fluid::StageProjection::every_stage};

inline constexpr std::string_view kSubgridWords[] = {"smagorinsky", "tke"};
inline constexpr fluid::SubgridModel kSubgridModels[] = {fluid::SubgridModel::smagorinsky,
                                                         fluid::SubgridModel::tke};

// Defaults owned elsewhere:
inline constexpr fluid::PressureSettings kPressureDefaults{};

inline constexpr Key kSolverKeys[] = {
    {.path = "solver.pressure", .type = Type::word, .words = kPressureWords, .word = "cg"},
    {.path = "solver.tolerance",
     .type = Type::number,
     .bound = Bound::positive,
     .at_most = bounds::kMaxTolerance,
     .number = fluid::kDefaultPressureTolerance},
    {.path = "solver.max_iterations",
     .type = Type::integer,
     .lowest = 1,
     .highest = bounds::kMaxSolverIterations,
     .number = kPressureDefaults.max_iterations},
    {.path = "solver.jacobi_iterations",
     .type = Type::integer,
     .lowest = 1,
     .highest = bounds::kMaxSolverIterations,
     .number = kPressureDefaults.jacobi_iterations},
    {.path = "solver.advection", .type = Type::word, .words = kAdvectionWords, .word = "semi_lagrangian"},
    {.path = "solver.stage_projection",
     .type = Type::word,
     .words = kStageProjectionWords,
     .word = "final_stage"},
    {.path = "solver.vorticity_confinement",
     .type = Type::number,
     .bound = Bound::non_negative,
     .at_most = bounds::kMaxVorticityConfinement,
     .number = fluid::WindSettings{}.vorticity_confinement},
    {.path = "solver.subgrid", .type = Type::word, .words = kSubgridWords, .word = "smagorinsky"},
    {.path = "solver.smagorinsky_constant",
     .type = Type::number,
     .bound = Bound::non_negative,
     .below = fluid::WindSettings::kSmagorinskyConstantBelow,
     .number = fluid::WindSettings{}.smagorinsky_constant},
};

/// The prose of each key of kSolverKeys (SolverKeys.cpp), which schema::docs (io/ScenarioSchema.hpp) finds by
/// its path.
std::span<const KeyDocs> solver_docs();

}  // namespace fw::io::schema
