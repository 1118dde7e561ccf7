#include "host/stages/wind/PressureProjection.hpp"

#include "fluid/PressureLevels.hpp"
#include "host/stages/SavedStateNames.hpp"

namespace fw::host {

PressureProjection::PressureProjection(const WindPartContext& context)
    : context_(context),
      solver_(context.cc, context.setup.spec,
              fluid::build_pressure_levels(context.setup.spec, context.setup.solid),
              context.setup.settings.pressure, context.seam.pressure_blocks()) {}

std::size_t PressureProjection::estimate_device_bytes(const fluid::GridSpec& spec, const BlockShare& share) {
  return PressureSolver::estimate_device_bytes(spec, share);
}

std::size_t PressureProjection::device_bytes() const {
  return estimate_device_bytes(context_.setup.spec, context_.seam.share());
}

PressureSolveStatus PressureProjection::project(DeviceVelocity& vel) {
  FluidStages& stages = context_.stages;
  PressureSolveStatus status;
  context_.clock.time("divergence", [&] { stages.enqueue_divergence_rhs(mask(), vel, solver_.rhs()); });
  context_.clock.time("pressure", [&] { status = solver_.solve(); });
  context_.clock.time("gradient", [&] {
    for (int c = 0; c < 3; ++c)
      stages.enqueue_subtract_gradient(c, mask(), solver_.solution(), vel.component(c));
    context_.seam.exchange(vel);
  });
  return status;
}

std::vector<float> PressureProjection::download_pressure(double dt) {
  std::vector<float> phi(context_.seam.local().cell_count());
  context_.cc.queue().enqueueReadBuffer(solver_.solution(), CL_TRUE, 0, phi.size() * sizeof(float),
                                        phi.data());
  const double inv_dt = dt > 0.0 ? 1.0 / dt : 0.0;
  for (auto& p : phi) p = static_cast<float>(p * inv_dt);
  return phi;
}

void PressureProjection::save_state(StageState& state) {
  state.save(context_.cc, saved::kPressureSolution, solver_.solution());
}

void PressureProjection::restore_state(const StageState& state) {
  state.restore(context_.cc, kWindGridState, saved::kPressureSolution, solver_.solution());
}

std::vector<GridArray> PressureProjection::saved_arrays() const {
  return {{saved::kPressureSolution, -1}};
}

}  // namespace fw::host
