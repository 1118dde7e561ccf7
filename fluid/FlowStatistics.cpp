#include "fluid/FlowStatistics.hpp"

#include <fftw3.h>
#include <fmt/format.h>

#include <cmath>
#include <numbers>
#include <numeric>
#include <stdexcept>

namespace fw::fluid {

double mean(const std::vector<double>& x) {
  if (x.empty()) throw std::invalid_argument("mean: empty signal");
  return std::accumulate(x.begin(), x.end(), 0.0) / double(x.size());
}

double covariance(const std::vector<double>& x, const std::vector<double>& y) {
  if (x.size() != y.size())
    throw std::invalid_argument(fmt::format("covariance: sizes {} and {} differ", x.size(), y.size()));
  const double mx = mean(x), my = mean(y);
  double sum = 0.0;
  for (std::size_t i = 0; i < x.size(); ++i) sum += (x[i] - mx) * (y[i] - my);
  return sum / double(x.size());
}

double standard_deviation(const std::vector<double>& x) {
  return std::sqrt(covariance(x, x));
}

std::vector<double> autocorrelation(const std::vector<double>& x, std::size_t max_lag) {
  const double m = mean(x), variance = covariance(x, x);
  std::vector<double> r(std::min(max_lag + 1, x.size()), 0.0);
  if (!(variance > 0.0)) return r;
  for (std::size_t lag = 0; lag < r.size(); ++lag) {
    double sum = 0.0;
    for (std::size_t i = 0; i + lag < x.size(); ++i) sum += (x[i] - m) * (x[i + lag] - m);
    r[lag] = sum / (double(x.size()) * variance);
  }
  return r;
}

double integral_time_scale(const std::vector<double>& x, double dt) {
  if (!(dt > 0.0)) throw std::invalid_argument("integral_time_scale: dt must be > 0");
  const std::vector<double> r = autocorrelation(x, x.size() / 2);
  double area = 0.0;
  for (std::size_t lag = 1; lag < r.size(); ++lag) {
    if (r[lag] <= 0.0) {
      area += 0.5 * r[lag - 1] * dt * r[lag - 1] / (r[lag - 1] - r[lag]);  // up to the zero crossing
      return area;
    }
    area += 0.5 * (r[lag - 1] + r[lag]) * dt;
  }
  return area;
}

Spectrum power_spectrum(const std::vector<double>& x, double dt, std::size_t segment) {
  if (segment < 8 || segment % 2 != 0)
    throw std::invalid_argument(
        fmt::format("power_spectrum: segment must be even and >= 8, got {}", segment));
  if (x.size() < segment)
    throw std::invalid_argument(fmt::format(
        "power_spectrum: the signal has {} samples, fewer than one segment ({})", x.size(), segment));
  if (!(dt > 0.0)) throw std::invalid_argument("power_spectrum: dt must be > 0");
  std::vector<double> window(segment), in(segment);
  double window_power = 0.0;
  for (std::size_t i = 0; i < segment; ++i) {
    window[i] = 0.5 * (1.0 - std::cos(2.0 * std::numbers::pi * double(i) / double(segment)));
    window_power += window[i] * window[i];
  }
  const std::size_t bins = segment / 2 + 1;
  fftw_complex* out = fftw_alloc_complex(bins);
  fftw_plan plan = fftw_plan_dft_r2c_1d(int(segment), in.data(), out, FFTW_ESTIMATE);
  std::vector<double> sum(bins, 0.0);
  std::size_t segments = 0;
  for (std::size_t start = 0; start + segment <= x.size(); start += segment / 2, ++segments) {
    double m = 0.0;
    for (std::size_t i = 0; i < segment; ++i) m += x[start + i];
    m /= double(segment);
    for (std::size_t i = 0; i < segment; ++i) in[i] = (x[start + i] - m) * window[i];
    fftw_execute(plan);
    for (std::size_t b = 0; b < bins; ++b) sum[b] += out[b][0] * out[b][0] + out[b][1] * out[b][1];
  }
  fftw_destroy_plan(plan);
  fftw_free(out);
  Spectrum s;
  // One-sided: interior bins count twice; |X|^2 dt / sum(w^2) is the two-sided density of a windowed segment.
  for (std::size_t b = 1; b < bins; ++b) {
    const double two_sided = sum[b] / double(segments) * dt / window_power;
    s.frequency.push_back(double(b) / (double(segment) * dt));
    s.density.push_back(b + 1 == bins ? two_sided : 2.0 * two_sided);
  }
  return s;
}

double log_log_slope(const Spectrum& spectrum, double f_low, double f_high) {
  double sx = 0, sy = 0, sxx = 0, sxy = 0;
  int n = 0;
  for (std::size_t i = 0; i < spectrum.frequency.size(); ++i) {
    const double f = spectrum.frequency[i];
    if (f < f_low || f > f_high || !(spectrum.density[i] > 0.0)) continue;
    const double lx = std::log(f), ly = std::log(spectrum.density[i]);
    sx += lx, sy += ly, sxx += lx * lx, sxy += lx * ly;
    ++n;
  }
  if (n < 3)
    throw std::invalid_argument(
        fmt::format("log_log_slope: {} frequencies in [{}, {}] Hz, at least 3 needed", n, f_low, f_high));
  return (n * sxy - sx * sy) / (n * sxx - sx * sx);
}

double peak_frequency(const Spectrum& spectrum, double f_low, double f_high) {
  double best = -1.0, at = 0.0;
  for (std::size_t i = 0; i < spectrum.frequency.size(); ++i) {
    const double f = spectrum.frequency[i];
    if (f >= f_low && f <= f_high && spectrum.density[i] > best) best = spectrum.density[i], at = f;
  }
  return at;
}

}  // namespace fw::fluid
