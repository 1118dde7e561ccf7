// The pressure equation's cell masks on the fine grid and on every multigrid level.
//
//   auto levels = fw::fluid::build_pressure_levels(spec, solid_cells);   // levels[0] is the fine grid
//
// A mask byte holds FW_MASK_FLUID and one "open" bit per face (kernels/shared_types.h). The Poisson
// operator on cell c is  (A p)_c = popcount(open) * p_c - sum over open faces of p_neighbour,
// where the neighbour across an outflow face is a ghost with p = 0 and a periodic face wraps.
//
// Coarsening halves every axis longer than one cell (rounding up). A coarse cell is fluid if any of its
// children is; its face is open if a fluid child on that side has the face open. Coarsening stops at a
// level where a periodic axis would get an odd cell count above 1 (an even count keeps the red-black
// colouring a true two-colouring across the seam), or once the level has at most `coarsest_cells` cells.
#pragma once

#include <array>
#include <cstdint>
#include <vector>

#include "fluid/GridSpec.hpp"

namespace fw::fluid {

struct PressureLevel {
  int nx = 0, ny = 0, nz = 0;
  std::vector<std::uint8_t> mask;  // nx*ny*nz, x-fastest
  std::size_t cell_count() const { return std::size_t(nx) * ny * nz; }
};

/// Mask of the fine grid. `solid` holds one byte per cell (non-zero: solid), or is empty for no solids.
PressureLevel build_fine_pressure_level(const GridSpec& spec, const std::vector<std::uint8_t>& solid);

/// One coarser level of `fine` (see the header comment for the rules).
PressureLevel coarsen_pressure_level(const PressureLevel& fine, const GridSpec& spec);

/// Fine level first, then coarser levels until the stopping rule holds.
std::vector<PressureLevel> build_pressure_levels(const GridSpec& spec, const std::vector<std::uint8_t>& solid,
                                                 std::size_t coarsest_cells = 512);

/// The cells along x, y and z of each level build_pressure_levels(spec, any solid, coarsest_cells) makes: the
/// hierarchy's shape depends on the grid alone, so its memory is known before the solids are.
std::vector<std::array<int, 3>> pressure_level_extents(const GridSpec& spec,
                                                       std::size_t coarsest_cells = 512);

/// True if the level can be halved again without breaking the periodic even-count rule.
bool can_coarsen(const PressureLevel& level, const GridSpec& spec);

}  // namespace fw::fluid
