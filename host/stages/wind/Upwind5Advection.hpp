// solver.advection: upwind5. Flux-form fifth-order upwind advection (Wicker & Skamarock 2002) in three
// Runge-Kutta stages, each from the padded copy of the stage before; the order drops near walls and solids
// (fluid/UpwindStencil.hpp's flux orders). Stable up to a Courant number (|u| + |v| + |w|) dt / h of
// fluid::kUpwind5CourantLimit.
//
//   fw::host::Upwind5Advection advection(context);
//   advection.advect(fields, dt, stage_end);   // stage_end: the prescribed faces back after stages 1 and 2
#pragma once

#include "host/stages/wind/Advection.hpp"

namespace fw::host {

class Upwind5Advection : public Advection {
 public:
  explicit Upwind5Advection(const WindPartContext& context);

  static constexpr fluid::AdvectionScheme kScheme = fluid::AdvectionScheme::upwind5;
  static constexpr double kCourantLimit = fluid::kUpwind5CourantLimit;

  /// Three stages, each padding the three components (a read and a write of each face), then reading a
  /// face of each padded component, the base value and the packed order (2 bytes), and storing the result.
  /// Its loads are whole rows, not gathers.
  static constexpr double kGatheredLoadsPerFace = 0.0;
  static constexpr double kBytesPerFace = 3 * (3 * kPadBytesPerFace + (3 * 4 + 4 + 2 + kStoreBytesPerFace));
  /// The padded copy, a second stage velocity and the flux orders.
  static std::size_t estimate_device_bytes(const fluid::GridSpec& grid);
  /// Its stencil reaches FW_PAD faces whatever the Courant number (its limit keeps that below 1).
  static int halo_cells(double courant);

  void advect(WindFields& fields, float dt, const StageEnd& stage_end) override;
  std::size_t device_bytes() const override { return estimate_device_bytes(context_.seam.local()); }

 private:
  DeviceVelocity padded_, back_;
  DeviceUpwindOrders orders_;
};

}  // namespace fw::host
