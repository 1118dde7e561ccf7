// VonKarmanSpectrum: the integrals that define it (energy 3/2 sigma^2, each 1D spectrum sigma^2, L_u from
// F_u(0)), the -5/3 inertial range, the isotropic relations between E and the 1D spectra, the frequency
// form and argument checks. Every integral is a trapezoid rule after a change of variable that makes the
// integrand decay exponentially at both ends, where the trapezoid rule converges exponentially with the step.
#include "fluid/TurbulenceSpectrum.hpp"

#include <catch2/catch.hpp>

#include <cmath>
#include <functional>
#include <limits>
#include <numbers>
#include <stdexcept>
#include <string>

using fw::fluid::VonKarmanSpectrum;

namespace {

// Steps of the trapezoid rules below: halving them changes no integral here by more than 1e-13 relative
// (tried), so they are converged to round-off.
constexpr double kLogStep = 0.01;
// Integrals over k in (0, inf) as integrals over s = ln(k L) in [-kLogLo, kLogHi]: the integrands f(k) k here
// fall at least as e^(-2 s / 3) above and e^s below, so the cut tails are below e^(-40) ~ 4e-18 relatively.
constexpr double kLogLo = 40.0, kLogHi = 60.0;

// Integral of f(k) over k in (0, inf), with k = e^s / L.
double integrate_positive(const std::function<double(double)>& f, double L) {
  double sum = 0.0;
  const int n = int((kLogLo + kLogHi) / kLogStep);
  for (int i = 0; i <= n; ++i) {
    const double k = std::exp(-kLogLo + i * kLogStep) / L;
    sum += (i == 0 || i == n ? 0.5 : 1.0) * f(k) * k;  // dk = k ds
  }
  return sum * kLogStep;
}

// Integral of f(k) over k in (k1, inf), k1 > 0, with k = k1 exp(e^t): dk = k e^t dt, so a finite f(k1)
// decays as e^t at t -> -inf, and f ~ k^(-8/3) double-exponentially at t -> +inf; t in [-40, 5] leaves
// tails below e^(-40) relatively (k up to k1 e^148).
double integrate_above(const std::function<double(double)>& f, double k1) {
  constexpr double t_lo = -40.0, t_hi = 5.0, step = 1e-3;
  double sum = 0.0;
  const int n = int((t_hi - t_lo) / step);
  for (int i = 0; i <= n; ++i) {
    const double t = t_lo + i * step;
    const double s = std::exp(t);
    const double k = k1 * std::exp(s);
    sum += (i == 0 || i == n ? 0.5 : 1.0) * f(k) * k * s;  // dk = k ds, ds = s dt
  }
  return sum * step;
}

std::string validation_error(const VonKarmanSpectrum& s) {
  try {
    s.validate();
  } catch (const std::invalid_argument& e) {
    return e.what();
  }
  return "";
}

// Round-off of ~5000 to 25000 positive terms each within 1e-16 relative, with margin: what a converged
// quadrature (kLogStep) is held to.
constexpr double kQuadratureTolerance = 1e-10;

}  // namespace

TEST_CASE("VonKarmanSpectrum: E integrates to 3/2 sigma^2 and each 1D spectrum to sigma^2") {
  for (const VonKarmanSpectrum s : {VonKarmanSpectrum{2.4, 30.0}, VonKarmanSpectrum{0.3, 0.5}}) {
    INFO("sigma " << s.sigma << " L_u " << s.integral_length);
    const double L = s.spectrum_length();
    const double sigma2 = s.sigma * s.sigma;
    CHECK(integrate_positive([&](double k) { return s.energy(k); }, L) ==
          Approx(1.5 * sigma2).epsilon(kQuadratureTolerance));
    CHECK(integrate_positive([&](double k) { return s.longitudinal(k); }, L) ==
          Approx(sigma2).epsilon(kQuadratureTolerance));
    CHECK(integrate_positive([&](double k) { return s.transverse(k); }, L) ==
          Approx(sigma2).epsilon(kQuadratureTolerance));
  }
}

TEST_CASE("VonKarmanSpectrum: F_u(0) pi / (2 sigma^2) is the integral length L_u") {
  const VonKarmanSpectrum s{1.7, 42.0};
  // The autocorrelation's integral is pi F_u(0) / (2 sigma^2) for a one-sided F_u (Wiener-Khinchin). The
  // formula has no quadrature: only a few roundings of 1e-16 each.
  CHECK(s.longitudinal(0.0) * std::numbers::pi / (2.0 * s.sigma * s.sigma) == Approx(42.0).epsilon(1e-14));
  // The transverse integral scale is half the longitudinal one in isotropic turbulence.
  CHECK(s.transverse(0.0) * std::numbers::pi / (2.0 * s.sigma * s.sigma) == Approx(21.0).epsilon(1e-14));
  CHECK(s.spectrum_length() * fw::fluid::von_karman_integral_ratio() == Approx(42.0).epsilon(1e-14));
  // sqrt(pi) Gamma(5/6) / Gamma(1/3), independently: Gamma(1/3) Gamma(2/3) = 2 pi / sqrt 3 (reflection).
  const double ratio = std::sqrt(std::numbers::pi) * std::tgamma(5.0 / 6.0) * std::tgamma(2.0 / 3.0) *
                       std::sqrt(3.0) / (2.0 * std::numbers::pi);
  CHECK(fw::fluid::von_karman_integral_ratio() == Approx(ratio).epsilon(1e-14));
}

TEST_CASE("VonKarmanSpectrum: the 1D spectra fall as k^(-5/3) at high k, F_v / F_u -> 4/3") {
  const VonKarmanSpectrum s{2.0, 10.0};
  const double L = s.spectrum_length();
  // At k L = 1e4 the exact local slope of F_u is -5/3 (k L)^2 / (1 + (k L)^2) = -5/3 (1 - 1e-8); the
  // central difference over +-1e-3 in ln k adds an error ~1e-7 (the step squared times a bounded third
  // derivative), so 1e-6 holds both.
  const double k = 1e4 / L, d = 1e-3;
  const auto slope = [&](double (VonKarmanSpectrum::*f)(double) const) {
    return (std::log((s.*f)(k * std::exp(d))) - std::log((s.*f)(k * std::exp(-d)))) / (2.0 * d);
  };
  CHECK(slope(&VonKarmanSpectrum::longitudinal) == Approx(-5.0 / 3.0).margin(1e-6));
  CHECK(slope(&VonKarmanSpectrum::transverse) == Approx(-5.0 / 3.0).margin(1e-6));
  // E(k) falls as k^(-5/3) too: the same bound on the difference.
  CHECK(slope(&VonKarmanSpectrum::energy) == Approx(-5.0 / 3.0).margin(1e-6));
  // F_v / F_u = (1 + 8/3 x^2) / (2 (1 + x^2)) = 4/3 - 5 / (6 (1 + x^2)) at x = k L = 1e4: 4/3 - 8e-9.
  CHECK(s.transverse(k) / s.longitudinal(k) == Approx(4.0 / 3.0).margin(1e-7));
}

TEST_CASE("VonKarmanSpectrum: F_u and F_v follow from E by the isotropic relations") {
  // F_u(k1) = int_k1^inf E(k)/k (1 - k1^2/k^2) dk and F_v(k1) = 1/2 int_k1^inf E(k)/k (1 + k1^2/k^2) dk
  // (one-sided 1D spectra of isotropic turbulence, Pope 2000, eq. 6.216): E and the 1D spectra are one
  // spectrum, not three formulas that merely share a name.
  const VonKarmanSpectrum s{1.3, 25.0};
  const double L = s.spectrum_length();
  for (double k1L : {1e-3, 0.1, 0.7, 1.0, 3.0, 30.0, 1e3}) {
    const double k1 = k1L / L;
    INFO("k1 L = " << k1L);
    const double fu =
        integrate_above([&](double k) { return s.energy(k) / k * (1.0 - k1 * k1 / (k * k)); }, k1);
    const double fv =
        0.5 * integrate_above([&](double k) { return s.energy(k) / k * (1.0 + k1 * k1 / (k * k)); }, k1);
    CHECK(fu == Approx(s.longitudinal(k1)).epsilon(kQuadratureTolerance));
    CHECK(fv == Approx(s.transverse(k1)).epsilon(kQuadratureTolerance));
  }
}

TEST_CASE("VonKarmanSpectrum: a sigma or length that is not finite and positive is rejected") {
  const double nan = std::numeric_limits<double>::quiet_NaN(), inf = std::numeric_limits<double>::infinity();
  CHECK(validation_error(VonKarmanSpectrum{2.0, 30.0}).empty());
  for (double bad : {0.0, -1.0, nan, inf}) {
    INFO(bad);
    CHECK_THAT(validation_error(VonKarmanSpectrum{bad, 30.0}),
               Catch::StartsWith("VonKarmanSpectrum:") && Catch::Contains("sigma"));
    CHECK_THAT(validation_error(VonKarmanSpectrum{2.0, bad}),
               Catch::StartsWith("VonKarmanSpectrum:") && Catch::Contains("integral_length"));
  }
}
