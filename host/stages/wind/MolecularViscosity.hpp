// The fluid's own viscosity (solver.viscosity, m^2/s): explicit diffusion of the velocity, sub-stepped so
// that each sub-step keeps nu dt / h^2 within the stable 1/6 with a margin. Holds no memory.
//
//   fw::host::MolecularViscosity viscosity(context);
//   int substeps = viscosity.substeps(dt);             // 0 when solver.viscosity is 0
//   viscosity.apply(fields, dt, enforce_boundaries);
#pragma once

#include <functional>

#include "host/stages/wind/WindPart.hpp"

namespace fw::host {

class MolecularViscosity : public WindPart {
 public:
  explicit MolecularViscosity(const WindPartContext& context) : context_(context) {}

  /// The sub-steps a step of dt (s) takes; 0 without viscosity.
  int substeps(double dt) const;
  /// fields.vel diffused over dt in substeps(dt) sub-steps, each ending with `boundaries` (the prescribed
  /// faces back) and its halo exchanged.
  void apply(WindFields& fields, double dt, const std::function<void(DeviceVelocity&)>& boundaries);

  const char* stage() const override { return "viscosity"; }
  std::size_t device_bytes() const override { return 0; }
  std::vector<HaloNeed> halo_needs() const override { return {{HaloField::faces, 1}}; }

 private:
  WindPartContext context_;
};

}  // namespace fw::host
