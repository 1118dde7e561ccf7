#include "fluid/FlowStatistics.hpp"

#include <fftw3.h>
#include <fmt/format.h>

#include <algorithm>
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

double premultiplied_peak_frequency(const Spectrum& spectrum, int bins_per_decade) {
  if (bins_per_decade <= 0)
    throw std::invalid_argument(
        fmt::format("premultiplied_peak_frequency: bins_per_decade must be > 0, got {}", bins_per_decade));
  if (spectrum.frequency.empty() || !(spectrum.frequency.front() > 0.0))
    throw std::invalid_argument("premultiplied_peak_frequency: the spectrum needs frequencies above 0");
  // Bin b holds x = log10(f / f_0) in [b, b + 1) / bins_per_decade; it sits at the mean x of its
  // frequencies (few and unevenly placed in the lowest bins).
  const double f0 = spectrum.frequency.front();
  std::vector<double> sum, position, count;
  for (std::size_t i = 0; i < spectrum.frequency.size(); ++i) {
    const double f = spectrum.frequency[i], x = std::log10(f / f0);
    const auto b = std::size_t(std::floor(x * bins_per_decade + 1e-9));
    if (b >= sum.size()) sum.resize(b + 1, 0.0), position.resize(b + 1, 0.0), count.resize(b + 1, 0.0);
    sum[b] += f * spectrum.density[i];
    position[b] += x;
    count[b] += 1.0;
  }
  // Empty bins (narrower than the frequency spacing, at the low end) take no part.
  std::vector<double> centre, value;
  for (std::size_t b = 0; b < sum.size(); ++b)
    if (count[b] > 0.0) centre.push_back(position[b] / count[b]), value.push_back(sum[b] / count[b]);
  if (value.size() < 3)
    throw std::invalid_argument(fmt::format(
        "premultiplied_peak_frequency: {} bins hold a frequency, at least 3 needed", value.size()));
  // The peak's region: the run of bins around the largest that stay above half of it. A parabola in
  // (log f, log f S) fitted to all of them by least squares: exact for a peak that is Gaussian in log f,
  // and the noise of each bin averages out over the region (a canopy's w spectrum is flat-topped: a factor of
  // 1.5 either side of its peak lowers f S by a fifth only, so any one bin may win).
  const std::size_t best = std::size_t(std::max_element(value.begin(), value.end()) - value.begin());
  std::size_t low = best, high = best;
  while (low > 0 && value[low - 1] >= 0.5 * value[best]) --low;
  while (high + 1 < value.size() && value[high + 1] >= 0.5 * value[best]) ++high;
  // At least three bins, so that a parabola is determined.
  while (high - low < 2) {
    if (low > 0) --low;
    if (high - low < 2 && high + 1 < value.size()) ++high;
  }
  double s0 = 0, s1 = 0, s2 = 0, s3 = 0, s4 = 0, t0 = 0, t1 = 0, t2 = 0;
  for (std::size_t b = low; b <= high; ++b) {
    // Centred on the largest bin, for conditioning.
    const double x = centre[b] - centre[best], y = std::log(std::max(value[b], 1e-300));
    s0 += 1, s1 += x, s2 += x * x, s3 += x * x * x, s4 += x * x * x * x;
    t0 += y, t1 += x * y, t2 += x * x * y;
  }
  // Normal equations of y = a + b x + c x^2, by Cramer's rule.
  const auto det3 = [](double a, double b, double c, double d, double e, double f, double g, double h,
                       double i) { return a * (e * i - f * h) - b * (d * i - f * g) + c * (d * h - e * g); };
  const double det = det3(s0, s1, s2, s1, s2, s3, s2, s3, s4);
  const double slope = det3(s0, t0, s2, s1, t1, s3, s2, t2, s4) / det;
  const double curvature = det3(s0, s1, t0, s1, s2, t1, s2, s3, t2) / det;
  double at = centre[best];
  if (std::isfinite(slope) && curvature < 0.0)
    at = std::clamp(centre[best] - slope / (2.0 * curvature), centre[low], centre[high]);
  return f0 * std::pow(10.0, at);
}

}  // namespace fw::fluid
