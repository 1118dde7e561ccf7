// The von Karman spectrum of isotropic turbulence: the 3D energy spectrum that the synthetic inflow box is
// built from, and the one-sided 1D spectra that a probe or a tree sees (Taylor's hypothesis).
//
//   fw::fluid::VonKarmanSpectrum s{/*sigma=*/2.4, /*integral_length=*/30.0};
//   double e  = s.energy(0.1);            // E(k), m^3/s^2, k in rad/m
//   double fu = s.longitudinal(0.1);      // F_u(k1), m^3/s^2, one-sided: integral over k1 >= 0 is sigma^2
//
// With L the spectrum's length scale and L_u = integral_length the longitudinal integral scale (what a wind
// engineer measures from an autocorrelation), L_u = L sqrt(pi) Gamma(5/6) / Gamma(1/3) = 0.7468 L, and
//   E(k)     = A sigma^2 L (kL)^4 / (1 + (kL)^2)^(17/6),   A = 3 Gamma(17/6) / (Gamma(5/2) Gamma(1/3)),
//              so that the integral of E over k >= 0 is (3/2) sigma^2;
//   F_u(k1)  = (2 sigma^2 L_u / pi) / (1 + (k1 L)^2)^(5/6);
//   F_v(k1)  = (sigma^2 L_u / pi) (1 + (8/3)(k1 L)^2) / (1 + (k1 L)^2)^(11/6)   (v and w alike).
// At high k both 1D spectra fall as k1^(-5/3) (the inertial range), and F_v / F_u -> 4/3 there. Frequency
// spectra follow from k1 = 2 pi f / U: S(f) = (2 pi / U) F(2 pi f / U), one-sided in Hz.
#pragma once

namespace fw::fluid {

struct VonKarmanSpectrum {
  double sigma = 1.0;            // standard deviation of each velocity component, m/s (> 0)
  double integral_length = 1.0;  // L_u, the longitudinal integral length scale, m (> 0)

  /// Throws std::invalid_argument("VonKarmanSpectrum: ...") unless both are finite and > 0.
  void validate() const;
  /// L = L_u / 0.7468, the length in the spectra's formulas, m.
  double spectrum_length() const;
  /// E(k), m^3/s^2, for a wavenumber magnitude k >= 0 (rad/m).
  double energy(double k) const;
  /// F_u(k1) and F_v(k1) = F_w(k1), one-sided, m^3/s^2, for k1 >= 0 (rad/m).
  double longitudinal(double k1) const;
  double transverse(double k1) const;
};

/// L_u / L for the von Karman spectrum: sqrt(pi) Gamma(5/6) / Gamma(1/3) = 0.74684.
double von_karman_integral_ratio();

}  // namespace fw::fluid
