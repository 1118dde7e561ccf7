// Flux-form upwind advection of the face velocities (solver.advection: upwind5): the interpolation to a flux
// point at fifth, third or first order, and where the order drops beside walls, outflow faces and solids.
//
//   const fluid::UpwindOrders orders = fluid::upwind_orders(spec, solid);  // once per grid
//   const int order = fluid::flux_order(orders[c][face], axis, fluid::FluxSide::upper);
//   const double flux = U * fluid::upwind_interpolation(order, U, values);  // values m-2 .. m+3
//
// Wicker & Skamarock (2002). Each face of component c is the centre of a control volume; along each axis a
// its momentum flux U q crosses the volume's lower and upper sides, which lie halfway between the face and
// its neighbours at -1 and +1 along a. U is the velocity normal to that side (its own component averaged
// from the two faces that meet there); q there comes from the values m-2 .. m+3 along a (m the face below
// the flux point), biased upwind by the sign of U:
//   fifth order: q = (37 (q_m + q_m+1) - 8 (q_m-1 + q_m+2) + (q_m-2 + q_m+3)) / 60
//                    - sign(U) (10 (q_m+1 - q_m) - 5 (q_m+2 - q_m-1) + (q_m+3 - q_m-2)) / 60
//   third order: q = (7 (q_m + q_m+1) - (q_m-1 + q_m+2)) / 12 - sign(U) (3 (q_m+1 - q_m) - (q_m+2 - q_m-1)) /
//   12 first order: q = (q_m + q_m+1) / 2 - sign(U) (q_m+1 - q_m) / 2   (the upwind value)
// The tendency of a face is -(sum over the axes of upper flux - lower flux) / h. A face's upper flux is its
// upper neighbour's lower flux, computed from the same values, so the fluxes telescope: total momentum is
// conserved in a periodic box.
//
// The order of a flux is the highest whose values are all usable: a value is usable when it lies in the
// domain (a periodic axis wraps) or beyond an inflow face (whose ghosts hold the prescribed inflow, the
// profile and the inflow turbulence, FW_PAD layers deep), and is not inside a solid (every cell beside the
// face along c is solid). So the order drops to third, then first, over the last faces before a wall, an
// outflow face or a solid, and stays fifth up to an inflow face; first order always applies, its two values
// being the face and its neighbour (a ghost there by the boundary rules of reference::fetch). At an inflow
// the drop cost the turbulence that enters: with first order over the first cell, eddies of 7 to 10 cells
// kept 0.61 of their variance 10 cells in, with fifth 0.77 (docs/numerics.md, "Where the inflow's intensity
// went").
#pragma once

#include <array>
#include <cstdint>
#include <vector>

#include "fluid/GridSpec.hpp"
#include "kernels/shared_types.h"

namespace fw::fluid {

/// Per component, one uint16 a face (the component's face order, x fastest): the order code
/// (FW_UPWIND_FIRST, _THIRD, _FIFTH) of its lower and upper flux along each axis, at FW_UPWIND_SHIFT.
using UpwindOrders = std::array<std::vector<std::uint16_t>, 3>;

enum class FluxSide { lower = 0, upper = 1 };

/// The orders of every face's fluxes on `spec` with `solid` (one byte a cell, non-zero solid; empty: none).
/// Throws std::invalid_argument when solid has the wrong size.
UpwindOrders upwind_orders(const GridSpec& spec, const std::vector<std::uint8_t>& solid);

/// The order code of one flux from a face's packed orders.
inline int flux_order(std::uint16_t packed, int axis, FluxSide side) {
  return (packed >> FW_UPWIND_SHIFT(axis, static_cast<int>(side))) & FW_UPWIND_BITS;
}

/// q at the flux point between values[2] and values[3] (values: q_m-2 .. q_m+3), upwind-biased by the sign
/// of the normal velocity U, at the order of `order_code` (the formulas above; values[0], [1], [4], [5]
/// unused at first order, [0] and [5] at third).
double upwind_interpolation(int order_code, double normal_velocity, const std::array<double, 6>& values);

}  // namespace fw::fluid
