#include "host/stages/wind/Upwind5Advection.hpp"

#include <utility>

#include "fluid/UpwindStencil.hpp"

namespace fw::host {
namespace {

// The whole grid's flux orders, cut to the block: a block's edge is no wall to them.
DeviceUpwindOrders block_orders(const WindPartContext& context) {
  fluid::UpwindOrders orders = fluid::upwind_orders(context.setup.spec, context.setup.solid);
  for (int c = 0; c < 3; ++c) orders[std::size_t(c)] = context.seam.cut(std::move(orders[std::size_t(c)]), c);
  return context.stages.upload_upwind_orders(orders);
}

}  // namespace

Upwind5Advection::Upwind5Advection(const WindPartContext& context)
    : Advection(context),
      padded_(context.stages.allocate_padded_velocity()),
      back_(context.stages.allocate_velocity()),
      orders_(block_orders(context)) {}

std::size_t Upwind5Advection::estimate_device_bytes(const fluid::GridSpec& grid) {
  return FluidStages::padded_velocity_bytes(grid) + FluidStages::velocity_bytes(grid) +
         FluidStages::upwind_orders_bytes(grid);
}

int Upwind5Advection::halo_cells(double) {
  return FW_PAD;
}

void Upwind5Advection::advect(WindFields& fields, float dt, const StageEnd& stage_end) {
  // Wicker & Skamarock's three stages from u at the step's start: u1 = u + dt/3 R(u), u2 = u + dt/2 R(u1),
  // u + dt R(u2). Stages alternate between tmp and back; each reads only the padded copy of the one before
  // and u itself. The first two get their prescribed faces back (and, if asked, a projection), as the last
  // does with the rest of the step.
  constexpr float kStageFractions[] = {1.0f / 3.0f, 0.5f, 1.0f};
  FluidStages& stages = context_.stages;
  DeviceVelocity* stage = &fields.vel;
  for (int n = 0; n < 3; ++n) {
    stages.enqueue_pad(*stage, padded_);
    DeviceVelocity& out = n == 1 ? back_ : fields.tmp;
    for (int c = 0; c < 3; ++c)
      stages.enqueue_upwind_stage(c, kStageFractions[n] * dt, padded_, orders_, fields.vel.component(c),
                                  out.component(c));
    if (n < 2) {
      stage_end(out);
      context_.seam.exchange(out);
    }
    stage = &out;
  }
  std::swap(fields.vel, fields.tmp);
  context_.seam.exchange(fields.vel);
}

}  // namespace fw::host
