#include "host/stages/wind/MacCormackAdvection.hpp"

#include <utility>

namespace fw::host {

MacCormackAdvection::MacCormackAdvection(const WindPartContext& context)
    : Advection(context),
      padded_(context.stages.allocate_padded_velocity()),
      padded_forward_(context.stages.allocate_padded_velocity()),
      back_(context.stages.allocate_velocity()) {}

std::size_t MacCormackAdvection::estimate_device_bytes(const fluid::GridSpec& grid) {
  return 2 * FluidStages::padded_velocity_bytes(grid) + FluidStages::velocity_bytes(grid);
}

void MacCormackAdvection::advect(WindFields& fields, float dt, const StageEnd&) {
  FluidStages& stages = context_.stages;
  // Forward into tmp, backward (from tmp's padded copy) into back, corrected in place in back.
  stages.enqueue_pad(fields.vel, padded_);
  for (int c = 0; c < 3; ++c)
    stages.enqueue_advect(c, dt, padded_, padded_.component(c), fields.tmp.component(c));
  context_.seam.exchange(fields.tmp);
  stages.enqueue_pad(fields.tmp, padded_forward_);
  for (int c = 0; c < 3; ++c)
    stages.enqueue_advect(c, -dt, padded_, padded_forward_.component(c), back_.component(c));
  for (int c = 0; c < 3; ++c)
    stages.enqueue_maccormack_correct(c, padded_, padded_.component(c), fields.tmp.component(c),
                                      back_.component(c), back_.component(c));
  std::swap(fields.vel, back_);
  context_.seam.exchange(fields.vel);
}

}  // namespace fw::host
