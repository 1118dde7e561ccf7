// Deardorff's subgrid-energy model (solver.subgrid: tke; fluid/SubgridTke.hpp): each step the energy e is
// advected, diffused, produced by the resolved strain and the canopy's wakes, and dissipated; nu_t =
// min(C_m l sqrt(e), cap). e starts in equilibrium with the strain of the first field it sees.
//
//   fw::host::TkeSubgrid subgrid(context, mask);
//   subgrid.apply(fields, dt, canopy_drag_density);
//   std::vector<float> e = subgrid.download_subgrid_energy(fields);
#pragma once

#include "host/stages/wind/SubgridModel.hpp"

namespace fw::host {

class TkeSubgrid : public SubgridModel {
 public:
  TkeSubgrid(const WindPartContext& context, cl::Buffer& mask);
  /// nu_t, e and the advected e of a step: three floats a cell.
  static std::size_t estimate_device_bytes(const fluid::GridSpec& grid);
  std::size_t device_bytes() const override { return estimate_device_bytes(context_.seam.local()); }

  /// e, m^2/s^2 a cell (0 in solids); started in equilibrium with fields.vel when it holds none yet.
  std::vector<float> download_subgrid_energy(WindFields& fields) override;
  /// Sets e (finite, >= 0, a float a cell) for the next step; std::invalid_argument otherwise.
  void upload_subgrid_energy(const std::vector<float>& energy) override;
  void restart() override { energy_set_ = false; }
  cl::Buffer* subgrid_energy() override { return energy_set_ ? &energy_ : nullptr; }
  void save_state(StageState& state) override;
  void restore_state(const StageState& state) override;
  std::vector<GridArray> saved_arrays() const override;

 private:
  void update_eddy_viscosity(WindFields& fields, float cap, cl::Buffer* drag_density) override;
  /// e in equilibrium with the strain of vel, unless e holds a state.
  void start_energy(WindFields& fields);

  cl::Buffer energy_, advected_energy_;
  bool energy_set_ = false;  // energy_ holds a state (else the next stage starts it at equilibrium)
};

}  // namespace fw::host
