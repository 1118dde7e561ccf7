#include "host/stages/wind/TkeSubgrid.hpp"

#include <fmt/format.h>

#include <cmath>
#include <stdexcept>

#include "host/stages/SavedStateNames.hpp"

namespace fw::host {

TkeSubgrid::TkeSubgrid(const WindPartContext& context, cl::Buffer& mask)
    : SubgridModel(context, mask),
      energy_(context.cc.buffer(context.seam.local().cell_count() * sizeof(float))),
      advected_energy_(context.cc.buffer(context.seam.local().cell_count() * sizeof(float))) {}

std::size_t TkeSubgrid::estimate_device_bytes(const fluid::GridSpec& grid) {
  return 3 * eddy_viscosity_bytes(grid);
}

void TkeSubgrid::start_energy(WindFields& fields) {
  if (energy_set_) return;
  context_.stages.enqueue_tke_equilibrium(mask_, fields.vel, energy_);
  context_.seam.exchange_cells(energy_);
  energy_set_ = true;
}

void TkeSubgrid::update_eddy_viscosity(WindFields& fields, float cap, cl::Buffer* drag_density) {
  // nu_t from e^n (it also diffuses the velocity), then e^n advected into advected_energy_, then the update
  // back into energy_; all read the forced velocity.
  FluidStages& stages = context_.stages;
  start_energy(fields);
  stages.enqueue_tke_viscosity(cap, mask_, energy_, eddy_viscosity_);
  context_.seam.exchange_cells(eddy_viscosity_);
  stages.enqueue_tke_advect(mask_, fields.vel, energy_, advected_energy_);
  // The update's diffusion reads the advected e of the cells beside each one: across a cut, the halo's.
  context_.seam.exchange_cells(advected_energy_);
  stages.enqueue_tke_update(cap, mask_, fields.vel, eddy_viscosity_, drag_density, advected_energy_, energy_);
  context_.seam.exchange_cells(energy_);
}

std::vector<float> TkeSubgrid::download_subgrid_energy(WindFields& fields) {
  start_energy(fields);
  std::vector<float> energy(context_.seam.local().cell_count());
  context_.cc.queue().enqueueReadBuffer(energy_, CL_TRUE, 0, energy.size() * sizeof(float), energy.data());
  return energy;
}

void TkeSubgrid::upload_subgrid_energy(const std::vector<float>& energy) {
  const std::size_t cells = context_.seam.local().cell_count();
  if (energy.size() != cells)
    throw std::invalid_argument(
        fmt::format("WindGrid: subgrid energy has {} cells, the grid {}", energy.size(), cells));
  for (float e : energy)
    if (!std::isfinite(e) || e < 0.0f)
      throw std::invalid_argument(fmt::format("WindGrid: subgrid energy must be finite and >= 0, got {}", e));
  context_.cc.queue().enqueueWriteBuffer(energy_, CL_TRUE, 0, energy.size() * sizeof(float), energy.data());
  energy_set_ = true;
}

void TkeSubgrid::save_state(StageState& state) {
  SubgridModel::save_state(state);
  if (energy_set_) state.save(context_.cc, saved::kSubgridEnergy, energy_);
}

void TkeSubgrid::restore_state(const StageState& state) {
  SubgridModel::restore_state(state);
  // Without a saved subgrid energy the next stage starts it at equilibrium, as the run that saved it would.
  energy_set_ = state.buffers.count(saved::kSubgridEnergy) > 0;
  if (energy_set_) state.restore(context_.cc, kWindGridState, saved::kSubgridEnergy, energy_);
}

std::vector<GridArray> TkeSubgrid::saved_arrays() const {
  std::vector<GridArray> arrays = SubgridModel::saved_arrays();
  arrays.push_back({saved::kSubgridEnergy, -1});
  return arrays;
}

}  // namespace fw::host
