#include "io/settings/WindSource.hpp"

#include <cmath>
#include <limits>
#include <numbers>

namespace fw::io {

namespace {

/// sin and cos of an angle in degrees, exactly 0 and +-1 at whole multiples of 90 degrees. sin(degrees * pi /
/// 180) is not: at 270 degrees the cosine comes out as -1.8e-16, which would make a wind along x cross the
/// south face (an "auto" face parallel to the wind must resolve to outflow, see WindScenario::grid_spec).
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

std::array<double, 3> wind_vector(const WindSource& wind, double t) {
  const double speed = wind.speed(t);
  // Meteorological: the direction is where the wind comes FROM, so it blows toward direction + 180 degrees.
  const auto [sin_theta, cos_theta] = sin_cos_degrees(wind.direction(t));
  return {-speed * sin_theta, -speed * cos_theta, 0.0};
}

std::array<double, 3> TurbulenceSettings::standard_deviations(double speed) const {
  if (sigma) return *sigma;
  const double sigma_u = intensity.value_or(0.0) * speed;
  return {sigma_u, sigma_u, sigma_u};
}

}  // namespace fw::io
