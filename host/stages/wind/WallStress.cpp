#include "host/stages/wind/WallStress.hpp"

#include "fluid/SubgridStress.hpp"

namespace fw::host {

WallFaces WallStress::block_wall_faces(const WindGridSetup& setup, const BlockShare& share) {
  // The block's solids, halo included.
  const fluid::GridSpec local = share.local(setup.spec);
  const std::vector<std::uint8_t> solid =
      setup.solid.empty() ? setup.solid : share.cut(setup.solid, setup.spec);
  return list_wall_faces(local, fluid::wall_cells(local, solid));
}

WallStress::WallStress(const WindPartContext& context)
    : context_(context),
      list_(block_wall_faces(context.setup, context.seam.share())),
      faces_(context.stages.upload_wall_faces(list_)),
      drag_coefficient_(
          fluid::wall_drag_coefficient(context.setup.spec.h, context.setup.settings.wall_roughness_length)) {}

std::size_t WallStress::estimate_device_bytes(const WindGridSetup& setup, const BlockShare& share) {
  return FluidStages::wall_faces_bytes(block_wall_faces(setup, share));
}

void WallStress::apply(WindFields& fields) {
  context_.stages.enqueue_wall_stress(static_cast<float>(drag_coefficient_), faces_, fields.vel);
  context_.seam.exchange(fields.vel);
}

}  // namespace fw::host
