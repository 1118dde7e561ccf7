// A periodic box of synthetic isotropic turbulence with the von Karman spectrum
// (fluid/TurbulenceSpectrum.hpp), synthesised in the Fourier domain with FFTW, deterministic from a seed: the
// inflow turbulence that the wind grid sweeps through its inflow plane by Taylor's hypothesis
// (docs/design.md, "Turbulence").
//
//   fw::fluid::TurbulenceBoxSpec spec;
//   spec.cells = {512, 128, 64};          // points along x, y, z, each even and >= 4
//   spec.spacing = 2.0;                   // m
//   spec.spectrum = {/*sigma=*/2.4, /*integral_length=*/30.0};
//   spec.seed = 7;
//   fw::fluid::TurbulenceBox box(spec);   // throws std::invalid_argument("TurbulenceBox: ...")
//   queue.enqueueWriteBuffer(buf, CL_TRUE, 0, box.values().size() * sizeof(float), box.values().data());
//   auto [u, v, w] = box.sample(x - mean_speed * t, y, z);   // m/s: periodic, trilinear (Taylor)
//
// Math. The box has n_a points along axis a at spacing h (period P_a = n_a h). On its wavevector lattice
// k_a = 2 pi m_a / P_a, with m_a = -n_a/2 + 1 ... n_a/2 - 1, each k != 0 up to the shortest wavelength
// (|k| <= 2 pi / shortest_wavelength, when one is given) and, when the box has a sweep axis, off the plane
// k_sweep = 0 (see sweep_axis), gets
//   u_hat(k) = a(k) k x (D n),   a(k) = sqrt(dK E(k) / (4 pi k^4)),   dK = (2 pi)^3 / (P_x P_y P_z),
// n a complex Gaussian vector with <n n^H> = I, D = diag(d_x, d_y, d_z) (below), and u_hat(-k) =
// conj(u_hat(k)) so that the field is real. With D = I, <u_hat u_hat^H> = Phi(k) dK with the isotropic
// spectral tensor
//   Phi_ij(k) = E(k) / (4 pi k^2) (delta_ij - k_i k_j / k^2);
// whatever D, u_hat is the curl of a vector potential, k . u_hat = 0 exactly: the synthesised field is
// divergence-free. The k = 0 mode (the mean) is zero, and so is every mode on a Nyquist plane (m_a = n_a/2
// on any axis): a Nyquist mode is its own partner -k, so it could carry only a real amplitude, and its k_a
// is ambiguous in sign, so neither k x n nor the divergence has one meaning there. The field is u(x) = sum
// over the lattice of u_hat(k) exp(i k . x), FFTW's unnormalised complex-to-real transform of the half
// spectrum.
//
// Normalisation. The lattice holds only part of the spectrum (nothing below the box's fundamental, nothing
// above Nyquist or the shortest wavelength, nothing on the sweep's still plane, and a coarse sum near the
// spectral peak when the box is a few L_u long), and not the same part for each component: the expected
// variance of component c with D = I,
//   V_c = sum over the lattice of Phi_cc(k) dK = S_a + S_b   (a, b the other two axes),
//   S_a = sum over the lattice of a(k)^2 k_a^2,
// differs between components when the axes differ in length (0.75, 0.97, 0.97 for 1152 x 64 x 64 points of
// 1 m and L_u = 18 m: the short axes' coarse k_y and k_z miss the transverse wavenumbers near the peak that
// u's variance comes from). resolved_fraction() returns V_c / sigma^2. With D, component c's expected
// variance is sum over b != c of d_b^2 S_a (a the third axis): three linear equations in d^2, which with
// every variance sigma^2 give
//   d_a^2 = sigma^2 (S_b + S_c - S_a) / (2 S_b S_c)   (b, c the other two axes),
// so that each component's expected variance on this lattice is sigma^2 and the box stays divergence-free.
// That needs S_a < S_b + S_c for every axis (equivalently 3 V_c > V_a + V_b), which fails only for a narrow
// tube along one axis: 1152 x 64 x 64 points of 1 m with L_u = 18 m (3.6 L_u across) passes, 2048 x 32 x 32
// (1.8 L_u across) does not. Where it fails (weights_balanced() false), D = I and component c is scaled by
// sigma / sqrt(V_c) instead, which leaves a divergence of relative size |f_a - f_b| / f (f_c = 1 / sqrt(V_c))
// that the wind grid's pressure projection removes. Either way the expected variance is a deterministic
// property of the lattice and the spectrum, not the realised variance of this seed, so a seed's own
// fluctuation (realised_sigma()) is kept. The variance the lattice cannot hold is thereby put on the modes it
// has: the resolved spectrum, and F_u(0) with the box's integral length, rise by ~1 / resolved_fraction().
// component_scale multiplies the components afterwards; unequal scales (which let a user ask for sigma_u,
// sigma_v, sigma_w that differ) leave a divergence of relative size |s_a - s_b| / s that the projection
// removes.
//
// Random numbers. One std::mt19937_64 seeded with `seed` and one std::normal_distribution<double> draw, for
// each drawn mode, six numbers: Re n_x, Im n_x, Re n_y, Im n_y, Re n_z, Im n_z (n_c = (a + i b) / sqrt 2).
// Modes are visited in the half spectrum's storage order: z index outermost, then y, then x (0 ... n_x/2),
// indices i_a = m_a mod n_a. Skipped without a draw: k = 0, Nyquist modes, and on the k_x = 0 plane the half
// with m_z < 0 or (m_z = 0 and m_y < 0), which is set to the conjugate of its partner. A mode shorter than
// shortest_wavelength, or on the sweep's still plane, is drawn and left at zero, so that every other mode
// keeps the draws it has without the cut: a box with a shortest wavelength is the same box low-passed and
// scaled (up to the small change the cut makes to the weights d_a). The same seed gives the same box bit for
// bit on the same build (standard library, FFTW, no FFTW wisdom imported).
//
// Storage. Point (i, j, k) is at (i, j, k) h (m), x fastest; values() interleaves 3 floats per point (u, v,
// w, m/s): index 3 (i + n_x (j + n_y k)) + c, ready to upload to an OpenCL buffer as-is.
//
// Threads. Construction calls FFTW's planner, which is not thread-safe; a mutex serialises this class's
// planner calls, but other FFTW users in the process must not plan at the same time. A built box is
// immutable and safe to read from any thread.
#pragma once

#include <array>
#include <cstddef>
#include <cstdint>
#include <limits>
#include <vector>

#include "fluid/TurbulenceSpectrum.hpp"

namespace fw::fluid {

/// The wind grid's inflow box has this many points per grid cell along each axis, h / 2 apart for cells of
/// h: every face of an inflow plane (at whole cells along its normal, half cells across) then sits on a box
/// point, and the plane carries the box's values without interpolation. The scenario's wind.turbulence box
/// counts cells; the box it becomes (host/app/plan/TurbulencePlan.cpp) has this many times as many points
/// along each axis.
inline constexpr int kTurbulencePointsPerCell = 2;

/// The inflow box holds no wavelength under this many cells of the wind grid (nor under the unresolved
/// forcing's cutoff_cells, where that is longer: the trees get those eddies from Stam's forcing). The grid
/// cannot carry shorter eddies; it damps them within a few cells, and the box's points every h / 2 reach
/// wavelengths of one cell, which the grid aliases. A box of L_u = 9 cells under upwind5 lost 10.6% of
/// sigma_u within 10 cells of the inflow uncut, 7.5% cut at 2 cells, 4.0% at 4 and 3.4% at 6
/// (docs/numerics.md, "Where the inflow's intensity went"); 4 gains nearly all of it and puts less of the
/// variance cut away on the long waves (the integral length rises with it, header comment).
inline constexpr double kInflowShortestWavelengthCells = 4.0;

struct TurbulenceBoxSpec {
  /// The fewest points along an axis: the smallest even count with a mode that is neither k = 0 nor Nyquist.
  static constexpr int kMinPoints = 4;
  /// The most points in all: values() holds 3 floats a point, and the wind grid's kernels index buffers
  /// with a 32-bit int.
  static constexpr std::size_t kMaxPoints = std::size_t(std::numeric_limits<int>::max()) / 3;

  std::array<int, 3> cells{0, 0, 0};               ///< points along x, y, z; each even and >= kMinPoints
  double spacing = 0.0;                            ///< h, distance between points, m (> 0)
  VonKarmanSpectrum spectrum;                      ///< sigma (m/s) and L_u (m) of the isotropic turbulence
  std::array<double, 3> component_scale{1, 1, 1};  ///< multiplies u, v, w after normalisation (>= 0)
  std::uint64_t seed = 0;
  /// m: the box holds no mode of a shorter wavelength (|k| > 2 pi / shortest_wavelength), and its sigma is
  /// put on the longer ones (header comment). 0: every mode up to the lattice's Nyquist wavenumber.
  double shortest_wavelength = 0.0;
  /// The axis the box is swept along past a fixed point (0, 1, 2), or -1. Its modes with k_a = 0 are
  /// constant along the sweep: they would stand still at every point, a steady pattern of streaks and
  /// vortices in the mean wind rather than turbulence, and a point's record as the box passes would carry
  /// only sigma^2 - 2 L_u sigma^2 / P_a of the variance (a quarter for a box 8 L_u long). They are left out,
  /// and sigma is put on the others (header comment), so that the variance a point sees is sigma^2.
  int sweep_axis = -1;

  /// Throws std::invalid_argument("TurbulenceBox: ...") for a cell count that is odd, below kMinPoints or
  /// whose product exceeds kMaxPoints, a spacing that is not finite and > 0, an invalid spectrum, a
  /// component scale that is not finite and >= 0, a shortest wavelength that is not finite and >= 0, or a
  /// sweep axis other than -1, 0, 1, 2.
  void validate() const;
  std::size_t point_count() const { return std::size_t(cells[0]) * cells[1] * cells[2]; }
  /// The period along each axis, n_a h, m.
  std::array<double, 3> period() const {
    return {cells[0] * spacing, cells[1] * spacing, cells[2] * spacing};
  }
};

class TurbulenceBox {
 public:
  /// Synthesises the box (header comment). Throws std::invalid_argument("TurbulenceBox: ...") for an
  /// invalid spec, or one whose lattice holds none of the spectrum (V_c not finite and > 0).
  explicit TurbulenceBox(const TurbulenceBoxSpec& spec);

  const TurbulenceBoxSpec& spec() const { return spec_; }
  const std::array<int, 3>& cells() const { return spec_.cells; }
  double spacing() const { return spec_.spacing; }
  std::array<double, 3> period() const { return spec_.period(); }
  /// 3 floats per point (u, v, w, m/s), x fastest (header comment).
  const std::vector<float>& values() const { return values_; }

  /// (u, v, w) at point (i, j, k), m/s; 0 <= i < n_x and so on, else std::invalid_argument.
  std::array<double, 3> at(int i, int j, int k) const;
  /// (u, v, w) at a position in metres, m/s: trilinear between the 8 surrounding points, periodic in all
  /// three axes, so any finite position is valid (a non-finite one throws std::invalid_argument).
  std::array<double, 3> sample(double x, double y, double z) const;

  /// Standard deviation of u, v and w over the box's points, m/s.
  std::array<double, 3> realised_sigma() const { return realised_sigma_; }
  /// V_c / sigma^2: the expected fraction of each component's variance that the lattice holds before
  /// normalisation (header comment). The part above Nyquist falls only as (pi L / h)^(-2/3), so this stays
  /// well below 1: ~0.80 at L_u = 4 h, 0.86 at 8 h, 0.91 at 16 h for a box many L_u long.
  std::array<double, 3> resolved_fraction() const { return resolved_fraction_; }
  /// Whether the vector potential's weights D gave every component sigma and kept the box divergence-free
  /// (header comment); false where the lattice is too lopsided for them, and the components were scaled
  /// one by one instead.
  bool weights_balanced() const { return weights_balanced_; }

 private:
  TurbulenceBoxSpec spec_;
  std::vector<float> values_;
  std::array<double, 3> realised_sigma_{};
  std::array<double, 3> resolved_fraction_{};
  bool weights_balanced_ = false;
};

/// The unit-sigma box that the wind grid sweeps through its inflow faces (host/app/plan/TurbulencePlan.cpp
/// builds a run's with it): box_cells cells of h (m) along x, y, z with kTurbulencePointsPerCell points
/// per cell, the von Karman spectrum of integral length length_scale (m), no wavelength under
/// max(kInflowShortestWavelengthCells, cutoff_cells) cells, the still plane of sweep_axis (the axis the
/// ambient wind sweeps it along, -1: none) left out, and `seed`.
TurbulenceBoxSpec inflow_box_spec(const std::array<int, 3>& box_cells, double h, double length_scale,
                                  double cutoff_cells, int sweep_axis, std::uint64_t seed);

}  // namespace fw::fluid
