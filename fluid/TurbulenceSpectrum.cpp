#include "fluid/TurbulenceSpectrum.hpp"

#include <fmt/format.h>

#include <cmath>
#include <numbers>
#include <stdexcept>

namespace fw::fluid {

double von_karman_integral_ratio() {
  return std::sqrt(std::numbers::pi) * std::tgamma(5.0 / 6.0) / std::tgamma(1.0 / 3.0);
}

void VonKarmanSpectrum::validate() const {
  if (!(std::isfinite(sigma) && sigma > 0.0))
    throw std::invalid_argument(fmt::format("VonKarmanSpectrum: sigma must be > 0 m/s, got {}", sigma));
  if (!(std::isfinite(integral_length) && integral_length > 0.0))
    throw std::invalid_argument(
        fmt::format("VonKarmanSpectrum: integral_length must be > 0 m, got {}", integral_length));
}

double VonKarmanSpectrum::spectrum_length() const {
  return integral_length / von_karman_integral_ratio();
}

double VonKarmanSpectrum::energy(double k) const {
  const double L = spectrum_length();
  const double a = 3.0 * std::tgamma(17.0 / 6.0) / (std::tgamma(2.5) * std::tgamma(1.0 / 3.0));
  const double x2 = (k * L) * (k * L);
  return a * sigma * sigma * L * x2 * x2 / std::pow(1.0 + x2, 17.0 / 6.0);
}

double VonKarmanSpectrum::longitudinal(double k1) const {
  const double L = spectrum_length();
  const double x2 = (k1 * L) * (k1 * L);
  return 2.0 * sigma * sigma * integral_length / std::numbers::pi / std::pow(1.0 + x2, 5.0 / 6.0);
}

double VonKarmanSpectrum::transverse(double k1) const {
  const double L = spectrum_length();
  const double x2 = (k1 * L) * (k1 * L);
  return sigma * sigma * integral_length / std::numbers::pi * (1.0 + 8.0 / 3.0 * x2) /
         std::pow(1.0 + x2, 11.0 / 6.0);
}

}  // namespace fw::fluid
