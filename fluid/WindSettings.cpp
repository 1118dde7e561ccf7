#include "fluid/WindSettings.hpp"

#include <fmt/format.h>

#include <cmath>
#include <limits>
#include <stdexcept>

namespace fw::fluid {

std::string to_string(AdvectionScheme scheme) {
  switch (scheme) {
    case AdvectionScheme::semi_lagrangian:
      return "semi_lagrangian";
    case AdvectionScheme::maccormack:
      return "maccormack";
    case AdvectionScheme::upwind5:
      return "upwind5";
  }
  return "?";
}

std::string to_string(PressureSolverType solver) {
  switch (solver) {
    case PressureSolverType::jacobi:
      return "jacobi";
    case PressureSolverType::multigrid:
      return "multigrid";
    case PressureSolverType::cg:
      return "cg";
  }
  return "?";
}

std::string to_string(SubgridModel model) {
  switch (model) {
    case SubgridModel::smagorinsky:
      return "smagorinsky";
    case SubgridModel::tke:
      return "tke";
  }
  return "?";
}

void WindSettings::validate() const {
  if (cfl <= 0.0 && !(dt > 0.0))
    throw std::invalid_argument(fmt::format("WindSettings: fixed time step must be > 0 s, got {}", dt));
  if (cfl > 0.0 && !(max_dt > 0.0))
    throw std::invalid_argument(fmt::format("WindSettings: max_dt must be > 0 s, got {}", max_dt));
  if (viscosity < 0.0)
    throw std::invalid_argument(fmt::format("WindSettings: viscosity must be >= 0 m^2/s, got {}", viscosity));
  if (vorticity_confinement < 0.0)
    throw std::invalid_argument(
        fmt::format("WindSettings: vorticity_confinement must be >= 0, got {}", vorticity_confinement));
  if (!(smagorinsky_constant >= 0.0 && smagorinsky_constant < kSmagorinskyConstantBelow))
    throw std::invalid_argument(
        fmt::format("WindSettings: smagorinsky_constant must lie in [0, {}) (typically 0.1-0.2), got {}",
                    kSmagorinskyConstantBelow, smagorinsky_constant));
  if (subgrid == SubgridModel::tke && smagorinsky_constant != 0.0)
    throw std::invalid_argument(fmt::format(
        "WindSettings: smagorinsky_constant applies to the smagorinsky subgrid model only; the tke model "
        "takes its eddy viscosity from the subgrid energy, got {}",
        smagorinsky_constant));
  if (!(wall_roughness_length >= 0.0) || !std::isfinite(wall_roughness_length))
    throw std::invalid_argument(
        fmt::format("WindSettings: wall_roughness_length must be >= 0 m, got {}", wall_roughness_length));
  if (!(pressure.tolerance > 0.0))
    throw std::invalid_argument(
        fmt::format("WindSettings: pressure tolerance must be > 0, got {}", pressure.tolerance));
  if (pressure.max_iterations <= 0 || pressure.jacobi_iterations <= 0 || pressure.smoothing_sweeps <= 0)
    throw std::invalid_argument("WindSettings: pressure iteration counts must be positive");
}

}  // namespace fw::fluid
