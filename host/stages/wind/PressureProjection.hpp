// The projection that makes the wind divergence-free: the divergence of the velocity, the pressure equation
// solved for it (host/stages/PressureSolver), and the pressure gradient subtracted from every face.
//
//   fw::host::PressureProjection projection(context);
//   fw::host::PressureSolveStatus status = projection.project(fields.vel);
//   projection.mask();                        // the cells' fluid and face bits, which the other parts read
#pragma once

#include <memory>
#include <vector>

#include "host/stages/PressureSolver.hpp"
#include "host/stages/wind/WindPart.hpp"

namespace fw::host {

class PressureProjection : public WindPart {
 public:
  explicit PressureProjection(const WindPartContext& context);

  /// Bytes the solver allocates for the whole grid `spec` on the rank's share of it.
  static std::size_t estimate_device_bytes(const fluid::GridSpec& spec, const BlockShare& share);

  /// vel <- vel less the gradient of the pressure that makes it divergence-free; its halo exchanged. Times
  /// its three stages ("divergence", "pressure", "gradient").
  PressureSolveStatus project(DeviceVelocity& vel);
  /// Kinematic pressure p / rho = phi / dt at cell centres for the last step's dt (s), m^2/s^2 (0 in
  /// solids).
  std::vector<float> download_pressure(double dt);
  /// The pressure mask of the rank's block (a byte a cell: FW_MASK_FLUID and the open faces).
  cl::Buffer& mask() { return solver_.mask(); }
  PressureSolver& solver() { return solver_; }
  const PressureSolver& solver() const { return solver_; }

  const char* stage() const override { return "pressure"; }
  std::size_t device_bytes() const override;
  std::vector<HaloNeed> halo_needs() const override { return {{HaloField::faces, 1}}; }
  /// The last solution, which warm-starts the next solve.
  void save_state(StageState& state) override;
  void restore_state(const StageState& state) override;
  std::vector<GridArray> saved_arrays() const override;

 private:
  WindPartContext context_;
  PressureSolver solver_;
};

}  // namespace fw::host
