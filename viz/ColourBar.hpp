// A vertical colour bar: the map from lo (bottom) to hi (top), round-numbered ticks, and its title (the
// field and its unit) above it.
//
//   fw::viz::draw_colour_bar(canvas, {1100, 80, 22, 320}, fw::viz::ColourMap::named("wind"), 0.0, 22.0,
//                            "speed (m/s)");
#pragma once

#include <string>

#include "viz/Camera.hpp"
#include "viz/Canvas.hpp"
#include "viz/ColourMap.hpp"

namespace fw::viz {

/// bar: the bar's own rectangle, px; ticks and labels go to its right, the title above. hi > lo.
void draw_colour_bar(Canvas& canvas, const Viewport& bar, const ColourMap& map, double lo, double hi,
                     const std::string& title);

}  // namespace fw::viz
