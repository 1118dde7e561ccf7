#include "host/stages/wind/SubgridModel.hpp"

#include <fmt/format.h>

#include <stdexcept>
#include <utility>

#include "fluid/SubgridStress.hpp"
#include "host/stages/SavedStateNames.hpp"
#include "host/stages/wind/SmagorinskySubgrid.hpp"
#include "host/stages/wind/TkeSubgrid.hpp"

namespace fw::host {

SubgridModel::SubgridModel(const WindPartContext& context, cl::Buffer& mask)
    : context_(context),
      mask_(mask),
      eddy_viscosity_(context.cc.zero_floats(context.seam.local().cell_count())) {}

std::size_t SubgridModel::eddy_viscosity_bytes(const fluid::GridSpec& grid) {
  return ComputeContext::allocation_bytes(grid.cell_count() * sizeof(float));
}

void SubgridModel::apply(WindFields& fields, double dt, cl::Buffer* drag_density) {
  // The strain and the diffusion read the forced velocity with the boundary rules for ghosts; the
  // diffusion writes out of place (into the scratch), then the fields swap.
  update_eddy_viscosity(fields, static_cast<float>(fluid::eddy_viscosity_cap(context_.setup.spec.h, dt)),
                        drag_density);
  // A halo cell across a cut periodic seam sees the seam's face n, which a whole grid reads as face 0 there
  // (the two differ between boundary passes): its nu_t is its owner's.
  context_.seam.exchange_cells(eddy_viscosity_);
  // Over a rough wall the log-law stress carries the wall's flux, so no eddy flux crosses into it.
  const bool wall_slip = context_.setup.settings.wall_roughness_length > 0.0;
  context_.stages.enqueue_diffuse_eddy(wall_slip, mask_, eddy_viscosity_, fields.vel, fields.tmp);
  std::swap(fields.vel, fields.tmp);
  context_.seam.exchange(fields.vel);
}

std::vector<float> SubgridModel::download_eddy_viscosity() {
  std::vector<float> viscosity(context_.seam.local().cell_count());
  context_.cc.queue().enqueueReadBuffer(eddy_viscosity_, CL_TRUE, 0, viscosity.size() * sizeof(float),
                                        viscosity.data());
  return viscosity;
}

std::vector<float> SubgridModel::download_subgrid_energy(WindFields&) {
  throw std::logic_error("WindGrid: no subgrid energy without solver.subgrid tke");
}

void SubgridModel::upload_subgrid_energy(const std::vector<float>&) {
  throw std::logic_error("WindGrid: no subgrid energy without solver.subgrid tke");
}

void SubgridModel::save_state(StageState& state) {
  state.save(context_.cc, saved::kEddyViscosity, eddy_viscosity_);
}

void SubgridModel::restore_state(const StageState& state) {
  state.restore(context_.cc, kWindGridState, saved::kEddyViscosity, eddy_viscosity_);
}

std::vector<GridArray> SubgridModel::saved_arrays() const {
  return {{saved::kEddyViscosity, -1}};
}

namespace {

enum class Chosen { none, smagorinsky, tke };

// The one rule: solver.subgrid tke, else Smagorinsky's while its constant is > 0.
Chosen chosen_model(const fluid::WindSettings& settings) {
  if (settings.subgrid == fluid::SubgridModel::tke) return Chosen::tke;
  return settings.smagorinsky_constant > 0.0 ? Chosen::smagorinsky : Chosen::none;
}

}  // namespace

std::unique_ptr<SubgridModel> make_subgrid_model(const WindPartContext& context, cl::Buffer& mask) {
  switch (chosen_model(context.setup.settings)) {
    case Chosen::tke:
      return std::make_unique<TkeSubgrid>(context, mask);
    case Chosen::smagorinsky:
      return std::make_unique<SmagorinskySubgrid>(context, mask);
    case Chosen::none:
      break;
  }
  return nullptr;
}

std::size_t subgrid_model_bytes(const fluid::WindSettings& settings, const fluid::GridSpec& grid) {
  switch (chosen_model(settings)) {
    case Chosen::tke:
      return TkeSubgrid::estimate_device_bytes(grid);
    case Chosen::smagorinsky:
      return SmagorinskySubgrid::estimate_device_bytes(grid);
    case Chosen::none:
      break;
  }
  return 0;
}

}  // namespace fw::host
