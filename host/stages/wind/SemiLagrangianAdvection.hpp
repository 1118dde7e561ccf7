// solver.advection: semi_lagrangian. Stam's stable back-trace: each face's value is the velocity at the
// foot of its trajectory over dt (RK2, trilinear), read from a padded copy whose ghosts follow the boundary
// rules. Unconditionally stable, first-order diffusive.
//
//   fw::host::SemiLagrangianAdvection advection(context);
//   advection.advect(fields, dt, {});
#pragma once

#include "host/stages/wind/Advection.hpp"

namespace fw::host {

class SemiLagrangianAdvection : public Advection {
 public:
  explicit SemiLagrangianAdvection(const WindPartContext& context);

  static constexpr fluid::AdvectionScheme kScheme = fluid::AdvectionScheme::semi_lagrangian;
  static constexpr double kCourantLimit = std::numeric_limits<double>::infinity();
  static int halo_cells(double courant) { return traced_halo_cells(courant); }

  /// Scalar loads gathered per face (kernels/fluid_advect.cl): the velocity at the face (the component, and
  /// four faces of each other one: 9), the velocity at the midpoint (3 x 8 corners) and the component at
  /// the foot (8).
  static constexpr double kGatheredLoadsPerFace = 9 + 24 + 8;
  /// A pad and the result written.
  static constexpr double kBytesPerFace = kPadBytesPerFace + kStoreBytesPerFace;
  /// The padded copy of the velocity.
  static std::size_t estimate_device_bytes(const fluid::GridSpec& grid);

  void advect(WindFields& fields, float dt, const StageEnd& stage_end) override;
  std::size_t device_bytes() const override { return estimate_device_bytes(context_.seam.local()); }

 private:
  DeviceVelocity padded_;
};

}  // namespace fw::host
