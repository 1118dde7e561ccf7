// The subgrid model: an eddy viscosity nu_t for the turbulence the grid does not resolve, and the velocity
// diffused by it (the subgrid stress -2 nu_t S_ij), once a step after the canopy drag. One class per model,
// picked from the settings once:
//   SmagorinskySubgrid  solver.smagorinsky_constant > 0: nu_t = (C_s h)^2 |S| (fluid/SubgridStress.hpp);
//   TkeSubgrid          solver.subgrid: tke: Deardorff's subgrid energy e carried from step to step, and
//                       nu_t = C_m l sqrt(e) (fluid/SubgridTke.hpp).
//
//   std::unique_ptr<fw::host::SubgridModel> subgrid = fw::host::make_subgrid_model(context, mask);  // or
//   null subgrid->apply(fields, dt, canopy_drag_density);    // null: no canopy
#pragma once

#include <memory>
#include <vector>

#include "host/stages/wind/WindPart.hpp"

namespace fw::host {

class SubgridModel : public WindPart {
 public:
  /// nu_t from the model, then fields.vel <- fields.vel + dt div(nu_t grad vel), halos exchanged.
  /// drag_density: the canopy's k (1/m, a float a cell), which the tke model's sources and sinks read; null
  /// without a canopy.
  void apply(WindFields& fields, double dt, cl::Buffer* drag_density);
  /// nu_t of the last apply(), m^2/s, a float a cell (0 before the first).
  std::vector<float> download_eddy_viscosity();
  /// The model's subgrid energy, m^2/s^2 a cell: only the tke model keeps one (std::logic_error here).
  virtual std::vector<float> download_subgrid_energy(WindFields& fields);
  virtual void upload_subgrid_energy(const std::vector<float>& energy);
  /// The device's nu_t of the last apply() (the wind's statistics read it in place).
  cl::Buffer& eddy_viscosity() { return eddy_viscosity_; }
  /// The device's subgrid energy, where the model keeps one and it holds a state; else null.
  virtual cl::Buffer* subgrid_energy() { return nullptr; }
  /// A new velocity field: what the model carries starts again from it.
  virtual void restart() {}

  const char* stage() const override { return "subgrid"; }
  std::vector<HaloNeed> halo_needs() const override { return {{HaloField::faces, 1}, {HaloField::cells, 1}}; }
  void save_state(StageState& state) override;
  void restore_state(const StageState& state) override;
  std::vector<GridArray> saved_arrays() const override;

  /// Bytes of the one field every model keeps: nu_t.
  static std::size_t eddy_viscosity_bytes(const fluid::GridSpec& grid);

 protected:
  SubgridModel(const WindPartContext& context, cl::Buffer& mask);
  /// nu_t into eddy_viscosity_ for a step of the context's dt, capped at cap (fluid::eddy_viscosity_cap).
  virtual void update_eddy_viscosity(WindFields& fields, float cap, cl::Buffer* drag_density) = 0;

  WindPartContext context_;
  cl::Buffer& mask_;
  cl::Buffer eddy_viscosity_;
};

/// The model the settings ask for (solver.subgrid tke, else Smagorinsky's when its constant is > 0), or
/// null when there is none.
std::unique_ptr<SubgridModel> make_subgrid_model(const WindPartContext& context, cl::Buffer& mask);
/// Bytes the model the settings ask for allocates on `grid` (0 for none).
std::size_t subgrid_model_bytes(const fluid::WindSettings& settings, const fluid::GridSpec& grid);

}  // namespace fw::host
