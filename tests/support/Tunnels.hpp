// Small wind tunnels for the tests over MPI ranks: grids whose solids, canopy and trees sit across the cuts
// of every split of up to 4 ranks.
#pragma once

#include <array>
#include <vector>

#include "fluid/GridSpec.hpp"
#include "fluid/WindSettings.hpp"
#include "host/stages/WindGrid.hpp"

namespace fw::test {

/// A wind tunnel with a rotated box and a cylinder in it, 32 x 16 x 8 cells of 1 m from (-4, 2, 0): inflow
/// on the west, outflow on the east, slip sides and lid, a no-slip floor; `scheme`, CFL 0.8, dt at most
/// 0.5 s, ambient wind (6, 1, 0) m/s.
host::WindGridSetup tunnel(fluid::AdvectionScheme scheme);

/// The tunnel with everything a forest's wind has: upwind5, inflow turbulence (a 64 x 32 x 16 box of 0.5 m,
/// seed 5), the tke model, a rough floor (z0 0.1 m, wall stress on a slip floor) and vorticity confinement.
host::WindGridSetup turbulent_tunnel();

/// A channel of 32 x 16 x 8 cells of 1 m, periodic in x and y over a no-slip floor under a slip lid,
/// MacCormack, held at the ambient wind (4, 0, 0) m/s by the mean forcing (the layer mean is a sum over every
/// rank's faces), with a gust travelling through it, Smagorinsky and vorticity confinement (whose cell fields
/// a halo cell across the periodic seam must take from their owner); dt 0.2 s.
host::WindGridSetup periodic_channel();

/// `setup`'s grid cut into `blocks` over `world`, with the halo its advection scheme needs at its CFL number.
host::WindBlocks blocks_of(const host::WindGridSetup& setup, std::array<int, 2> blocks,
                           const host::Communicator& world);

/// A canopy's drag density (1/m, one float a cell): `density` in the cells first .. end - 1, zero elsewhere.
std::vector<float> canopy_in_cells(const fluid::GridSpec& spec, std::array<int, 3> first,
                                   std::array<int, 3> end, float density);

/// A canopy's drag density for a tunnel: 0.3 / m in cells 6-25 x 3-12 x 0-4.
std::vector<float> tunnel_canopy(const fluid::GridSpec& spec);

}  // namespace fw::test
