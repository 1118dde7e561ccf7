// An item of a scenario's obstacles (docs/scenario.md, "obstacles"): a box, cylinder or sphere. Its keys are
// io/schema/ObstacleKeys.hpp's.
//
//   for (const fw::io::Obstacle& obstacle : obstacles)
//     std::visit([&](const auto& shape) { solids.add(shape); }, obstacle);
#pragma once

#include <variant>

#include "fluid/SolidMap.hpp"

namespace fw::io {

/// Shapes the wind grid voxelises (fluid/SolidMap.hpp), with the same parameters.
using Obstacle = std::variant<fluid::SolidBox, fluid::SolidCylinder, fluid::SolidSphere>;

}  // namespace fw::io
