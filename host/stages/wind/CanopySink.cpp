#include "host/stages/wind/CanopySink.hpp"

#include <fmt/format.h>

#include <cmath>
#include <stdexcept>

namespace fw::host {

std::size_t CanopySink::estimate_device_bytes(const fluid::GridSpec& grid) {
  return ComputeContext::allocation_bytes(grid.cell_count() * sizeof(float));
}

void CanopySink::set(std::vector<float> drag_density, const fluid::DragLaw& law) {
  law.validate();
  law_ = law;
  const fluid::GridSpec& local = context_.seam.local();
  if (!drag_density.empty() && drag_density.size() == context_.setup.spec.cell_count())
    drag_density = context_.seam.cut(std::move(drag_density));
  bool any = false;
  if (!drag_density.empty()) {
    if (drag_density.size() != local.cell_count())
      throw std::invalid_argument(fmt::format("WindGrid: canopy drag density has {} cells, the grid {}",
                                              drag_density.size(), local.cell_count()));
    for (float k : drag_density) {
      if (!std::isfinite(k) || k < 0.0f)
        throw std::invalid_argument(
            fmt::format("WindGrid: canopy drag density must be finite and >= 0, got {}", k));
      any = any || k > 0.0f;
    }
  }
  // Over ranks the drag is on wherever any block has some: a block with none still takes part in the drag
  // step's halo exchange, as its neighbours do, or the ranks' messages pair up with the wrong exchanges. Its
  // density stays zero, as the same cells' are in one process.
  on_ = context_.seam.world().max(any ? 1.0 : 0.0) > 0.0;
  if (!on_) {
    drag_density_ = cl::Buffer();
    box_ = CellBox{};
    return;
  }
  box_ = nonzero_cell_box(local, drag_density);
  drag_density_ = context_.cc.buffer(drag_density.size() * sizeof(float));
  context_.cc.queue().enqueueWriteBuffer(drag_density_, CL_TRUE, 0, drag_density.size() * sizeof(float),
                                         drag_density.data());
}

void CanopySink::apply(WindFields& fields) {
  context_.stages.enqueue_canopy_drag(drag_density_, box_, fields.vel, fields.tmp, law_);
  context_.seam.exchange(fields.vel);
}

}  // namespace fw::host
