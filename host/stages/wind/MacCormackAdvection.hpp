// solver.advection: maccormack. Selle et al.'s MacCormack step on the semi-Lagrangian trace: forward over dt,
// back over -dt from the forward result, half the round trip's error corrected, clamped to the values around
// the foot so that the correction makes no new extrema. Second order where the field is smooth.
//
//   fw::host::MacCormackAdvection advection(context);
//   advection.advect(fields, dt, {});
#pragma once

#include "host/stages/wind/Advection.hpp"

namespace fw::host {

class MacCormackAdvection : public Advection {
 public:
  explicit MacCormackAdvection(const WindPartContext& context);

  static constexpr fluid::AdvectionScheme kScheme = fluid::AdvectionScheme::maccormack;
  static constexpr double kCourantLimit = std::numeric_limits<double>::infinity();
  static int halo_cells(double courant) { return traced_halo_cells(courant); }

  /// Two semi-Lagrangian traces and the correction's trace (its back-trace, the 8 corners, the forward and
  /// backward values).
  static constexpr double kGatheredLoadsPerFace = 2 * (9 + 24 + 8) + (9 + 24 + 8 + 2);
  /// Two pads and stores, and the correction reading q, the forward and the backward values.
  static constexpr double kBytesPerFace =
      2 * (kPadBytesPerFace + kStoreBytesPerFace) + (3 * 4 + kStoreBytesPerFace);
  /// Two padded copies (of the velocity and of the forward result) and the backward result.
  static std::size_t estimate_device_bytes(const fluid::GridSpec& grid);

  void advect(WindFields& fields, float dt, const StageEnd& stage_end) override;
  std::size_t device_bytes() const override { return estimate_device_bytes(context_.seam.local()); }

 private:
  DeviceVelocity padded_, padded_forward_, back_;
};

}  // namespace fw::host
