// Where the pictures cut the wind by default: the anemometer height, 10 m above the ground (the WMO's
// standard height for surface wind), used by `forestwind render` and by view.py alike.
//
//   double z = fw::viz::default_slice_height({0, 0, 0}, {400, 240, 60}, 2.0);   // 10 m
#pragma once

#include <array>

namespace fw::viz {

/// The standard height of a wind measurement above the ground, m.
constexpr double kAnemometerHeight = 10.0;

/// The anemometer height: 10 m above the domain floor, clamped into the domain's cell centres (origin z +
/// cell_size/2 .. top - cell_size/2), m. Throws std::invalid_argument("default_slice_height: ...") for a
/// non-positive or non-finite size or cell size.
double default_slice_height(const std::array<double, 3>& origin, const std::array<double, 3>& size,
                            double cell_size);

}  // namespace fw::viz
