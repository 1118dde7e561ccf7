#include "fluid/TurbulenceBox.hpp"

#include <fftw3.h>
#include <fmt/format.h>

#include <algorithm>
#include <cmath>
#include <complex>
#include <cstring>
#include <limits>
#include <memory>
#include <mutex>
#include <numbers>
#include <random>
#include <stdexcept>
#include <type_traits>

namespace fw::fluid {

namespace {

constexpr int kComponents = 3;
// Each drawn half-spectrum mode stands for itself and its conjugate partner -k in the full lattice sum.
constexpr double kPartnerWeight = 2.0;

// FFTW's planner (plan creation and destruction) is not re-entrant.
std::mutex& planner_mutex() {
  static std::mutex m;
  return m;
}

struct FftwFree {
  void operator()(void* p) const { fftw_free(p); }
};
struct PlanFree {
  void operator()(fftw_plan p) const {
    std::lock_guard lock(planner_mutex());
    fftw_destroy_plan(p);
  }
};
using ComplexBuffer = std::unique_ptr<fftw_complex[], FftwFree>;
using RealBuffer = std::unique_ptr<double[], FftwFree>;

ComplexBuffer complex_buffer(std::size_t n) {
  ComplexBuffer b(fftw_alloc_complex(n));
  if (!b) throw std::bad_alloc();
  std::memset(b.get(), 0, n * sizeof(fftw_complex));
  return b;
}

// The signed wave index m of storage index i on an axis of n points (FFTW's order: 0, 1, ..., -1).
int signed_index(int i, int n) {
  return i <= n / 2 ? i : i - n;
}

constexpr std::size_t kNoPartner = std::numeric_limits<std::size_t>::max();

// Calls f(index, partner, k) for every drawn mode of the half spectrum, in the order the random numbers are
// drawn (header comment, "Random numbers"): index its place in the half spectrum, partner the place of its
// conjugate partner -k where that is stored too (on the k_x = 0 plane), else kNoPartner, and k its
// wavevector (rad/m).
template <typename F>
void visit_drawn_modes(const std::array<int, 3>& cells, const std::array<double, 3>& dk, F&& f) {
  const int nx = cells[0], ny = cells[1], nz = cells[2], hx = nx / 2 + 1;
  for (int iz = 0; iz < nz; ++iz) {
    if (iz == nz / 2) continue;  // Nyquist plane
    const int mz = signed_index(iz, nz);
    for (int iy = 0; iy < ny; ++iy) {
      if (iy == ny / 2) continue;
      const int my = signed_index(iy, ny);
      for (int ix = 0; ix < hx - 1; ++ix) {  // ix = nx / 2 is the Nyquist plane
        // On k_x = 0 only one of each pair (k, -k) is drawn; this also skips k = 0.
        if (ix == 0 && !(mz > 0 || (mz == 0 && my > 0))) continue;
        const std::size_t idx = (std::size_t(iz) * ny + iy) * hx + ix;
        const std::size_t partner =
            ix == 0 ? (std::size_t((nz - iz) % nz) * ny + (ny - iy) % ny) * hx : kNoPartner;
        f(idx, partner, std::array<double, 3>{dk[0] * ix, dk[1] * my, dk[2] * mz});
      }
    }
  }
}

}  // namespace

void TurbulenceBoxSpec::validate() const {
  static constexpr const char* kAxis = "xyz";
  for (int a = 0; a < kComponents; ++a) {
    if (cells[a] < kMinPoints || cells[a] % 2 != 0)
      throw std::invalid_argument(fmt::format("TurbulenceBox: cells along {} must be even and >= {}, got {}",
                                              kAxis[a], kMinPoints, cells[a]));
  }
  // Each count is < 2^31, so the product of the first two cannot overflow std::size_t.
  const std::size_t xy = std::size_t(cells[0]) * std::size_t(cells[1]);
  if (xy > kMaxPoints || xy * std::size_t(cells[2]) > kMaxPoints)
    throw std::invalid_argument(fmt::format("TurbulenceBox: {} x {} x {} points exceed the limit of {}",
                                            cells[0], cells[1], cells[2], kMaxPoints));
  if (!(std::isfinite(spacing) && spacing > 0.0))
    throw std::invalid_argument(fmt::format("TurbulenceBox: spacing must be > 0 m, got {}", spacing));
  try {
    spectrum.validate();
  } catch (const std::invalid_argument& e) {
    throw std::invalid_argument(fmt::format("TurbulenceBox: {}", e.what()));
  }
  for (int a = 0; a < kComponents; ++a) {
    if (!(std::isfinite(component_scale[a]) && component_scale[a] >= 0.0))
      throw std::invalid_argument(fmt::format(
          "TurbulenceBox: component_scale[{}] must be finite and >= 0, got {}", a, component_scale[a]));
  }
  if (!(std::isfinite(shortest_wavelength) && shortest_wavelength >= 0.0))
    throw std::invalid_argument(fmt::format(
        "TurbulenceBox: shortest_wavelength must be finite and >= 0 m, got {}", shortest_wavelength));
  if (sweep_axis < -1 || sweep_axis > 2)
    throw std::invalid_argument(
        fmt::format("TurbulenceBox: sweep_axis must be -1, 0, 1 or 2, got {}", sweep_axis));
}

TurbulenceBox::TurbulenceBox(const TurbulenceBoxSpec& spec) : spec_(spec) {
  spec_.validate();
  const int nx = spec_.cells[0], ny = spec_.cells[1], nz = spec_.cells[2];
  const int hx = nx / 2 + 1;  // x points of the half spectrum (FFTW's r2c/c2r layout)
  const std::size_t modes = std::size_t(hx) * ny * nz;
  const std::size_t points = spec_.point_count();
  const double h = spec_.spacing;
  constexpr double two_pi = 2.0 * std::numbers::pi;
  const std::array<double, 3> dk{two_pi / (nx * h), two_pi / (ny * h), two_pi / (nz * h)};
  const double dK = dk[0] * dk[1] * dk[2];
  const double k_max = spec_.shortest_wavelength > 0.0 ? two_pi / spec_.shortest_wavelength
                                                       : std::numeric_limits<double>::infinity();
  // a(k)^2 (header comment), or 0 for a mode above the shortest wavelength or one the sweep leaves still.
  const auto amplitude2 = [&](const std::array<double, 3>& k) {
    const double k2 = k[0] * k[0] + k[1] * k[1] + k[2] * k[2];
    if (k2 > k_max * k_max || (spec_.sweep_axis >= 0 && k[std::size_t(spec_.sweep_axis)] == 0.0)) return 0.0;
    return dK * spec_.spectrum.energy(std::sqrt(k2)) / (4.0 * std::numbers::pi * k2 * k2);
  };

  // S_a, summed over the full lattice (each drawn mode and its partner): the expected variances follow.
  std::array<double, 3> S{0.0, 0.0, 0.0};
  visit_drawn_modes(spec_.cells, dk, [&](std::size_t, std::size_t, const std::array<double, 3>& k) {
    const double a2 = amplitude2(k);
    for (int c = 0; c < kComponents; ++c) S[c] += kPartnerWeight * a2 * k[c] * k[c];
  });
  const double sigma2 = spec_.spectrum.sigma * spec_.spectrum.sigma;
  std::array<double, 3> variance{};  // V_c, with D = I
  for (int c = 0; c < kComponents; ++c) {
    variance[c] = S[(c + 1) % 3] + S[(c + 2) % 3];
    if (!(std::isfinite(variance[c]) && variance[c] > 0.0))
      throw std::invalid_argument(fmt::format(
          "TurbulenceBox: the {} x {} x {} lattice at {} m holds none of the spectrum with L_u = {} m", nx,
          ny, nz, h, spec_.spectrum.integral_length));
    resolved_fraction_[c] = variance[c] / sigma2;
  }
  // The vector potential's weights d_a, and what multiplies each component after the transform.
  // d_a^2 = sigma^2 (S_b + S_c - S_a) / (2 S_b S_c), b and c the other two axes, where all three are > 0.
  const auto others = [&](int a) { return std::array<double, 2>{S[(a + 1) % 3], S[(a + 2) % 3]}; };
  weights_balanced_ = true;
  for (int a = 0; a < kComponents; ++a)
    weights_balanced_ = weights_balanced_ && others(a)[0] + others(a)[1] > S[a];
  std::array<double, 3> weight{1.0, 1.0, 1.0}, factor{};
  for (int a = 0; a < kComponents; ++a) {
    const auto [sb, sc] = others(a);
    if (weights_balanced_) weight[a] = std::sqrt(sigma2 * (sb + sc - S[a]) / (2.0 * sb * sc));
    factor[a] =
        spec_.component_scale[a] * (weights_balanced_ ? 1.0 : spec_.spectrum.sigma / std::sqrt(variance[a]));
  }

  std::array<ComplexBuffer, kComponents> u_hat{complex_buffer(modes), complex_buffer(modes),
                                               complex_buffer(modes)};
  std::mt19937_64 rng(spec_.seed);
  std::normal_distribution<double> normal(0.0, 1.0);
  const double inv_sqrt2 = 1.0 / std::numbers::sqrt2;
  // Each drawn mode: its six numbers, then u_hat = a(k) k x (D n) and its stored partner, or nothing when
  // a(k) = 0 (the numbers drawn all the same, so that the other modes keep theirs).
  const auto draw_mode = [&](std::size_t idx, std::size_t partner, const std::array<double, 3>& k) {
    std::array<std::complex<double>, 3> n;
    for (int c = 0; c < kComponents; ++c) {
      const double re = normal(rng);
      const double im = normal(rng);
      n[c] = weight[c] * std::complex<double>{re * inv_sqrt2, im * inv_sqrt2};
    }
    const double amp = std::sqrt(amplitude2(k));
    if (amp == 0.0) return;
    const std::array<std::complex<double>, 3> kxn{k[1] * n[2] - k[2] * n[1], k[2] * n[0] - k[0] * n[2],
                                                  k[0] * n[1] - k[1] * n[0]};
    for (int c = 0; c < kComponents; ++c) {
      const std::complex<double> value = amp * kxn[c];
      u_hat[c][idx][0] = value.real();
      u_hat[c][idx][1] = value.imag();
      if (partner != kNoPartner) {
        u_hat[c][partner][0] = value.real();
        u_hat[c][partner][1] = -value.imag();
      }
    }
  };
  visit_drawn_modes(spec_.cells, dk, draw_mode);

  RealBuffer real(fftw_alloc_real(points));
  if (!real) throw std::bad_alloc();
  std::unique_ptr<std::remove_pointer_t<fftw_plan>, PlanFree> plan;
  {
    std::lock_guard lock(planner_mutex());
    // FFTW_ESTIMATE picks the algorithm without timing, so the plan (and the rounding) is the same every run.
    plan.reset(
        fftw_plan_dft_c2r_3d(nz, ny, nx, u_hat[0].get(), real.get(), FFTW_ESTIMATE | FFTW_DESTROY_INPUT));
  }
  if (!plan) throw std::runtime_error("TurbulenceBox: FFTW could not plan the transform");

  values_.resize(kComponents * points);
  std::array<double, 3> sum{}, sum2{};
  for (int c = 0; c < kComponents; ++c) {
    // fftw_malloc gives every buffer the same alignment, as the new-array execute requires.
    fftw_execute_dft_c2r(plan.get(), u_hat[c].get(), real.get());
    u_hat[c].reset();
    for (std::size_t p = 0; p < points; ++p) {
      const float v = static_cast<float>(factor[c] * real[p]);
      values_[kComponents * p + c] = v;
      sum[c] += v;
      sum2[c] += double(v) * v;
    }
  }
  for (int c = 0; c < kComponents; ++c) {
    const double mean = sum[c] / double(points);
    realised_sigma_[c] = std::sqrt(std::max(0.0, sum2[c] / double(points) - mean * mean));
  }
}

std::array<double, 3> TurbulenceBox::at(int i, int j, int k) const {
  const auto& n = spec_.cells;
  if (i < 0 || i >= n[0] || j < 0 || j >= n[1] || k < 0 || k >= n[2])
    throw std::invalid_argument(
        fmt::format("TurbulenceBox: point ({}, {}, {}) outside {} x {} x {}", i, j, k, n[0], n[1], n[2]));
  const std::size_t p = kComponents * (std::size_t(i) + std::size_t(n[0]) * (j + std::size_t(n[1]) * k));
  return {values_[p], values_[p + 1], values_[p + 2]};
}

std::array<double, 3> TurbulenceBox::sample(double x, double y, double z) const {
  if (!(std::isfinite(x) && std::isfinite(y) && std::isfinite(z)))
    throw std::invalid_argument(fmt::format("TurbulenceBox: cannot sample at ({}, {}, {})", x, y, z));
  const std::array<double, 3> pos{x, y, z};
  std::array<std::size_t, 3> lo{}, hi{};
  std::array<double, 3> t{};
  for (int a = 0; a < kComponents; ++a) {
    const double f = pos[a] / spec_.spacing;
    const double fl = std::floor(f);
    t[a] = f - fl;
    const int n = spec_.cells[a];
    double wrapped = std::fmod(fl, double(n));  // exact for integers, in (-n, n)
    if (wrapped < 0.0) wrapped += n;
    lo[a] = std::size_t(wrapped);
    hi[a] = lo[a] + 1 == std::size_t(n) ? 0 : lo[a] + 1;
  }
  const std::size_t nx = spec_.cells[0], nxy = nx * spec_.cells[1];
  std::array<double, 3> out{0.0, 0.0, 0.0};
  for (int corner = 0; corner < 8; ++corner) {
    const bool bx = corner & 1, by = corner & 2, bz = corner & 4;
    const double w = (bx ? t[0] : 1.0 - t[0]) * (by ? t[1] : 1.0 - t[1]) * (bz ? t[2] : 1.0 - t[2]);
    const std::size_t p =
        kComponents * ((bx ? hi[0] : lo[0]) + nx * (by ? hi[1] : lo[1]) + nxy * (bz ? hi[2] : lo[2]));
    for (int c = 0; c < kComponents; ++c) out[c] += w * values_[p + c];
  }
  return out;
}

TurbulenceBoxSpec inflow_box_spec(const std::array<int, 3>& box_cells, double h, double length_scale,
                                  double cutoff_cells, int sweep_axis, std::uint64_t seed) {
  TurbulenceBoxSpec spec;
  for (int a = 0; a < 3; ++a) spec.cells[a] = kTurbulencePointsPerCell * box_cells[a];
  spec.spacing = h / kTurbulencePointsPerCell;
  spec.spectrum = {1.0, length_scale};
  spec.seed = seed;
  spec.shortest_wavelength = std::max(kInflowShortestWavelengthCells, cutoff_cells) * h;
  spec.sweep_axis = sweep_axis;
  return spec;
}

}  // namespace fw::fluid
