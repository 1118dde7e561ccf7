// The three-dimensional energy spectrum of a velocity field on a periodic cube, by FFTW: how the kinetic
// energy spreads over the eddy sizes (decaying isotropic turbulence, the advection schemes' resolution).
//
//   fw::fluid::MacVelocity vel = wind.download_velocity();      // a periodic n x n x n grid
//   std::vector<double> E = fw::fluid::shell_energy_spectrum(spec, vel);
//   // E[m - 1]: the energy (m^2/s^2) of the eddies of wavelength n / m cells, m = 1 .. n / 2
//
// Math. Each component is transformed on its own face lattice (n points along every axis: a periodic
// axis' high twin left out), which is a uniform lattice shifted by half a cell along two axes: the shift
// changes only the phases, so no interpolation to cell centres damps the small eddies. With
// u_hat(k) = sum over the N = n^3 points of u(x) exp(-i k . x), the energy of wavevector k is
// |u_hat|^2 / (2 N^2) summed over the components, and shell m collects the k whose integer index
// length |m_vec| rounds to m. By Parseval the shells m = 1 .. n/2 hold the field's mean kinetic energy
// (u^2 + v^2 + w^2) / 2 less that of the mean flow and of the wavevectors beyond n / 2 (the cube's corners).
#pragma once

#include <vector>

#include "fluid/GridSpec.hpp"
#include "fluid/MacVelocity.hpp"

namespace fw::fluid {

/// E per shell m = 1 .. n/2 (index m - 1), m^2/s^2. Throws std::invalid_argument unless spec is a
/// periodic cube with an even n >= 4 and vel fits it.
std::vector<double> shell_energy_spectrum(const GridSpec& spec, const MacVelocity& vel);

}  // namespace fw::fluid
