#include "fluid/DragLaw.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <cmath>
#include <stdexcept>

namespace fw::fluid {

double DragLaw::factor(double speed) const {
  if (constant()) return 1.0;
  return std::pow(std::max(speed, kSpeedFloor * reference_speed) / reference_speed, exponent);
}

FwDragLaw DragLaw::to_device() const {
  FwDragLaw law{};
  law.exponent = float(exponent);
  law.lowest_speed = float(kSpeedFloor * reference_speed);
  law.inverse_reference_speed = float(1.0 / reference_speed);
  return law;
}

void DragLaw::validate() const {
  if (!(exponent >= kLowestExponent && exponent <= 0.0))
    throw std::invalid_argument(
        fmt::format("DragLaw: the exponent must lie in [{:.4g}, 0], got {}", kLowestExponent, exponent));
  if (!(std::isfinite(reference_speed) && reference_speed > 0.0))
    throw std::invalid_argument(
        fmt::format("DragLaw: the reference speed must be > 0 m/s, got {}", reference_speed));
}

}  // namespace fw::fluid
