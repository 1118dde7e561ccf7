#include "host/stages/wind/SemiLagrangianAdvection.hpp"

#include <utility>

namespace fw::host {

SemiLagrangianAdvection::SemiLagrangianAdvection(const WindPartContext& context)
    : Advection(context), padded_(context.stages.allocate_padded_velocity()) {}

std::size_t SemiLagrangianAdvection::estimate_device_bytes(const fluid::GridSpec& grid) {
  return FluidStages::padded_velocity_bytes(grid);
}

void SemiLagrangianAdvection::advect(WindFields& fields, float dt, const StageEnd&) {
  FluidStages& stages = context_.stages;
  stages.enqueue_pad(fields.vel, padded_);
  for (int c = 0; c < 3; ++c)
    stages.enqueue_advect(c, dt, padded_, padded_.component(c), fields.tmp.component(c));
  std::swap(fields.vel, fields.tmp);
  context_.seam.exchange(fields.vel);
}

}  // namespace fw::host
