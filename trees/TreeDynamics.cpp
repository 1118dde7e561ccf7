#include "trees/TreeDynamics.hpp"

#include <fmt/format.h>

#include <array>
#include <cmath>
#include <stdexcept>
#include <utility>

namespace fw::trees {
namespace {

constexpr std::array<std::pair<TreeDynamics, const char*>, 3> kNames = {{
    {TreeDynamics::modal, "modal"},
    {TreeDynamics::rigid_bodies, "rigid_bodies"},
    {TreeDynamics::springs, "springs"},
}};

// A bend beyond a right angle has no meaning for one element turning about its base.
constexpr double kRightAngleDeg = 90.0;

}  // namespace

const char* dynamics_name(TreeDynamics model) {
  for (const auto& [value, name] : kNames)
    if (value == model) return name;
  throw std::logic_error("dynamics_name: unknown model");
}

std::optional<TreeDynamics> parse_dynamics(std::string_view word) {
  for (const auto& [value, name] : kNames)
    if (word == name) return value;
  return std::nullopt;
}

void SpeciesDynamics::validate() const {
  const auto fail = [](const std::string& what) { throw std::invalid_argument("SpeciesDynamics: " + what); };
  if (!(std::isfinite(rigid_bodies.damping_ratio) && rigid_bodies.damping_ratio >= 0.0))
    fail(fmt::format("rigid_bodies.damping_ratio must be finite and >= 0, got {}",
                     rigid_bodies.damping_ratio));
  if (!(springs.max_angle_deg > 0.0 && springs.max_angle_deg < kRightAngleDeg))
    fail(fmt::format("springs.max_angle_deg must lie in (0, {}), got {}", kRightAngleDeg,
                     springs.max_angle_deg));
  if (!(std::isfinite(springs.sway_amplitude) && springs.sway_amplitude >= 0.0))
    fail(fmt::format("springs.sway_amplitude must be finite and >= 0, got {}", springs.sway_amplitude));
  if (!(std::isfinite(springs.sway_frequency_hz) && springs.sway_frequency_hz > 0.0))
    fail(fmt::format("springs.sway_frequency_hz must be finite and > 0, got {}", springs.sway_frequency_hz));
}

}  // namespace fw::trees
