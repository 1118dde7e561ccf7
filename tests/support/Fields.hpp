// Helpers for tests that compare device fields with the CPU reference.
#pragma once

#include <array>
#include <cstdint>
#include <random>
#include <vector>

#include "fluid/GridSpec.hpp"
#include "fluid/InflowProfile.hpp"
#include "fluid/ReferenceStages.hpp"
#include "host/runtime/ComputeContext.hpp"
#include "host/stages/FluidStages.hpp"

namespace fw::test {

/// A small grid that exercises every boundary type: inflow west, outflow east, periodic south/north,
/// no-slip ground, slip top; 24 x 16 x 12 cells of 2 m.
fluid::GridSpec mixed_boundary_spec();

/// A grid of 37 x 23 x 11 cells of 2 m, no side a multiple of a work-group's (8 rows; 8 x 16 cells under
/// PoCL's GPU mapping): the items past the arrays in a range rounded up to whole groups must leave them
/// alone. mixed_boundary_spec's boundaries, but slip south and no-slip north (a periodic axis must be even).
fluid::GridSpec ragged_spec();

/// Solid box in the middle of `spec` (about a fifth of each dimension).
std::vector<std::uint8_t> box_solid(const fluid::GridSpec& spec);

/// Ambient (7, 3, 0) m/s with a log profile (z0 = 0.5 m, reference 10 m).
fluid::InflowState test_inflow(const fluid::GridSpec& spec);

/// Uniform random face velocities in [-amplitude, amplitude] m/s.
fluid::MacVelocity random_velocity(const fluid::GridSpec& spec, double amplitude, std::uint32_t seed);
/// A smooth wind: component c is mean[c] m/s plus a long-wave ripple of amplitude ripple[c] m/s (the mean of
/// sines of the face's position, one wavelength across the grid along each axis).
fluid::MacVelocity smooth_velocity(const fluid::GridSpec& spec, const std::array<double, 3>& mean,
                                   const std::array<double, 3>& ripple);
/// The field of known plane moments that the statistics' tests use (fluid/PlaneProfiles, host/stages/
/// PlaneStatistics): u = U0 + G z + C sin(2 pi y / Ly), v = A sin(2 pi x / Lx), w = B sin(2 pi x / Lx), each
/// set on its faces, which lie at the cell centres along the axes it varies in, so that the cell-centred
/// values are exact: <u> = U0 + G z, u_2 = C^2 / 2, v_2 = A^2 / 2, w_2 = B^2 / 2, v_w = A B / 2, u_w = 0 (the
/// sines in x and y average out together), u_3 = w_3 = 0 (a sine's odd moments over whole periods).
struct SineShear {
  static constexpr double U0 = 3.0, G = 0.25, C = 0.8, A = 1.5, B = 0.6;
};
/// That field on `spec` (whole sine periods need an even number of cells along x and y).
fluid::MacVelocity sine_shear_velocity(const fluid::GridSpec& spec);
/// Copies the low face of every periodic axis onto its high twin (the solver keeps them equal; advection's
/// first RK2 stage reads the high face directly while interpolation wraps to the low one).
void match_periodic_faces(const fluid::GridSpec& spec, fluid::MacVelocity& vel);
std::vector<float> random_cells(std::size_t n, double amplitude, std::uint32_t seed);

void upload(host::ComputeContext& cc, const std::vector<float>& host, cl::Buffer& device);
std::vector<float> download(host::ComputeContext& cc, cl::Buffer& device, std::size_t n);
void upload(host::ComputeContext& cc, const fluid::MacVelocity& host, host::DeviceVelocity& device);
/// New device buffers holding `host`.
host::DeviceVelocity upload_velocity(host::ComputeContext& cc, const fluid::MacVelocity& host);
fluid::MacVelocity download(host::ComputeContext& cc, host::DeviceVelocity& device,
                            const fluid::GridSpec& spec);
/// Inflow turbulence for the kernel tests: a small box whose spacing (2.5 m) differs from the test grids'
/// (2 m) and whose offset is not a whole number of points, so that every interpolation weight and the
/// periodic wrap (the grids are longer than the box) are exercised; sigma 1.7 m/s.
void add_small_turbulence(fluid::InflowState& inflow);
cl::Buffer upload_profile(host::ComputeContext& cc, const fluid::InflowState& inflow,
                          const fluid::GridSpec& spec);

/// u at the centre of cell (i, j, k): the mean of its two x faces, m/s.
double u_centre(const fluid::GridSpec& spec, const fluid::MacVelocity& vel, int i, int j, int k);
/// u at the point (i + 1/2, j + 1/2) at height z (m) above the grid's floor: u_centre interpolated linearly
/// in z between cell centres, the lowest and highest centres' below and above them.
double u_at(const fluid::GridSpec& spec, const fluid::MacVelocity& vel, int i, int j, double z);

/// max |a - b| / max(max |b|, floor): the relative error of a against reference b.
double relative_error(const std::vector<float>& a, const std::vector<float>& b, double floor = 1e-30);
double relative_error(const fluid::MacVelocity& a, const fluid::MacVelocity& b);
/// Fraction of entries with |a - b| > tolerance * max|b|.
double mismatch_fraction(const std::vector<float>& a, const std::vector<float>& b, double tolerance);

}  // namespace fw::test
