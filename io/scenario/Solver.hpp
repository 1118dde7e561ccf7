// The reader of a scenario's solver section (Solver.cpp), which load_scenario (Load.cpp) calls.
//
//   read_solver(loader, *solver, scenario.solver);
#pragma once

#include "io/scenario/Reader.hpp"
#include "io/settings/SolverSettings.hpp"

namespace fw::io::reader {

void read_solver(const Loader& loader, const Field& field, SolverSettings& solver);

}  // namespace fw::io::reader
