#include "viz/DisplacementScale.hpp"

#include <algorithm>
#include <cmath>

namespace fw::viz {

double displacement_scale(std::vector<double> magnitudes) {
  if (magnitudes.empty()) return 0.0;
  const std::size_t rank = std::size_t(std::ceil(kDisplacementQuantile * magnitudes.size())) - 1;
  std::nth_element(magnitudes.begin(), magnitudes.begin() + rank, magnitudes.end());
  return magnitudes[rank];
}

std::vector<double> displacement_magnitudes(std::span<const float> xyz) {
  std::vector<double> magnitudes;
  magnitudes.reserve(xyz.size() / 3);
  for (std::size_t n = 0; n + 2 < xyz.size(); n += 3) {
    double d = 0.0;
    for (int c = 0; c < 3; ++c) d += double(xyz[n + c]) * double(xyz[n + c]);
    magnitudes.push_back(std::sqrt(d));
  }
  return magnitudes;
}

}  // namespace fw::viz
