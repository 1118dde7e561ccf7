// Standard gravity: the one value every tree model uses (a leaf's fall, a bent tree's own weight).
#pragma once

namespace fw::trees {

inline constexpr double kGravity = 9.81;  ///< m/s^2

}  // namespace fw::trees
