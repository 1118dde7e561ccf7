#include "io/WindFrame.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <cmath>
#include <stdexcept>
#include <string>
#include <utility>

namespace fw::io {
namespace {

void require_mac_sizes(const char* function, const fluid::GridSpec& spec, const fluid::MacVelocity& vel) {
  const std::size_t expected[3] = {spec.u_count(), spec.v_count(), spec.w_count()};
  for (int c = 0; c < 3; ++c) {
    if (vel.component(c).size() != expected[c]) {
      throw std::invalid_argument(fmt::format("{}: expected {} {} values for a {}x{}x{} grid, got {}",
                                              function, expected[c], "uvw"[c], spec.nx, spec.ny, spec.nz,
                                              vel.component(c).size()));
    }
  }
}

template <typename T>
void require_optional(const char* name, const std::vector<T>& values, std::size_t cells) {
  if (!values.empty() && values.size() != cells) {
    throw std::invalid_argument(fmt::format("WindFrame: {}: expected 0 or {} values (one per cell), got {}",
                                            name, cells, values.size()));
  }
}

}  // namespace

void WindFrame::validate() const {
  if (dims[0] <= 0 || dims[1] <= 0 || dims[2] <= 0) {
    throw std::invalid_argument(fmt::format("WindFrame: dims: expected positive cell counts, got {}x{}x{}",
                                            dims[0], dims[1], dims[2]));
  }
  if (!(h > 0.0) || !std::isfinite(h)) {
    throw std::invalid_argument(fmt::format("WindFrame: h: expected a finite cell size > 0, got {}", h));
  }
  const std::size_t cells = cell_count();
  if (velocity.size() != 3 * cells) {
    throw std::invalid_argument(fmt::format("WindFrame: velocity: expected {} values (3 per cell), got {}",
                                            3 * cells, velocity.size()));
  }
  require_optional("pressure", pressure, cells);
  require_optional("solid", solid, cells);
  require_optional("canopy_density", canopy_density, cells);
}

std::vector<float> cell_centred_velocity(const fluid::GridSpec& spec, const fluid::MacVelocity& vel) {
  require_mac_sizes("cell_centred_velocity", spec, vel);
  const std::size_t nx = std::size_t(spec.nx), ny = std::size_t(spec.ny), nz = std::size_t(spec.nz);
  std::vector<float> out(3 * nx * ny * nz);
  for (std::size_t k = 0; k < nz; ++k) {
    for (std::size_t j = 0; j < ny; ++j) {
      for (std::size_t i = 0; i < nx; ++i) {
        const std::size_t cell = i + nx * (j + ny * k);
        // The two faces of the cell along each axis: index +1 along that axis in the component's own array.
        const std::size_t u0 = i + (nx + 1) * (j + ny * k);
        const std::size_t v0 = i + nx * (j + (ny + 1) * k);
        const std::size_t w0 = i + nx * (j + ny * k);
        out[3 * cell + 0] = float(0.5 * (double(vel.u[u0]) + vel.u[u0 + 1]));
        out[3 * cell + 1] = float(0.5 * (double(vel.v[v0]) + vel.v[v0 + nx]));
        out[3 * cell + 2] = float(0.5 * (double(vel.w[w0]) + vel.w[w0 + nx * ny]));
      }
    }
  }
  return out;
}

WindFrame make_wind_frame(const fluid::GridSpec& spec, const fluid::MacVelocity& vel,
                          std::vector<float> pressure, std::vector<std::uint8_t> solid,
                          std::vector<float> canopy_density, double time, long step) {
  WindFrame frame;
  frame.dims = {spec.nx, spec.ny, spec.nz};
  frame.h = spec.h;
  frame.origin = spec.origin;
  for (int a = 0; a < 3; ++a) frame.periodic[std::size_t(a)] = spec.periodic(a);
  frame.time = time;
  frame.step = step;
  frame.velocity = cell_centred_velocity(spec, vel);
  frame.pressure = std::move(pressure);
  frame.solid = std::move(solid);
  frame.canopy_density = std::move(canopy_density);
  frame.validate();
  return frame;
}

std::vector<float> wind_speed(const WindFrame& frame) {
  frame.validate();
  const std::size_t cells = frame.cell_count();
  std::vector<float> speed(cells);
  for (std::size_t c = 0; c < cells; ++c) {
    const double x = frame.velocity[3 * c], y = frame.velocity[3 * c + 1], z = frame.velocity[3 * c + 2];
    speed[c] = float(std::sqrt(x * x + y * y + z * z));
  }
  return speed;
}

std::vector<float> wind_vorticity(const WindFrame& frame) {
  frame.validate();
  const int n[3] = {frame.dims[0], frame.dims[1], frame.dims[2]};
  const std::size_t stride[3] = {1, std::size_t(n[0]), std::size_t(n[0]) * n[1]};
  std::vector<float> out(3 * frame.cell_count());

  for (int k = 0; k < n[2]; ++k) {
    for (int j = 0; j < n[1]; ++j) {
      for (int i = 0; i < n[0]; ++i) {
        const int index[3] = {i, j, k};
        const std::size_t cell = frame.cell_index(i, j, k);
        // d[a][c] = d(velocity_c)/d(x_a): central inside and across a periodic axis' seam, one-sided in
        // the edge cells of another axis.
        double d[3][3] = {};
        for (int a = 0; a < 3; ++a) {
          if (n[a] == 1) continue;
          const bool wraps = frame.periodic[std::size_t(a)];
          const int lo = wraps ? (index[a] + n[a] - 1) % n[a] : std::max(index[a] - 1, 0);
          const int hi = wraps ? (index[a] + 1) % n[a] : std::min(index[a] + 1, n[a] - 1);
          const std::size_t cell_lo = cell - std::size_t(index[a]) * stride[a] + std::size_t(lo) * stride[a];
          const std::size_t cell_hi = cell - std::size_t(index[a]) * stride[a] + std::size_t(hi) * stride[a];
          const double span = (wraps ? 2 : hi - lo) * frame.h;
          for (int c = 0; c < 3; ++c) {
            d[a][c] = (double(frame.velocity[3 * cell_hi + c]) - frame.velocity[3 * cell_lo + c]) / span;
          }
        }
        out[3 * cell + 0] = float(d[1][2] - d[2][1]);  // dw/dy - dv/dz
        out[3 * cell + 1] = float(d[2][0] - d[0][2]);  // du/dz - dw/dx
        out[3 * cell + 2] = float(d[0][1] - d[1][0]);  // dv/dx - du/dy
      }
    }
  }
  return out;
}

std::array<float, 3> sample_velocity(const fluid::GridSpec& spec, const fluid::MacVelocity& vel,
                                     const std::array<double, 3>& world_position) {
  require_mac_sizes("sample_velocity", spec, vel);
  for (double p : world_position) {
    if (!std::isfinite(p)) {
      throw std::invalid_argument(fmt::format("sample_velocity: expected a finite position, got ({}, {}, {})",
                                              world_position[0], world_position[1], world_position[2]));
    }
  }
  const int n[3] = {spec.nx, spec.ny, spec.nz};
  std::array<float, 3> result{};
  for (int c = 0; c < 3; ++c) {
    // Component c's samples sit at integer cell coordinates along axis c and at half-integers elsewhere.
    int extent[3];
    int base[3];
    double frac[3];
    for (int a = 0; a < 3; ++a) {
      extent[a] = n[a] + (a == c ? 1 : 0);
      double x = (world_position[a] - spec.origin[a]) / spec.h - (a == c ? 0.0 : 0.5);
      x = std::clamp(x, 0.0, double(extent[a] - 1));
      // The last sample along an axis is reached as base extent-2 with weight 1 (or base 0 for one sample).
      base[a] = std::min(int(std::floor(x)), std::max(extent[a] - 2, 0));
      frac[a] = extent[a] == 1 ? 0.0 : x - base[a];
    }
    const std::vector<float>& q = vel.component(c);
    auto at = [&](int di, int dj, int dk) {
      const std::size_t i = std::size_t(std::min(base[0] + di, extent[0] - 1));
      const std::size_t j = std::size_t(std::min(base[1] + dj, extent[1] - 1));
      const std::size_t k = std::size_t(std::min(base[2] + dk, extent[2] - 1));
      return double(q[i + std::size_t(extent[0]) * (j + std::size_t(extent[1]) * k)]);
    };
    double value = 0.0;
    for (int corner = 0; corner < 8; ++corner) {
      const int di = corner & 1, dj = (corner >> 1) & 1, dk = (corner >> 2) & 1;
      const double weight =
          (di ? frac[0] : 1.0 - frac[0]) * (dj ? frac[1] : 1.0 - frac[1]) * (dk ? frac[2] : 1.0 - frac[2]);
      if (weight != 0.0) value += weight * at(di, dj, dk);
    }
    result[std::size_t(c)] = float(value);
  }
  return result;
}

}  // namespace fw::io
