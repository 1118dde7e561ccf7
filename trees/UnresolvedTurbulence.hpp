// Per-tree stochastic modal forcing for the turbulence the wind grid cannot resolve (docs/design.md,
// "Numerics: Trees: Unresolved turbulence (Stam 1997)"): one shared periodic series of unit-intensity
// velocity fluctuations in travelled air distance, synthesised in the frequency domain, which every tree
// reads at its own offsets while its travelled distance grows with the local wind speed.
//
//   fw::trees::UnresolvedTurbulenceSettings s;
//   s.cell_size = 2.0;            // the wind grid's h, m
//   s.intensity = 0.15;           // sigma_u / U of the scenario
//   s.integral_length = 60.0;     // L_u, m
//   fw::trees::UnresolvedTurbulence series(s);          // validates, throws std::invalid_argument
//   std::vector<int> offsets = series.offsets(forest);   // per flat wind sample, in series points
//   fw::trees::TreeTravel travel(forest.instance_count());   // X_k and the last step's distance, m
//   // each step (trees/ForestReference.hpp):
//   //   f = ref.modal_forces(wind) + ref.unresolved_modal_forces(wind, travel, series, offsets,
//   s.intensity);
//   //   ref.step(q, qdot, f, dt, ...);
//   //   ref.advance_travelled(travel, wind, dt);
//   double var_q = series.response_variance(omega, zeta, mean_wind, projections, s.intensity);
//
// Model (decisions, and why):
// - Cutoff. The grid resolves eddies down to about cutoff_cells cells, so the unresolved part of the spectrum
//   is the wavenumbers k1 > k_c = 2 pi / (cutoff_cells h) (rad/m).
// - Series. Three dimensionless components xi_l (longitudinal), xi_t1, xi_t2 (transverse) of N points
//   (a power of two) at spacing dx (m), periodic with period P = N dx, of unit intensity: their one-sided
//   wavenumber spectra are F_u(k1) / U^2 and F_v(k1) / U^2 of the von Karman model
//   (fluid/TurbulenceSpectrum.hpp) with sigma / U = 1 and length L_u, i.e. VonKarmanSpectrum{1, L_u} read in
//   m, and zero for k1 <= k_c. Synthesis as in Stam 1997 (sections 5-6): white noise filtered by the
//   spectrum, then an inverse FFT, with bins k_p = 2 pi p / P (dk = 2 pi / P). Each bin belongs to one
//   component alone, c = p mod 3, and gets the deterministic amplitude a_p = sqrt(2 F_c(k_p) 3 dk) (it stands
//   for a width of 3 dk) and a phase uniform in [0, 2 pi) (unit-modulus white noise): xi_c(x) = sum_{p = c
//   mod 3} a_p cos(k_p x + phase_p). Deterministic amplitudes make every realisation's spectrum exactly the
//   model's, and disjoint bins make the components exactly uncorrelated, bin by bin: so the spectrum of any
//   force built from them at one point (delta f mixes all three) is exactly the model's too, for any seed,
//   and the response variance of a lightly damped mode, which the bins near its resonance set, does not
//   scatter from seed to seed. (With all three components on every bin, their random relative phases put
//   cross terms into each force bin: 2-8% scatter at 0.5 Hz.) The price is a line spacing of 3 dk per
//   component, 3 U / P = 9 mHz at 10 m/s for P = 3.3 km, far below the half-width zeta f of any mode resonant
//   above the cutoff frequency U / (cutoff_cells h): their ratio 3 cutoff_cells h / (zeta P) is 0.07 for h =
//   2 m, zeta = 0.05. Bins 0 (the mean) and N/2 (a real-only bin, which cannot take a random phase) are left
//   out. The series holds k1 < k_N = pi / dx only; in a wind U it carries frequencies up to f_max = U / (2
//   dx), so dx must make f_max exceed the highest mode of interest at the lowest wind speed of interest.
//   Phases come from std::mt19937_64(seed), one per interior bin in bin order, drawn for every bin, so moving
//   the cutoff keeps the phases of the bins that stay. FFTW plans with FFTW_ESTIMATE, which gives the same
//   rounding on every run.
// - Offsets. Tree k's wind sample s reads the series at (the window ending at) x = X_k + dx o_{k,s}, o an
//   integer number of series points in [0, N) from a hash of (seed, k, s): any (tree, sample) is drawn on its
//   own, so adding trees shifts no other tree's offsets. Uniform draws are typically ~P/3 apart, far beyond
//   L_u and far beyond the correlation length of the high-passed series (~ cutoff_cells h), so trees and
//   samples are effectively independent; with D draws about D^2 l / P pairs (l that correlation length) lie
//   close and share some forcing, which is harmless for a forest's statistics.
// - Travel. X_k(t) = integral of |v_k| dt, |v_k| the speed at tree k's first sample, advanced every step
//   (Taylor's hypothesis per tree: the frequency content follows the local wind speed).
// - Read window (anti-aliasing). A step holds the force for dt, so the wind is sampled at 1/dt, while the
//   series carries up to f_max = U / (2 dx), far above 1 / (2 dt) in a run (100 Hz against 25 Hz at 10 m/s,
//   dt = 0.02 s). A point read folds that band onto the trees' resonances: a 0.5 Hz mode (zeta 0.05, U
//   10 m/s, h 2 m) took 128x the model's variance at dt = 0.02 s and 600x at 0.04 s. So each step reads xi
//   as the series' mean over the air that passed the tree in the previous step, the window [x - W, x],
//   W = clamp(|v| dt of that step, dx, P): a box filter (sinc(k W / 2 pi)) whose zeros sit on the step
//   rate's multiples, and which never shrinks below one point spacing, so that it also stops the linear
//   interpolation's own aliasing (about +20% at 0.5 Hz for point reads 0.8 dx apart). The previous step's
//   distance, because the load runs before dt is known: a one-step lag of a random forcing, which changes
//   nothing of its statistics. The mean comes from the series' running integral, periodic because the
//   series has no mean.
// - Fluctuation. At sample s with wind v_s: v'_s = intensity |v_s| (xi_l e_par + xi_t1 e_h + xi_t2 e_v),
//   e_par = v_s / |v_s|, e_h the horizontal unit vector normal to it (z x e_par, normalised; x when the wind
//   is vertical), e_v = e_par x e_h. intensity = sigma_u / U of the scenario.
// - Force. Linearised drag, d(|v| v) = |v| dv + v (v . dv) / |v|:
//   delta f_i = sum_s [|v_s| v'_s + v_s (v_s . v'_s) / |v_s|] . (s^1/2 R p_i^s), N / kg^1/2, the projections
//   of the resolved force f_i = sum_s |v_s| v_s . (s^1/2 R p_i^s); zero where |v_s| = 0. With the
//   fluctuation above this is intensity |v_s|^2 (2 xi_l e_par + xi_t1 e_h + xi_t2 e_v) . g_s, g_s = s^1/2 R
//   p_i^s.
// - Analytic check. For one mode q'' + 2 zeta omega q' + omega^2 q = delta f in steady winds V_s:
//   S_f(f) = intensity^2 sum_s |V_s|^4 [4 (g_s . e_par)^2 S_l(f) + ((g_s . e_h)^2 + (g_s . e_v)^2) S_t(f)],
//   S_c(f) = (2 pi / U_0) F_c(2 pi f / U_0) the series' one-sided frequency spectrum at the tree's travel
//   speed U_0 = |V_0| (every sample of a tree advances with its first sample's speed), samples independent;
//   and sigma_q^2 = integral of |H(f)|^2 S_f(f) df, H = 1 / (omega^2 - (2 pi f)^2 + i 2 zeta omega 2 pi f),
//   over the band the series carries, U_0 k_c / (2 pi) < f < U_0 k_N / (2 pi). Given a read window W, S_c
//   also carries the box filter's sinc^2(k W / 2 pi), k = 2 pi f / U_0, which costs a mode of frequency f
//   about (pi f W / U_0)^2 / 3 of its variance.
#pragma once

#include <Eigen/Core>

#include <cstdint>
#include <vector>

#include "fluid/TurbulenceSpectrum.hpp"
#include "trees/Forest.hpp"

namespace fw::trees {

/// Per tree k of a forest: the travelled distance X_k and the distance travelled in the last step (the next
/// read's window), m.
struct TreeTravel {
  Eigen::VectorXd distance, last_step;
  TreeTravel() = default;
  explicit TreeTravel(int trees)
      : distance(Eigen::VectorXd::Zero(trees)), last_step(Eigen::VectorXd::Zero(trees)) {}
};

struct UnresolvedTurbulenceSettings {
  bool enabled = false;           ///< whether a run adds the forcing (the series itself ignores it)
  double cutoff_cells = 2.0;      ///< the smallest eddy the grid resolves, in cells (> 0)
  double cell_size = 1.0;         ///< h, the wind grid's cell size, m (> 0)
  double intensity = 0.1;         ///< sigma_u / U of the scenario (>= 0)
  double integral_length = 60.0;  ///< L_u of the von Karman spectrum, m (> 0)
  int series_length = 1 << 16;    ///< N, points of the series: a power of two, 4 .. 2^24
  double series_spacing = 0.05;   ///< dx, m: f_max = U / (2 dx), 100 Hz at 10 m/s
  std::uint64_t seed = 1;         ///< phases and offsets

  /// Throws std::invalid_argument("UnresolvedTurbulence: ...") for a value outside the ranges above, or a
  /// cutoff k_c at or above the series' Nyquist wavenumber pi / dx (the series would be zero).
  void validate() const;
  /// k_c = 2 pi / (cutoff_cells h), rad/m.
  double cutoff_wavenumber() const;
  /// VonKarmanSpectrum{1, L_u}: its F_u, F_v (m) are the unit-intensity spectra F / U^2.
  fluid::VonKarmanSpectrum spectrum() const;
};

class UnresolvedTurbulence {
 public:
  static constexpr int kLongitudinal = 0;          ///< xi_l, along the wind
  static constexpr int kTransverseHorizontal = 1;  ///< xi_t1, along e_h
  static constexpr int kTransverseVertical = 2;    ///< xi_t2, along e_v
  static constexpr int kComponents = 3;

  /// Synthesises the series (header comment). Throws std::invalid_argument("UnresolvedTurbulence: ...")
  /// through settings.validate().
  explicit UnresolvedTurbulence(const UnresolvedTurbulenceSettings& settings);

  const UnresolvedTurbulenceSettings& settings() const { return settings_; }
  int length() const { return settings_.series_length; }                      ///< N
  double spacing() const { return settings_.series_spacing; }                 ///< dx, m
  double period() const { return length() * spacing(); }                      ///< P = N dx, m
  double cutoff_wavenumber() const { return settings_.cutoff_wavenumber(); }  ///< k_c, rad/m
  double nyquist_wavenumber() const;                                          ///< k_N = pi / dx, rad/m
  /// f_max = U / (2 dx), Hz: the highest frequency the series carries in a wind of `speed` m/s.
  double max_frequency(double speed) const;

  /// The series' points, N by 3 (columns l, t1, t2), dimensionless; point n sits at x = n dx.
  const Eigen::MatrixX3d& values() const { return values_; }
  /// Periodic linear interpolation at x (m, any real), the three components.
  Eigen::Vector3d sample(double x) const;
  /// The running integral C(x) of the interpolated series from 0 to x (m), periodic in x.
  Eigen::Vector3d running_integral(double x) const;
  /// A step's read: the mean of the interpolated series over [x - W, x], W = clamp(window, dx, P) (m).
  Eigen::Vector3d average(double x, double window) const;
  /// The float table a device uploads, kDeviceFloatsPerPoint (6) floats a point: [6 n + c] component c's
  /// value at point n, [6 n + 3 + c] its running integral C(n dx) (m).
  std::vector<float> device_table() const;
  static constexpr std::size_t kDeviceFloatsPerPoint = 6;

  /// k_p = 2 pi p / P (rad/m) and the amplitude a_p of component c: sqrt(2 F_c(k_p) 3 dk) for p = c mod 3,
  /// else 0 (and 0 below the cutoff, at p = 0 and p >= N/2).
  double wavenumber(int bin) const;
  double amplitude(int bin, int component) const;
  /// The model's one-sided spectrum of component c at k1 (rad/m), m: F_c(k1) / U^2 for k_c < k1 < k_N,
  /// else 0.
  double model_spectrum(int component, double k1) const;
  /// Variances of component c: the model's, integral of model_spectrum over k1 (quadrature), and the
  /// realised series', sum_p a_p^2 / 2 (exact for every seed; the two differ by the bins' rectangle rule).
  double model_variance(int component) const;
  double realised_variance(int component) const;

  /// Offset of tree `tree`'s wind sample `sample`, in series points: an integer in [0, N) from (seed, tree,
  /// sample). Throws std::invalid_argument for a negative index.
  int offset(int tree, int sample) const;
  /// Every flat sample's offset for `forest`, in its flat sample order (Forest::sample_offset).
  std::vector<int> offsets(const Forest& forest) const;

  /// S_f(f) of one mode's delta f (header comment), (N / kg^1/2)^2 / Hz, at f >= 0 Hz: mean_wind rows V_s
  /// (m/s, world frame) and projections rows g_s = s^1/2 R p_i^s (kg^1/2 / m), one row per wind sample of
  /// the tree, row 0 the sample whose speed sets the travel; window W (m): 0 for the model's point read,
  /// else a read window whose box filter is included. Throws std::invalid_argument for sizes that differ or
  /// are zero, or a negative intensity, window or f.
  double modal_force_spectrum(double f, const Eigen::MatrixX3d& mean_wind,
                              const Eigen::MatrixX3d& projections, double intensity,
                              double window = 0.0) const;
  /// sigma_q^2 of q'' + 2 zeta omega q' + omega^2 q = delta f, (kg^1/2 m)^2: the integral of
  /// |H|^2 S_f over the series' band by adaptive Simpson quadrature, split at the resonance so that its peak
  /// (half-width zeta omega) is resolved. omega > 0 (rad/s), zeta > 0; else std::invalid_argument.
  double response_variance(double omega, double zeta, const Eigen::MatrixX3d& mean_wind,
                           const Eigen::MatrixX3d& projections, double intensity, double window = 0.0) const;

 private:
  // S_f(f) with the von Karman spectra taken as they are, for f inside the band (no band test).
  double in_band_force_spectrum(double f, const Eigen::MatrixX3d& mean_wind,
                                const Eigen::MatrixX3d& projections, double intensity, double window) const;

  UnresolvedTurbulenceSettings settings_;
  fluid::VonKarmanSpectrum spectrum_;
  Eigen::MatrixX3d values_;
  Eigen::MatrixX3d integral_;    // N by 3: C(n dx), C(0) = 0
  Eigen::MatrixX3d amplitudes_;  // (N/2 + 1) by 3: a_p per bin and component
};

/// The wind frame at v (m/s): columns e_par, e_h, e_v (header comment). v must be non-zero.
Eigen::Matrix3d unresolved_wind_frame(const Eigen::Vector3d& v);
/// v' = intensity |v| (xi_l e_par + xi_t1 e_h + xi_t2 e_v), m/s; zero for v = 0.
Eigen::Vector3d unresolved_fluctuation(const Eigen::Vector3d& v, const Eigen::Vector3d& xi, double intensity);
/// The linearised drag increment |v| v' + v (v . v') / |v|, m^2/s^2; zero for v = 0.
Eigen::Vector3d linearised_drag_increment(const Eigen::Vector3d& v, const Eigen::Vector3d& v_prime);

}  // namespace fw::trees
