// Smagorinsky's subgrid model: nu_t = min((C_s h)^2 |S|, cap) from the resolved strain
// (fluid/SubgridStress.hpp).
//
//   fw::host::SmagorinskySubgrid subgrid(context, mask);    // settings.smagorinsky_constant > 0
//   subgrid.apply(fields, dt, nullptr);
#pragma once

#include "host/stages/wind/SubgridModel.hpp"

namespace fw::host {

class SmagorinskySubgrid : public SubgridModel {
 public:
  SmagorinskySubgrid(const WindPartContext& context, cl::Buffer& mask);
  /// nu_t.
  static std::size_t estimate_device_bytes(const fluid::GridSpec& grid) { return eddy_viscosity_bytes(grid); }
  std::size_t device_bytes() const override { return estimate_device_bytes(context_.seam.local()); }

 private:
  void update_eddy_viscosity(WindFields& fields, float cap, cl::Buffer* drag_density) override;
};

}  // namespace fw::host
