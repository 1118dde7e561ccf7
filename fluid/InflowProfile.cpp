#include "fluid/InflowProfile.hpp"

#include <fmt/format.h>

#include <cmath>
#include <stdexcept>

namespace fw::fluid {

void InflowProfile::validate() const {
  if (!(reference_height > 0.0))
    throw std::invalid_argument(
        fmt::format("InflowProfile: reference_height must be > 0 m, got {}", reference_height));
  if (type == Type::power && !(alpha >= 0.0))
    throw std::invalid_argument(fmt::format("InflowProfile: power-law alpha must be >= 0, got {}", alpha));
  if (type == Type::log) {
    if (!(roughness_length > 0.0))
      throw std::invalid_argument(
          fmt::format("InflowProfile: roughness_length must be > 0 m, got {}", roughness_length));
    if (!(displacement_height >= 0.0))
      throw std::invalid_argument(
          fmt::format("InflowProfile: displacement_height must be >= 0 m, got {}", displacement_height));
    if (!(reference_height - displacement_height > roughness_length))
      throw std::invalid_argument(fmt::format(
          "InflowProfile: reference_height ({} m) must exceed displacement_height + roughness_length ({} m)",
          reference_height, displacement_height + roughness_length));
  }
}

double InflowProfile::shape(double z) const {
  switch (type) {
    case Type::uniform:
      return 1.0;
    case Type::power:
      return z <= 0.0 ? 0.0 : std::pow(z / reference_height, alpha);
    case Type::log: {
      const double above = z - displacement_height;
      if (above <= roughness_length) return 0.0;
      return std::log(above / roughness_length) /
             std::log((reference_height - displacement_height) / roughness_length);
    }
  }
  return 1.0;
}

std::vector<float> InflowProfile::sample_cell_centres(int nz, double h) const {
  std::vector<float> s(static_cast<std::size_t>(nz));
  for (int k = 0; k < nz; ++k) s[k] = static_cast<float>(shape((k + 0.5) * h));
  return s;
}

}  // namespace fw::fluid
