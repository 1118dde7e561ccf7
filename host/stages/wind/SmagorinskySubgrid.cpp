#include "host/stages/wind/SmagorinskySubgrid.hpp"

namespace fw::host {

SmagorinskySubgrid::SmagorinskySubgrid(const WindPartContext& context, cl::Buffer& mask)
    : SubgridModel(context, mask) {}

void SmagorinskySubgrid::update_eddy_viscosity(WindFields& fields, float cap, cl::Buffer*) {
  context_.stages.enqueue_eddy_viscosity(static_cast<float>(context_.setup.settings.smagorinsky_constant),
                                         cap, mask_, fields.vel, eddy_viscosity_);
}

}  // namespace fw::host
