// The Scenario structs' own functions: the wind at a time, the grid it gives, the solver settings. Reading a
// file into them is io/scenario/ (load_scenario: io/scenario/Load.cpp).
#include "io/Scenario.hpp"

#include <fmt/format.h>

#include <cmath>
#include <limits>
#include <numbers>
#include <utility>

namespace fw::io {

ScenarioError::ScenarioError(std::string file, int line, std::string key, const std::string& message)
    : std::invalid_argument(fmt::format("{}:{}: {}: {}", file, line, key, message)),
      file_(std::move(file)),
      line_(line),
      key_(std::move(key)) {}

std::string to_string(BoundaryChoice choice) {
  switch (choice) {
    case BoundaryChoice::automatic:
      return "auto";
    case BoundaryChoice::inflow:
      return "inflow";
    case BoundaryChoice::outflow:
      return "outflow";
    case BoundaryChoice::slip:
      return "slip";
    case BoundaryChoice::no_slip:
      return "no_slip";
    case BoundaryChoice::periodic:
      return "periodic";
    case BoundaryChoice::rough:
      return "rough";
  }
  return "?";
}

namespace {

/// sin and cos of an angle in degrees, exactly 0 and +-1 at whole multiples of 90 degrees. sin(degrees * pi /
/// 180) is not: at 270 degrees the cosine comes out as -1.8e-16, which would make a wind along x cross the
/// south face (an "auto" face parallel to the wind must resolve to outflow, see Scenario::grid_spec).
std::array<double, 2> sin_cos_degrees(double degrees) {
  constexpr double nan = std::numeric_limits<double>::quiet_NaN();
  if (!std::isfinite(degrees)) return {nan, nan};
  double reduced = std::fmod(degrees, 360.0);  // exact
  if (reduced < 0.0) reduced += 360.0;
  const double quadrant = std::round(reduced / 90.0);                          // 0..4
  const double rest = (reduced - 90.0 * quadrant) * std::numbers::pi / 180.0;  // within +-45 degrees
  const double s = std::sin(rest), c = std::cos(rest);
  switch (int(quadrant) % 4) {
    case 0:
      return {s, c};
    case 1:
      return {c, -s};
    case 2:
      return {-s, -c};
    default:
      return {-c, s};
  }
}

}  // namespace

std::array<double, 3> Scenario::wind_vector(double t) const {
  return io::wind_vector(wind, t);
}

std::array<double, 3> wind_vector(const WindSource& wind, double t) {
  const double speed = wind.speed(t);
  // Meteorological: the direction is where the wind comes FROM, so it blows toward direction + 180 degrees.
  const auto [sin_theta, cos_theta] = sin_cos_degrees(wind.direction(t));
  return {-speed * sin_theta, -speed * cos_theta, 0.0};
}

fluid::GridSpec Scenario::grid_spec(double t) const {
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

std::optional<double> Scenario::resolved_probe_interval() const {
  if (output.probe_interval) return output.probe_interval;
  if (wind.turbulence) return std::nullopt;  // every solver step, for spectra
  return output.interval;
}

std::array<double, 3> TurbulenceSettings::standard_deviations(double speed) const {
  if (sigma) return *sigma;
  const double sigma_u = intensity.value_or(0.0) * speed;
  return {sigma_u, sigma_u, sigma_u};
}

fluid::WindSettings Scenario::wind_settings() const {
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
