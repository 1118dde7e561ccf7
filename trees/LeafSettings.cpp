#include "trees/LeafSettings.hpp"

#include <fmt/format.h>

#include <cmath>
#include <stdexcept>

namespace fw::trees {
namespace {

[[noreturn]] void fail(const std::string& key, const std::string& rule, double got) {
  throw std::invalid_argument(fmt::format("LeafSettings: {} must be {}, got {}", key, rule, got));
}

void require_positive(const char* key, double value) {
  if (!std::isfinite(value) || value <= 0.0) fail(key, "finite and > 0", value);
}

void require_non_negative(const char* key, double value) {
  if (!std::isfinite(value) || value < 0.0) fail(key, "finite and >= 0", value);
}

}  // namespace

std::string to_string(FlutterModel model) {
  switch (model) {
    case FlutterModel::none:
      return "none";
    case FlutterModel::pseudo_branch:
      return "pseudo_branch";
    case FlutterModel::stochastic:
      return "stochastic";
  }
  throw std::invalid_argument(fmt::format("FlutterModel: unknown value {}", int(model)));
}

void LeafSettings::validate() const {
  require_positive("area", area);
  if (!std::isfinite(fraction) || fraction <= 0.0 || fraction > kMaxFraction)
    fail("fraction", fmt::format("in (0, {}]", kMaxFraction), fraction);
  require_positive("mass_per_area", mass_per_area);
  require_positive("frequency", frequency);
  if (!std::isfinite(damping_ratio) || damping_ratio < 0.0 || damping_ratio >= kDampingRatioBelow)
    fail("damping_ratio", fmt::format("in [0, {})", kDampingRatioBelow), damping_ratio);
  require_positive("petiole_strength", petiole_strength);
  require_non_negative("strength_spread", strength_spread);
  require_positive("flight_drag_coefficient", flight_drag_coefficient);
  for (const double w : amplitudes_deg) {
    if (!std::isfinite(w) || w < 0.0 || w > kMaxAmplitudeDeg)
      fail("amplitudes", fmt::format("in [0, {}] degrees", kMaxAmplitudeDeg), w);
  }
  if (!std::isfinite(roll_coupling)) fail("roll_coupling", "finite", roll_coupling);
  require_positive("reference_speed", reference_speed);
}

}  // namespace fw::trees
