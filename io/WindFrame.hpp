// One output frame of the wind grid on the host, cell-centred, and the derived fields the writers need.
//
//   fw::fluid::MacVelocity vel = ...;                     // face velocities read back from the device
//   fw::io::WindFrame frame = fw::io::make_wind_frame(spec, vel, pressure, solid, canopy, t, step);
//   std::vector<float> s = fw::io::wind_speed(frame);     // |velocity| per cell, m/s
//   std::vector<float> w = fw::io::wind_vorticity(frame); // curl per cell, 3 floats, 1/s
//   auto at_mast = fw::io::sample_velocity(spec, vel, {40.0, 120.0, 10.0});   // m/s at a world point
//
// Layout: every per-cell array is x-fastest, index = i + nx * (j + ny * k); three-component arrays are
// interleaved per cell (x, y, z of cell 0, then of cell 1, ...). Cell (i,j,k) spans
// origin + h * [i, i+1] x [j, j+1] x [k, k+1] (m); its centre is origin + h * (i+1/2, j+1/2, k+1/2).
#pragma once

#include "fluid/GridSpec.hpp"
#include "fluid/MacVelocity.hpp"
#include "io/settings/SiteSettings.hpp"

#include <array>
#include <cstddef>
#include <cstdint>
#include <vector>

namespace fw::io {

struct WindFrame {
  std::array<int, 3> dims{0, 0, 0};       ///< cells nx, ny, nz
  double h = 0.0;                         ///< cell size, m
  std::array<double, 3> origin{0, 0, 0};  ///< minimum corner of the domain, m
  double time = 0.0;                      ///< simulated time, s
  long step = 0;                          ///< solver step that produced the frame
  /// Whether the frame wraps along each axis, its last cell the neighbour of its first: a periodic axis
  /// that the frame spans whole (an MPI rank's block, cut along a periodic axis, has the neighbours there
  /// in its halo instead).
  std::array<bool, 3> periodic{false, false, false};

  std::vector<float> velocity;        ///< 3 per cell, m/s: mean of the cell's two faces per axis
  std::vector<float> pressure;        ///< 1 per cell, kinematic p/rho, m^2/s^2; may be empty
  std::vector<std::uint8_t> solid;    ///< 1 per cell, nonzero = solid (obstacle, terrain); may be empty
  std::vector<float> canopy_density;  ///< 1 per cell, frontal area density a, 1/m; may be empty
  /// The run's site, written with the frame (io/SiteVtk.hpp, the VDB metadata); null without one. Not owned:
  /// the writer's.
  const SiteSettings* site = nullptr;

  std::size_t cell_count() const { return std::size_t(dims[0]) * dims[1] * dims[2]; }
  std::size_t cell_index(int i, int j, int k) const {
    return std::size_t(i) + std::size_t(dims[0]) * (std::size_t(j) + std::size_t(dims[1]) * k);
  }
  bool is_solid(std::size_t cell) const { return !solid.empty() && solid[cell] != 0; }

  /// Throws std::invalid_argument("WindFrame: ...") for non-positive dims or h, a velocity array that is not
  /// 3 * cell_count(), or an optional array that is neither empty nor cell_count() long.
  void validate() const;
};

/// The cell-centred velocity of a MAC grid: 3 floats per cell, each the mean of the component's two faces
/// bounding the cell along its own axis (exact for a field linear along that axis). m/s.
/// Throws std::invalid_argument if an array of `vel` does not have the size `spec` implies.
std::vector<float> cell_centred_velocity(const fluid::GridSpec& spec, const fluid::MacVelocity& vel);

/// Builds a frame: cell-centred velocity from `vel`, the optional per-cell arrays moved in (each empty or
/// spec.cell_count() long, else std::invalid_argument), and the grid's size, placement and periodic axes
/// from `spec`.
WindFrame make_wind_frame(const fluid::GridSpec& spec, const fluid::MacVelocity& vel,
                          std::vector<float> pressure, std::vector<std::uint8_t> solid,
                          std::vector<float> canopy_density, double time, long step);

/// |velocity| per cell, m/s.
std::vector<float> wind_speed(const WindFrame& frame);

/// Vorticity curl(velocity) per cell, 3 floats (wx, wy, wz), 1/s. Derivatives are central differences of
/// the cell-centred velocity over 2h, wrapped along a periodic axis (frame.periodic) and one-sided over h
/// in the first and last cell of any other axis (0 along an axis one cell thick). Solid cells are not treated
/// specially: they hold whatever velocity the frame has.
std::vector<float> wind_vorticity(const WindFrame& frame);

/// Velocity at a world position (m) by trilinear interpolation of each component on its own staggered
/// lattice (u at x-faces, v at y-faces, w at z-faces), m/s. Positions outside a lattice are clamped onto
/// it, so outside the domain (or within half a cell of a wall, for the tangential components) the value of
/// the nearest sample is repeated. Exact for a linear field inside the lattice. Throws std::invalid_argument
/// for a non-finite position or arrays of the wrong size.
std::array<float, 3> sample_velocity(const fluid::GridSpec& spec, const fluid::MacVelocity& vel,
                                     const std::array<double, 3>& world_position);

}  // namespace fw::io
