#include "host/stages/wind/WindBoundaries.hpp"

#include <fmt/format.h>

#include <cmath>
#include <stdexcept>

namespace fw::host {

WindBoundaries::WindBoundaries(const WindPartContext& context, cl::Buffer& mask)
    : context_(context),
      mask_(mask),
      profile_shape_(context.setup.profile.sample_cell_centres(context.setup.spec.nz, context.setup.spec.h)) {
  const std::vector<float> values = inflow_buffer_values(inflow_state(), context.seam.local());
  inflow_ = context.cc.buffer(values.size() * sizeof(float));
  context.cc.queue().enqueueWriteBuffer(inflow_, CL_TRUE, 0, values.size() * sizeof(float), values.data());
  context.stages.set_profile(inflow_);
}

std::size_t WindBoundaries::turbulence_bytes(const fluid::GridSpec& grid,
                                             const fluid::TurbulenceBoxSpec& box) {
  constexpr std::size_t kComponents = 3;  // u, v, w a point
  return (box.point_count() * kComponents + std::size_t(fw_shell_face_offset(grid.nx, grid.ny, grid.nz, 6))) *
         sizeof(float);
}

std::size_t WindBoundaries::estimate_device_bytes(const fluid::GridSpec& grid,
                                                  const fluid::TurbulenceBoxSpec* box) {
  const std::size_t profile = std::size_t(grid.nz) * sizeof(float);
  return ComputeContext::allocation_bytes(profile + (box ? turbulence_bytes(grid, *box) : 0));
}

std::size_t WindBoundaries::device_bytes() const {
  const auto& box = context_.setup.turbulence;
  if (!box) return estimate_device_bytes(context_.seam.local(), nullptr);
  const fluid::TurbulenceBoxSpec spec = box->spec();
  return estimate_device_bytes(context_.seam.local(), &spec);
}

fluid::InflowState WindBoundaries::inflow_state() const {
  fluid::InflowState state;
  for (int a = 0; a < 3; ++a) state.ambient[a] = static_cast<float>(context_.setup.ambient[a]);
  state.profile = profile_shape_;
  state.turbulence = context_.setup.turbulence;
  state.turbulence_sigma = static_cast<float>(turbulence_sigma_);
  for (int a = 0; a < 3; ++a) state.turbulence_offset[a] = static_cast<float>(turbulence_offset_[a]);
  return state;
}

void WindBoundaries::set_turbulence_sigma(double sigma) {
  if (!(std::isfinite(sigma) && sigma >= 0.0))
    throw std::invalid_argument(fmt::format("WindGrid: turbulence sigma must be >= 0 m/s, got {}", sigma));
  turbulence_sigma_ = sigma;
  upload_step_inflow();
}

void WindBoundaries::advance(double dt) {
  if (const auto& box = context_.setup.turbulence) {
    // Taylor's hypothesis: the frozen box moves with the ambient wind; the offset stays within one box
    // length so that float positions keep their resolution over long runs.
    for (int a = 0; a < 3; ++a) {
      const double length = box->cells()[a] * box->spacing();
      turbulence_offset_[a] = std::fmod(turbulence_offset_[a] + context_.setup.ambient[a] * dt, length);
    }
  }
  upload_step_inflow();
}

void WindBoundaries::upload_step_inflow() {
  FwStep s = context_.stages.step();
  const fluid::InflowState inflow = inflow_state();
  for (int a = 0; a < 3; ++a) s.ambient[a] = inflow.ambient[a];
  set_step_turbulence(s, inflow);
  context_.stages.set_step(s);
}

void WindBoundaries::enforce(DeviceVelocity& vel) {
  for (int c = 0; c < 3; ++c) context_.stages.enqueue_enforce_boundaries(c, mask_, vel.component(c));
  context_.seam.copy_seam(vel);
}

fluid::MacVelocity WindBoundaries::initial_field() const {
  const fluid::GridSpec& spec = context_.seam.local();
  const fluid::InflowState inflow = inflow_state();
  fluid::MacVelocity vel(spec);
  for (int c = 0; c < 3; ++c) {
    const int ex = spec.nx + (c == 0), ey = spec.ny + (c == 1), ez = spec.nz + (c == 2);
    auto& q = vel.component(c);
    for (int k = 0; k < ez; ++k)
      for (int j = 0; j < ey; ++j)
        for (int i = 0; i < ex; ++i)
          q[std::size_t(i) + std::size_t(ex) * (j + std::size_t(ey) * k)] =
              static_cast<float>(inflow.value(spec, c, i, j, k, k));
  }
  return vel;
}

void WindBoundaries::save_state(StageState& state) {
  state.numbers["turbulence_sigma"] = {turbulence_sigma_};
  state.numbers["turbulence_offset"] = {turbulence_offset_.begin(), turbulence_offset_.end()};
}

void WindBoundaries::restore_state(const StageState& state) {
  turbulence_sigma_ = state.number(kWindGridState, "turbulence_sigma", 1)[0];
  const std::vector<double>& offset = state.number(kWindGridState, "turbulence_offset", 3);
  std::copy(offset.begin(), offset.end(), turbulence_offset_.begin());
}

}  // namespace fw::host
