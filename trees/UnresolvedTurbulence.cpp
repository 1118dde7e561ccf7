#include "trees/UnresolvedTurbulence.hpp"

#include <fftw3.h>
#include <fmt/format.h>

#include <algorithm>
#include <cmath>
#include <complex>
#include <cstring>
#include <memory>
#include <mutex>
#include <numbers>
#include <random>
#include <stdexcept>

namespace fw::trees {
namespace {

constexpr double kTwoPi = 2.0 * std::numbers::pi;
// The largest N: a device keeps the travelled distance's whole points in a float, exact below 2^24.
constexpr int kMaxSeriesLength = 1 << 24;
constexpr int kMinSeriesLength = 4;
// A wind whose horizontal part is below this fraction of its speed counts as vertical: z x e_par has no
// reliable direction there, and e_h = x is as good as any (the transverse components are statistically
// alike).
constexpr double kVerticalWind = 1e-9;
// Quadrature: relative tolerance per piece, the pieces each range starts with (so the first Simpson
// estimates cannot miss a feature), and the recursion's depth limit.
constexpr double kQuadratureTolerance = 1e-10;
constexpr int kInitialPieces = 32;
constexpr int kMaxDepth = 48;
// Breakpoints around a resonance, in half-widths zeta f_n either side of the peak.
constexpr double kResonanceBreaks[] = {0.0, 1.0, 3.0, 10.0, 30.0, 100.0};
// 53 random bits make a double in [0, 1) the same way on every standard library.
constexpr int kMantissaBits = 53;

[[noreturn]] void fail(const std::string& what) {
  throw std::invalid_argument("UnresolvedTurbulence: " + what);
}

// The splitmix64 finaliser (Steele, Lea & Flood 2014): a bijective mix of 64 bits with full avalanche, so
// neighbouring (tree, sample) indices give unrelated offsets.
std::uint64_t mix64(std::uint64_t z) {
  constexpr std::uint64_t kGolden = 0x9e3779b97f4a7c15ULL, kMul1 = 0xbf58476d1ce4e5b9ULL,
                          kMul2 = 0x94d049bb133111ebULL;
  z += kGolden;
  z = (z ^ (z >> 30)) * kMul1;
  z = (z ^ (z >> 27)) * kMul2;
  return z ^ (z >> 31);
}

// FFTW's planner (plan creation and destruction) is not re-entrant; fluid/TurbulenceBox plans too, but a
// process-wide lock is all that matters for this file's own concurrent constructions.
std::mutex& planner_mutex() {
  static std::mutex m;
  return m;
}

double simpson(double fa, double fm, double fb, double width) {
  return width / 6.0 * (fa + 4.0 * fm + fb);
}

template <typename F>
double adaptive_simpson(const F& fn, double a, double b, double fa, double fm, double fb, double whole,
                        double tolerance, int depth) {
  const double m = 0.5 * (a + b);
  const double lm = 0.5 * (a + m), rm = 0.5 * (m + b);
  const double flm = fn(lm), frm = fn(rm);
  const double left = simpson(fa, flm, fm, m - a), right = simpson(fm, frm, fb, b - m);
  const double delta = left + right - whole;
  // Richardson: the two halves' sum is accurate to about delta / 15 once delta is small.
  if (depth <= 0 || std::abs(delta) <= 15.0 * tolerance) return left + right + delta / 15.0;
  return adaptive_simpson(fn, a, m, fa, flm, fm, left, 0.5 * tolerance, depth - 1) +
         adaptive_simpson(fn, m, b, fm, frm, fb, right, 0.5 * tolerance, depth - 1);
}

// The integral of fn over [a, b], split at `breaks` (those inside) and into kInitialPieces equal pieces
// between them; each piece converges to kQuadratureTolerance of its own first estimate.
template <typename F>
double integrate(const F& fn, double a, double b, std::vector<double> breaks) {
  breaks.push_back(a);
  breaks.push_back(b);
  std::erase_if(breaks, [&](double x) { return !(x >= a && x <= b); });
  std::sort(breaks.begin(), breaks.end());
  breaks.erase(std::unique(breaks.begin(), breaks.end()), breaks.end());
  double total = 0.0;
  for (std::size_t j = 0; j + 1 < breaks.size(); ++j) {
    const double width = (breaks[j + 1] - breaks[j]) / kInitialPieces;
    for (int piece = 0; piece < kInitialPieces; ++piece) {
      const double lo = breaks[j] + piece * width, hi = lo + width;
      const double flo = fn(lo), fmid = fn(0.5 * (lo + hi)), fhi = fn(hi);
      const double whole = simpson(flo, fmid, fhi, hi - lo);
      total += adaptive_simpson(fn, lo, hi, flo, fmid, fhi, whole, kQuadratureTolerance * std::abs(whole),
                                kMaxDepth);
    }
  }
  return total;
}

void check_component(int component) {
  if (component < 0 || component >= UnresolvedTurbulence::kComponents)
    fail(fmt::format("component must be 0, 1 or 2, got {}", component));
}

void check_mean_wind(const Eigen::MatrixX3d& mean_wind, const Eigen::MatrixX3d& projections, double intensity,
                     double window) {
  if (!(std::isfinite(window) && window >= 0.0))
    fail(fmt::format("the read window must be finite and >= 0 m, got {}", window));
  if (mean_wind.rows() == 0 || mean_wind.rows() != projections.rows())
    fail(fmt::format("mean wind and projections need the same, non-zero number of rows, got {} and {}",
                     mean_wind.rows(), projections.rows()));
  if (!std::isfinite(intensity) || intensity < 0.0)
    fail(fmt::format("intensity must be finite and >= 0, got {}", intensity));
}

}  // namespace

void UnresolvedTurbulenceSettings::validate() const {
  auto positive = [](double x) { return std::isfinite(x) && x > 0.0; };
  if (!positive(cutoff_cells)) fail(fmt::format("cutoff_cells must be > 0, got {}", cutoff_cells));
  if (!positive(cell_size)) fail(fmt::format("cell_size must be > 0 m, got {}", cell_size));
  if (!std::isfinite(intensity) || intensity < 0.0)
    fail(fmt::format("intensity must be finite and >= 0, got {}", intensity));
  if (!positive(integral_length)) fail(fmt::format("integral_length must be > 0 m, got {}", integral_length));
  if (series_length < kMinSeriesLength || series_length > kMaxSeriesLength ||
      (series_length & (series_length - 1)) != 0)
    fail(fmt::format("series_length must be a power of two in [{}, {}], got {}", kMinSeriesLength,
                     kMaxSeriesLength, series_length));
  if (!positive(series_spacing)) fail(fmt::format("series_spacing must be > 0 m, got {}", series_spacing));
  const double nyquist = std::numbers::pi / series_spacing;
  if (!(cutoff_wavenumber() < nyquist))
    fail(
        fmt::format("the cutoff wavenumber {} rad/m (cutoff_cells {} x cell_size {} m) must lie below the "
                    "series' Nyquist wavenumber pi / series_spacing = {} rad/m",
                    cutoff_wavenumber(), cutoff_cells, cell_size, nyquist));
}

double UnresolvedTurbulenceSettings::cutoff_wavenumber() const {
  return kTwoPi / (cutoff_cells * cell_size);
}

fluid::VonKarmanSpectrum UnresolvedTurbulenceSettings::spectrum() const {
  return fluid::VonKarmanSpectrum{1.0, integral_length};
}

UnresolvedTurbulence::UnresolvedTurbulence(const UnresolvedTurbulenceSettings& settings)
    : settings_(settings), spectrum_(settings.spectrum()) {
  settings_.validate();
  const int n = length();
  const int bins = n / 2 + 1;
  const double dk = kTwoPi / period();
  amplitudes_ = Eigen::MatrixX3d::Zero(bins, kComponents);
  values_.resize(n, kComponents);

  std::mt19937_64 rng(settings_.seed);
  auto unit = [&rng] { return double(rng() >> (64 - kMantissaBits)) * std::ldexp(1.0, -kMantissaBits); };

  struct FftwFree {
    void operator()(void* p) const { fftw_free(p); }
  };
  std::unique_ptr<fftw_complex[], FftwFree> spectrum(fftw_alloc_complex(std::size_t(bins)));
  std::unique_ptr<double[], FftwFree> real(fftw_alloc_real(std::size_t(n)));
  if (!spectrum || !real) throw std::bad_alloc();
  fftw_plan plan;
  {
    std::lock_guard lock(planner_mutex());
    plan = fftw_plan_dft_c2r_1d(n, spectrum.get(), real.get(), FFTW_ESTIMATE | FFTW_DESTROY_INPUT);
  }
  // One phase per interior bin, drawn whether the bin is kept or not, so that the phases do not depend on
  // the cutoff; bin p belongs to component p mod 3 alone (header comment).
  std::vector<double> phases(std::size_t(bins), 0.0);
  for (int p = 1; p < n / 2; ++p) phases[std::size_t(p)] = kTwoPi * unit();
  for (int c = 0; c < kComponents; ++c) {
    std::memset(spectrum.get(), 0, std::size_t(bins) * sizeof(fftw_complex));
    for (int p = 1; p < n / 2; ++p) {
      if (p % kComponents != c) continue;
      // The bin stands for itself and its neighbours of the other components: a width of 3 dk.
      const double a = std::sqrt(2.0 * model_spectrum(c, wavenumber(p)) * kComponents * dk);
      amplitudes_(p, c) = a;
      // FFTW's c2r sums X_0 + 2 Re(sum_p X_p e^{i 2 pi p n / N}) (+ the Nyquist term): X_p = a_p / 2 e^{i
      // phi} gives sum_p a_p cos(k_p x_n + phi_p).
      spectrum[p][0] = 0.5 * a * std::cos(phases[std::size_t(p)]);
      spectrum[p][1] = 0.5 * a * std::sin(phases[std::size_t(p)]);
    }
    fftw_execute(plan);
    for (int j = 0; j < n; ++j) values_(j, c) = real[std::size_t(j)];
  }
  // The running integral of the interpolated series, point by point (trapezoids are exact for it).
  integral_.resize(n, kComponents);
  integral_.row(0).setZero();
  for (int j = 1; j < n; ++j)
    integral_.row(j) = integral_.row(j - 1) + 0.5 * spacing() * (values_.row(j - 1) + values_.row(j));
  std::lock_guard lock(planner_mutex());
  fftw_destroy_plan(plan);
}

double UnresolvedTurbulence::nyquist_wavenumber() const {
  return std::numbers::pi / spacing();
}

double UnresolvedTurbulence::max_frequency(double speed) const {
  return speed / (2.0 * spacing());
}

Eigen::Vector3d UnresolvedTurbulence::sample(double x) const {
  const int n = length();
  double u = x / spacing();
  u -= n * std::floor(u / n);  // [0, n], n itself only by rounding
  const int lo = std::min(int(std::floor(u)), n - 1);
  const double t = u - lo;
  const int hi = (lo + 1) & (n - 1);
  return ((1.0 - t) * values_.row(lo) + t * values_.row(hi)).transpose();
}

Eigen::Vector3d UnresolvedTurbulence::running_integral(double x) const {
  const int n = length();
  double u = x / spacing();
  u -= n * std::floor(u / n);
  const int lo = std::min(int(std::floor(u)), n - 1);
  const double t = u - lo;
  const int hi = (lo + 1) & (n - 1);
  // Over the period the integral is sum_j dx xi_j = 0 (no bin 0), so C wraps with the series.
  const Eigen::RowVector3d a = values_.row(lo), b = values_.row(hi);
  return (integral_.row(lo) + spacing() * (a * t + 0.5 * (b - a) * t * t)).transpose();
}

Eigen::Vector3d UnresolvedTurbulence::average(double x, double window) const {
  if (!(window >= 0.0)) fail(fmt::format("the read window must be >= 0 m, got {}", window));
  const double w = std::clamp(window, spacing(), period());
  return (running_integral(x) - running_integral(x - w)) / w;
}

std::vector<float> UnresolvedTurbulence::device_table() const {
  constexpr int kStride = int(kDeviceFloatsPerPoint);  // the values, then their running integrals
  static_assert(kStride == 2 * kComponents);
  std::vector<float> out(std::size_t(kStride) * std::size_t(length()));
  for (int j = 0; j < length(); ++j)
    for (int c = 0; c < kComponents; ++c) {
      out[std::size_t(kStride * j + c)] = float(values_(j, c));
      out[std::size_t(kStride * j + kComponents + c)] = float(integral_(j, c));
    }
  return out;
}

double UnresolvedTurbulence::wavenumber(int bin) const {
  return kTwoPi * bin / period();
}

double UnresolvedTurbulence::amplitude(int bin, int component) const {
  check_component(component);
  if (bin < 0 || bin >= amplitudes_.rows())
    fail(fmt::format("bin must be in [0, {}], got {}", amplitudes_.rows() - 1, bin));
  return amplitudes_(bin, component);
}

double UnresolvedTurbulence::model_spectrum(int component, double k1) const {
  check_component(component);
  if (!(k1 > cutoff_wavenumber() && k1 < nyquist_wavenumber())) return 0.0;
  return component == kLongitudinal ? spectrum_.longitudinal(k1) : spectrum_.transverse(k1);
}

double UnresolvedTurbulence::model_variance(int component) const {
  check_component(component);
  const double kc = cutoff_wavenumber(), kn = nyquist_wavenumber();
  // Inside the open band: model_spectrum is zero on its edges, the integral of the smooth F_c is not.
  auto f = [&](double k) {
    return component == kLongitudinal ? spectrum_.longitudinal(k) : spectrum_.transverse(k);
  };
  return integrate(f, kc, kn, {});
}

double UnresolvedTurbulence::realised_variance(int component) const {
  check_component(component);
  return 0.5 * amplitudes_.col(component).squaredNorm();
}

int UnresolvedTurbulence::offset(int tree, int sample) const {
  if (tree < 0 || sample < 0)
    fail(fmt::format("tree and sample indices must be >= 0, got {} and {}", tree, sample));
  const std::uint64_t h = mix64(mix64(mix64(settings_.seed) ^ std::uint64_t(tree)) ^ std::uint64_t(sample));
  return int(h & std::uint64_t(length() - 1));
}

std::vector<int> UnresolvedTurbulence::offsets(const Forest& forest) const {
  std::vector<int> out(std::size_t(forest.total_samples()));
  for (int k = 0; k < forest.instance_count(); ++k) {
    const int samples = forest.species_of(k).wind().sample_count();
    for (int s = 0; s < samples; ++s) out[std::size_t(forest.sample_offset(k) + s)] = offset(k, s);
  }
  return out;
}

double UnresolvedTurbulence::modal_force_spectrum(double f, const Eigen::MatrixX3d& mean_wind,
                                                  const Eigen::MatrixX3d& projections, double intensity,
                                                  double window) const {
  check_mean_wind(mean_wind, projections, intensity, window);
  if (!(f >= 0.0)) fail(fmt::format("frequency must be >= 0 Hz, got {}", f));
  const double travel = mean_wind.row(0).norm();
  if (travel == 0.0) return 0.0;  // a tree at rest in still air reads one point of the series: no spectrum
  const double k = kTwoPi * f / travel;
  if (!(k > cutoff_wavenumber() && k < nyquist_wavenumber())) return 0.0;
  return in_band_force_spectrum(f, mean_wind, projections, intensity, window);
}

double UnresolvedTurbulence::in_band_force_spectrum(double f, const Eigen::MatrixX3d& mean_wind,
                                                    const Eigen::MatrixX3d& projections, double intensity,
                                                    double window) const {
  const double travel = mean_wind.row(0).norm();
  const double to_k = kTwoPi / travel;
  // The window's box filter: the mean of e^{ikx} over a width W is sin(kW/2) / (kW/2).
  const double half_phase = 0.5 * to_k * f * window;
  const double box = half_phase > 0.0 ? std::pow(std::sin(half_phase) / half_phase, 2) : 1.0;
  const double s_l = box * to_k * spectrum_.longitudinal(to_k * f);
  const double s_t = box * to_k * spectrum_.transverse(to_k * f);
  double sum = 0.0;
  for (int s = 0; s < mean_wind.rows(); ++s) {
    const Eigen::Vector3d v = mean_wind.row(s).transpose();
    const double speed = v.norm();
    if (speed == 0.0) continue;
    const Eigen::Vector3d g = unresolved_wind_frame(v).transpose() * projections.row(s).transpose();
    // delta f_s = I |V|^2 (2 xi_l g_par + xi_t1 g_h + xi_t2 g_v), the three xi independent.
    sum += std::pow(speed, 4) * (4.0 * g(0) * g(0) * s_l + (g(1) * g(1) + g(2) * g(2)) * s_t);
  }
  return intensity * intensity * sum;
}

double UnresolvedTurbulence::response_variance(double omega, double zeta, const Eigen::MatrixX3d& mean_wind,
                                               const Eigen::MatrixX3d& projections, double intensity,
                                               double window) const {
  check_mean_wind(mean_wind, projections, intensity, window);
  if (!(std::isfinite(omega) && omega > 0.0)) fail(fmt::format("omega must be > 0 rad/s, got {}", omega));
  if (!(std::isfinite(zeta) && zeta > 0.0)) fail(fmt::format("zeta must be > 0, got {}", zeta));
  const double travel = mean_wind.row(0).norm();
  if (travel == 0.0) return 0.0;
  const double f_lo = travel * cutoff_wavenumber() / kTwoPi, f_hi = travel * nyquist_wavenumber() / kTwoPi;
  auto integrand = [&](double f) {
    const double w = kTwoPi * f;
    const std::complex<double> h = 1.0 / std::complex<double>(omega * omega - w * w, 2.0 * zeta * omega * w);
    // The band's own spectrum right up to its edges (modal_force_spectrum is 0 on them), so that the
    // quadrature sees no jump at its end points.
    return std::norm(h) * in_band_force_spectrum(f, mean_wind, projections, intensity, window);
  };
  const double f_n = omega / kTwoPi, half_width = zeta * f_n;
  std::vector<double> breaks;
  for (double b : kResonanceBreaks) {
    breaks.push_back(f_n - b * half_width);
    breaks.push_back(f_n + b * half_width);
  }
  return integrate(integrand, f_lo, f_hi, std::move(breaks));
}

Eigen::Matrix3d unresolved_wind_frame(const Eigen::Vector3d& v) {
  const double speed = v.norm();
  if (!(speed > 0.0)) fail("the wind frame needs a non-zero wind");
  const Eigen::Vector3d e_par = v / speed;
  Eigen::Vector3d e_h(-e_par.y(), e_par.x(), 0.0);  // z x e_par
  const double horizontal = e_h.norm();
  e_h = horizontal > kVerticalWind ? Eigen::Vector3d(e_h / horizontal) : Eigen::Vector3d::UnitX();
  Eigen::Matrix3d frame;
  frame.col(0) = e_par;
  frame.col(1) = e_h;
  frame.col(2) = e_par.cross(e_h);
  return frame;
}

Eigen::Vector3d unresolved_fluctuation(const Eigen::Vector3d& v, const Eigen::Vector3d& xi,
                                       double intensity) {
  const double speed = v.norm();
  if (speed == 0.0) return Eigen::Vector3d::Zero();
  return intensity * speed * (unresolved_wind_frame(v) * xi);
}

Eigen::Vector3d linearised_drag_increment(const Eigen::Vector3d& v, const Eigen::Vector3d& v_prime) {
  const double speed = v.norm();
  if (speed == 0.0) return Eigen::Vector3d::Zero();
  return speed * v_prime + v * (v.dot(v_prime) / speed);
}

}  // namespace fw::trees
