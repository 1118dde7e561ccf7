#include "trees/StandDensity.hpp"

#include <fmt/format.h>

#include <cmath>
#include <stdexcept>

namespace fw::trees {

bool StandDensity::forest_like() const {
  const double lai = leaf_area_index();
  return lai >= kForestLeafAreaIndexLow && lai <= kForestLeafAreaIndexHigh;
}

double crown_leaf_area_index(double stand_lai, double ground_area, double crown_area,
                             std::span<const PlacedTree> trees) {
  if (!(stand_lai > 0.0) || !(stand_lai <= StandDensity::kMaxLeafAreaIndex))
    throw std::invalid_argument(
        fmt::format("StandDensity: a stand's leaf area index must lie in (0, {}], got {}",
                    StandDensity::kMaxLeafAreaIndex, stand_lai));
  if (!(ground_area > 0.0) || !std::isfinite(ground_area))
    throw std::invalid_argument(
        fmt::format("StandDensity: the ground area must be finite and > 0, got {}", ground_area));
  if (trees.empty()) throw std::invalid_argument("StandDensity: a stand without trees carries no leaves");
  if (!(crown_area > 0.0) || !std::isfinite(crown_area))
    throw std::invalid_argument(fmt::format(
        "StandDensity: the crown has no horizontal extent (crown area {} m^2), so it carries no leaves",
        crown_area));
  double scale_squared = 0.0;
  for (const PlacedTree& tree : trees) scale_squared += tree.scale * tree.scale;
  return stand_lai * ground_area / (crown_area * scale_squared);
}

}  // namespace fw::trees
