// Face velocities of a MAC grid on the host: the plain data that the device wind grid downloads and
// uploads, the writers read, and the CPU reference computes with.
//
//   fw::fluid::MacVelocity vel(spec);            // every face 0 m/s
//   vel.component(0).size() == spec.u_count();
#pragma once

#include <array>
#include <vector>

#include "fluid/GridSpec.hpp"

namespace fw::fluid {

/// Face velocities of a MAC grid, m/s. Sizes: u (nx+1)*ny*nz, v nx*(ny+1)*nz, w nx*ny*(nz+1), x-fastest.
struct MacVelocity {
  std::vector<float> u, v, w;
  MacVelocity() = default;
  explicit MacVelocity(const GridSpec& spec)
      : u(spec.u_count(), 0.f), v(spec.v_count(), 0.f), w(spec.w_count(), 0.f) {}
  std::vector<float>& component(int c) { return c == 0 ? u : (c == 1 ? v : w); }
  const std::vector<float>& component(int c) const { return c == 0 ? u : (c == 1 ? v : w); }
};

}  // namespace fw::fluid
