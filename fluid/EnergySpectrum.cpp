#include "fluid/EnergySpectrum.hpp"

#include <fftw3.h>
#include <fmt/format.h>

#include <cmath>
#include <stdexcept>

namespace fw::fluid {

std::vector<double> shell_energy_spectrum(const GridSpec& spec, const MacVelocity& vel) {
  const int n = spec.nx;
  bool periodic = spec.ny == n && spec.nz == n && n >= 4 && n % 2 == 0;
  for (int a = 0; a < 3; ++a) periodic = periodic && spec.periodic(a);
  if (!periodic)
    throw std::invalid_argument(
        fmt::format("shell_energy_spectrum: needs a periodic cube of an even n >= 4 cells, got {} x {} x {}",
                    spec.nx, spec.ny, spec.nz));
  if (vel.u.size() != spec.u_count() || vel.v.size() != spec.v_count() || vel.w.size() != spec.w_count())
    throw std::invalid_argument("shell_energy_spectrum: the velocity does not fit the grid");
  const std::size_t points = std::size_t(n) * n * n, half = std::size_t(n / 2 + 1);
  std::vector<double> in(points);
  fftw_complex* out = fftw_alloc_complex(std::size_t(n) * n * half);
  // FFTW's row-major order, z slowest: the last dimension (x) is the halved one.
  fftw_plan plan = fftw_plan_dft_r2c_3d(n, n, n, in.data(), out, FFTW_ESTIMATE);
  std::vector<double> shells(std::size_t(n / 2), 0.0);
  const double norm = 1.0 / (2.0 * double(points) * double(points));
  for (int c = 0; c < 3; ++c) {
    const auto& q = vel.component(c);
    const std::size_t ex = std::size_t(n) + (c == 0), ey = std::size_t(n) + (c == 1);
    for (int k = 0; k < n; ++k)
      for (int j = 0; j < n; ++j)
        for (int i = 0; i < n; ++i)
          in[std::size_t(i) + n * (std::size_t(j) + n * std::size_t(k))] =
              q[std::size_t(i) + ex * (std::size_t(j) + ey * std::size_t(k))];
    fftw_execute(plan);
    for (int k = 0; k < n; ++k)
      for (int j = 0; j < n; ++j)
        for (int i = 0; i < int(half); ++i) {
          const double mx = i, my = j <= n / 2 ? j : j - n, mz = k <= n / 2 ? k : k - n;
          const long m = std::lround(std::sqrt(mx * mx + my * my + mz * mz));
          if (m < 1 || m > n / 2) continue;
          const fftw_complex& z = out[std::size_t(i) + half * (std::size_t(j) + n * std::size_t(k))];
          // The half spectrum holds each k with 0 < i < n/2 once for it and once for -k.
          const double weight = (i == 0 || i == n / 2) ? 1.0 : 2.0;
          shells[std::size_t(m - 1)] += weight * norm * (z[0] * z[0] + z[1] * z[1]);
        }
  }
  fftw_destroy_plan(plan);
  fftw_free(out);
  return shells;
}

}  // namespace fw::fluid
