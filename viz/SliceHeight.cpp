#include "viz/SliceHeight.hpp"

#include <algorithm>
#include <cmath>
#include <stdexcept>

namespace fw::viz {

double default_slice_height(const std::array<double, 3>& origin, const std::array<double, 3>& size,
                            double cell_size) {
  if (!(std::isfinite(origin[2]) && std::isfinite(size[2]) && size[2] > 0.0))
    throw std::invalid_argument("default_slice_height: the domain height must be a positive number of m");
  if (!(std::isfinite(cell_size) && cell_size > 0.0))
    throw std::invalid_argument("default_slice_height: the cell size must be a positive number of m");
  // Cell centres: a plane on the domain's top or floor would cut no cell (or ParaView would pick a side).
  const double half = std::min(0.5 * cell_size, 0.5 * size[2]);
  return std::clamp(origin[2] + kAnemometerHeight, origin[2] + half, origin[2] + size[2] - half);
}

}  // namespace fw::viz
