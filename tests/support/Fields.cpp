#include "tests/support/Fields.hpp"

#include <algorithm>
#include <cmath>
#include <memory>
#include <numbers>

#include "fluid/SolidMap.hpp"
#include "fluid/TurbulenceBox.hpp"

namespace fw::test {

fluid::GridSpec mixed_boundary_spec() {
  fluid::GridSpec spec;
  spec.nx = 24;
  spec.ny = 16;
  spec.nz = 12;
  spec.h = 2.0;
  spec.origin = {-10.0, 5.0, 0.0};
  using B = fluid::BoundaryType;
  spec.boundary = {B::inflow, B::outflow, B::periodic, B::periodic, B::no_slip, B::slip};
  return spec;
}

fluid::GridSpec ragged_spec() {
  fluid::GridSpec spec = mixed_boundary_spec();
  spec.nx = 37;
  spec.ny = 23;
  spec.nz = 11;
  spec.boundary[FW_FACE_SOUTH] = fluid::BoundaryType::slip;
  spec.boundary[FW_FACE_NORTH] = fluid::BoundaryType::no_slip;
  return spec;
}

std::vector<std::uint8_t> box_solid(const fluid::GridSpec& spec) {
  fluid::SolidMap solids(spec);
  const double L[3] = {spec.nx * spec.h, spec.ny * spec.h, spec.nz * spec.h};
  solids.add(fluid::SolidBox{
      "test box",
      {spec.origin[0] + 0.45 * L[0], spec.origin[1] + 0.5 * L[1], spec.origin[2] + 0.3 * L[2]},
      {0.2 * L[0], 0.25 * L[1], 0.3 * L[2]},
      20.0 * std::numbers::pi / 180.0});
  return solids.cells();
}

fluid::InflowState test_inflow(const fluid::GridSpec& spec) {
  fluid::InflowProfile profile;
  profile.type = fluid::InflowProfile::Type::log;
  profile.reference_height = 10.0;
  profile.roughness_length = 0.5;
  fluid::InflowState inflow;
  inflow.ambient = {7.0f, 3.0f, 0.0f};
  inflow.profile = profile.sample_cell_centres(spec.nz, spec.h);
  return inflow;
}

std::vector<float> random_cells(std::size_t n, double amplitude, std::uint32_t seed) {
  std::mt19937 rng(seed);
  std::uniform_real_distribution<float> dist(float(-amplitude), float(amplitude));
  std::vector<float> out(n);
  for (auto& x : out) x = dist(rng);
  return out;
}

fluid::MacVelocity random_velocity(const fluid::GridSpec& spec, double amplitude, std::uint32_t seed) {
  fluid::MacVelocity vel;
  vel.u = random_cells(spec.u_count(), amplitude, seed);
  vel.v = random_cells(spec.v_count(), amplitude, seed + 1);
  vel.w = random_cells(spec.w_count(), amplitude, seed + 2);
  return vel;
}

fluid::MacVelocity smooth_velocity(const fluid::GridSpec& spec, const std::array<double, 3>& mean,
                                   const std::array<double, 3>& ripple) {
  fluid::MacVelocity vel;
  const int n[3] = {spec.nx, spec.ny, spec.nz};
  for (int c = 0; c < 3; ++c) {
    const int ex = fluid::reference::extent(spec, c, 0), ey = fluid::reference::extent(spec, c, 1),
              ez = fluid::reference::extent(spec, c, 2);
    auto& q = vel.component(c);
    q.resize(std::size_t(ex) * ey * ez);
    for (int k = 0; k < ez; ++k)
      for (int j = 0; j < ey; ++j)
        for (int i = 0; i < ex; ++i) {
          const int at[3] = {i, j, k};
          double wave = 0.0;
          for (int a = 0; a < 3; ++a)
            wave += std::sin(2.0 * std::numbers::pi * (at[a] + (a == c ? 0.0 : 0.5)) / n[a] + a + c);
          q[std::size_t(i) + std::size_t(ex) * (j + std::size_t(ey) * k)] =
              static_cast<float>(mean[c] + ripple[c] * wave / 3.0);
        }
  }
  return vel;
}

void match_periodic_faces(const fluid::GridSpec& spec, fluid::MacVelocity& vel) {
  for (int c = 0; c < 3; ++c) {
    if (!spec.periodic(c)) continue;
    const int ex = fluid::reference::extent(spec, c, 0), ey = fluid::reference::extent(spec, c, 1),
              ez = fluid::reference::extent(spec, c, 2);
    const int n = c == 0 ? spec.nx : (c == 1 ? spec.ny : spec.nz);
    for (int k = 0; k < ez; ++k)
      for (int j = 0; j < ey; ++j)
        for (int i = 0; i < ex; ++i) {
          int idx[3] = {i, j, k};
          if (idx[c] != n) continue;
          idx[c] = 0;
          vel.component(c)[fluid::reference::face_index(spec, c, i, j, k)] =
              vel.component(c)[fluid::reference::face_index(spec, c, idx[0], idx[1], idx[2])];
        }
  }
}

void upload(host::ComputeContext& cc, const std::vector<float>& host, cl::Buffer& device) {
  cc.queue().enqueueWriteBuffer(device, CL_TRUE, 0, host.size() * sizeof(float), host.data());
}

std::vector<float> download(host::ComputeContext& cc, cl::Buffer& device, std::size_t n) {
  std::vector<float> out(n);
  cc.queue().enqueueReadBuffer(device, CL_TRUE, 0, n * sizeof(float), out.data());
  return out;
}

void upload(host::ComputeContext& cc, const fluid::MacVelocity& host, host::DeviceVelocity& device) {
  for (int c = 0; c < 3; ++c) upload(cc, host.component(c), device.component(c));
}

double u_centre(const fluid::GridSpec& spec, const fluid::MacVelocity& vel, int i, int j, int k) {
  return 0.5 * (vel.u[fluid::reference::face_index(spec, 0, i, j, k)] +
                vel.u[fluid::reference::face_index(spec, 0, i + 1, j, k)]);
}

double u_at(const fluid::GridSpec& spec, const fluid::MacVelocity& vel, int i, int j, double z) {
  const double level = std::clamp(z / spec.h - 0.5, 0.0, spec.nz - 1.0);
  const int k0 = std::min(int(level), spec.nz - 1), k1 = std::min(k0 + 1, spec.nz - 1);
  const double t = level - k0;
  return (1 - t) * u_centre(spec, vel, i, j, k0) + t * u_centre(spec, vel, i, j, k1);
}

host::DeviceVelocity upload_velocity(host::ComputeContext& cc, const fluid::MacVelocity& host) {
  host::DeviceVelocity device;
  for (int c = 0; c < 3; ++c) device.component(c) = cc.upload(host.component(c));
  return device;
}

fluid::MacVelocity download(host::ComputeContext& cc, host::DeviceVelocity& device,
                            const fluid::GridSpec& spec) {
  fluid::MacVelocity out(spec);
  for (int c = 0; c < 3; ++c) out.component(c) = download(cc, device.component(c), out.component(c).size());
  return out;
}

void add_small_turbulence(fluid::InflowState& inflow) {
  fluid::TurbulenceBoxSpec box;
  box.cells = {8, 8, 6};
  box.spacing = 2.5;
  box.spectrum = {1.0, 5.0};
  box.seed = 3;
  inflow.turbulence = std::make_shared<const fluid::TurbulenceBox>(box);
  inflow.turbulence_sigma = 1.7f;
  inflow.turbulence_offset = {13.3f, -4.1f, 0.7f};
}

cl::Buffer upload_profile(host::ComputeContext& cc, const fluid::InflowState& inflow,
                          const fluid::GridSpec& spec) {
  const std::vector<float> values = host::inflow_buffer_values(inflow, spec);
  cl::Buffer buf = cc.buffer(values.size() * sizeof(float));
  upload(cc, values, buf);
  return buf;
}

double relative_error(const std::vector<float>& a, const std::vector<float>& b, double floor) {
  double scale = floor, diff = 0.0;
  for (std::size_t i = 0; i < b.size(); ++i) {
    scale = std::max(scale, std::abs(double(b[i])));
    const double d = std::abs(double(a[i]) - double(b[i]));
    diff = std::isnan(d) ? INFINITY : std::max(diff, d);
  }
  return diff / scale;
}

double relative_error(const fluid::MacVelocity& a, const fluid::MacVelocity& b) {
  double e = 0.0;
  for (int c = 0; c < 3; ++c) e = std::max(e, relative_error(a.component(c), b.component(c)));
  return e;
}

double mismatch_fraction(const std::vector<float>& a, const std::vector<float>& b, double tolerance) {
  double scale = 0.0;
  for (float x : b) scale = std::max(scale, std::abs(double(x)));
  std::size_t bad = 0;
  for (std::size_t i = 0; i < b.size(); ++i)
    if (!(std::abs(double(a[i]) - double(b[i])) <= tolerance * scale)) ++bad;
  return double(bad) / double(b.size());
}

fluid::MacVelocity sine_shear_velocity(const fluid::GridSpec& s) {
  fluid::MacVelocity vel(s);
  const double kx = 2.0 * std::numbers::pi / (s.nx * s.h), ky = 2.0 * std::numbers::pi / (s.ny * s.h);
  for (int k = 0; k < s.nz; ++k)
    for (int j = 0; j < s.ny; ++j)
      for (int i = 0; i <= s.nx; ++i)
        vel.u[std::size_t(i + (s.nx + 1) * (j + s.ny * k))] = float(
            SineShear::U0 + SineShear::G * (k + 0.5) * s.h + SineShear::C * std::sin(ky * (j + 0.5) * s.h));
  for (int k = 0; k < s.nz; ++k)
    for (int j = 0; j <= s.ny; ++j)
      for (int i = 0; i < s.nx; ++i)
        vel.v[std::size_t(i + s.nx * (j + (s.ny + 1) * k))] =
            float(SineShear::A * std::sin(kx * (i + 0.5) * s.h));
  for (int k = 0; k <= s.nz; ++k)
    for (int j = 0; j < s.ny; ++j)
      for (int i = 0; i < s.nx; ++i)
        vel.w[std::size_t(i + s.nx * (j + s.ny * k))] = float(SineShear::B * std::sin(kx * (i + 0.5) * s.h));
  return vel;
}

}  // namespace fw::test
