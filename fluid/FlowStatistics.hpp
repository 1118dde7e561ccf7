// Statistics of sampled wind signals, for validation and for a probe's spectrum: mean, standard deviation,
// covariance, the integral time scale and the one-sided power spectral density (Welch's method, FFTW).
//
//   std::vector<double> u = ...;                          // one probe's u, sampled every dt seconds
//   double intensity = fw::fluid::standard_deviation(u) / fw::fluid::mean(u);
//   double length = fw::fluid::integral_time_scale(u, dt) * fw::fluid::mean(u);   // Taylor: L_u = U T_u
//   fw::fluid::Spectrum s = fw::fluid::power_spectrum(u, dt, /*segment=*/256);
//   double slope = fw::fluid::log_log_slope(s, 0.5, 2.0);   // -5/3 in the inertial range
//
// power_spectrum: the signal is cut into segments of `segment` samples overlapping by half, each detrended
// to zero mean, Hann-windowed and transformed; the periodograms are averaged and scaled so that the sum of
// S(f) df over f > 0 is the signal's variance (one-sided, units^2 / Hz).
#pragma once

#include <cstddef>
#include <vector>

namespace fw::fluid {

double mean(const std::vector<double>& x);
/// Population standard deviation (divides by n).
double standard_deviation(const std::vector<double>& x);
/// Covariance of two equally long signals (divides by n). Throws std::invalid_argument for unequal sizes.
double covariance(const std::vector<double>& x, const std::vector<double>& y);
/// The autocorrelation of the fluctuation, lags 0 .. max_lag (r(0) = 1), by direct sums.
std::vector<double> autocorrelation(const std::vector<double>& x, std::size_t max_lag);
/// T = integral of the autocorrelation from lag 0 to its first zero crossing (trapezoidal), s. dt > 0.
double integral_time_scale(const std::vector<double>& x, double dt);

struct Spectrum {
  std::vector<double> frequency;  ///< Hz, from df to the Nyquist frequency
  std::vector<double> density;    ///< one-sided PSD, units^2 / Hz
};
/// Welch's estimate (header comment). Throws std::invalid_argument("power_spectrum: ...") for segment < 8
/// or odd, a signal shorter than one segment, or dt <= 0.
Spectrum power_spectrum(const std::vector<double>& x, double dt, std::size_t segment);
/// Least-squares slope of log S against log f over frequencies in [f_low, f_high] (at least 3 points, else
/// std::invalid_argument).
double log_log_slope(const Spectrum& spectrum, double f_low, double f_high);
/// The frequency of the largest density within [f_low, f_high], Hz.
double peak_frequency(const Spectrum& spectrum, double f_low, double f_high);
/// The frequency of the peak of the premultiplied spectrum f S(f), Hz: where the variance per interval of
/// log f is largest (the dominant eddies of a series, as micrometeorology reads them). f S(f) is averaged
/// in bins of equal width in log f, `bins_per_decade` a decade (> 0), from the lowest frequency; around the
/// largest bin, the bins above half of it (at least three) are fitted by a parabola in (log f, log f S) by
/// least squares, whose vertex is the peak (kept within those bins). A broad, noisy spectrum's largest single
/// density jumps between frequencies far apart; the fit uses the whole peak. Throws std::invalid_argument
/// when fewer than three bins hold a frequency or bins_per_decade <= 0.
double premultiplied_peak_frequency(const Spectrum& spectrum, int bins_per_decade);

}  // namespace fw::fluid
