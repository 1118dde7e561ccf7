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
// k_a = 2 pi m_a / P_a, with m_a = -n_a/2 + 1 ... n_a/2 - 1, each k != 0 gets
//   u_hat(k) = sqrt(dK E(k) / (4 pi k^4)) (k x n),   dK = (2 pi)^3 / (P_x P_y P_z),
// n a complex Gaussian vector with <n n^H> = I, and u_hat(-k) = conj(u_hat(k)) so that the field is real.
// Then <u_hat u_hat^H> = Phi(k) dK with the isotropic spectral tensor
//   Phi_ij(k) = E(k) / (4 pi k^2) (delta_ij - k_i k_j / k^2),
// and k . u_hat = 0 exactly: the synthesised field is divergence-free. The k = 0 mode (the mean) is zero,
// and so is every mode on a Nyquist plane (m_a = n_a/2 on any axis): a Nyquist mode is its own partner
// -k, so it could carry only a real amplitude, and its k_a is ambiguous in sign, so neither k x n nor the
// divergence has one meaning there. The field is u(x) = sum over the lattice of u_hat(k) exp(i k . x),
// FFTW's unnormalised complex-to-real transform of the half spectrum.
//
// Normalisation. The lattice holds only part of the spectrum (nothing below the box's fundamental, nothing
// above Nyquist, and a coarse sum near the spectral peak when the box is a few L_u long), so component c is
// scaled by f_c = component_scale[c] sigma / sqrt(V_c), where V_c = sum over the lattice of Phi_cc(k) dK is
// its EXPECTED variance before scaling: a deterministic property of the lattice and the spectrum, not the
// realised variance of this seed, so a seed's own fluctuation (realised_sigma()) is kept. resolved_fraction()
// returns V_c / sigma^2. The variance the lattice cannot hold is thereby put on the modes it has: the
// resolved spectrum, and F_u(0) with the box's integral length, rise by ~1 / resolved_fraction(). The box is
// exactly divergence-free only when the three f_c are equal: equal component scales on a lattice with the
// same number of points on every axis. Otherwise (unequal component_scale, which lets a user ask for sigma_u,
// sigma_v, sigma_w that differ, or a lattice whose V_c differ; 0.87, 0.88, 0.96 for 512 x 128 x 64 points of
// 2 m and L_u = 30 m) the divergence is of relative size |f_a - f_b| / f; the wind grid's pressure projection
// removes it.
//
// Random numbers. One std::mt19937_64 seeded with `seed` and one std::normal_distribution<double> draw, for
// each drawn mode, six numbers: Re n_x, Im n_x, Re n_y, Im n_y, Re n_z, Im n_z (n_c = (a + i b) / sqrt 2).
// Modes are visited in the half spectrum's storage order: z index outermost, then y, then x (0 ... n_x/2),
// indices i_a = m_a mod n_a. Skipped without a draw: k = 0, Nyquist modes, and on the k_x = 0 plane the half
// with m_z < 0 or (m_z = 0 and m_y < 0), which is set to the conjugate of its partner. The same seed gives
// the same box bit for bit on the same build (standard library, FFTW, no FFTW wisdom imported).
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

  /// Throws std::invalid_argument("TurbulenceBox: ...") for a cell count that is odd, below kMinPoints or
  /// whose product exceeds kMaxPoints, a spacing that is not finite and > 0, an
  /// invalid spectrum, or a component scale that is not finite and >= 0.
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

 private:
  TurbulenceBoxSpec spec_;
  std::vector<float> values_;
  std::array<double, 3> realised_sigma_{};
  std::array<double, 3> resolved_fraction_{};
};

}  // namespace fw::fluid
