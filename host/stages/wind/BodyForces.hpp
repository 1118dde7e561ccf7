// The forces on the wind that no other part models: a uniform body force (solver.body_force), the mean
// forcing that holds a periodic domain's wind at the ambient (MeanForcing), the gusts' travelling balls, and
// vorticity confinement. Applied right after advection.
//
//   fw::host::BodyForces forces(context);
//   forces.update_mean_forcing(fields, dt);     // once a step, before apply: the PI controller's new push
//   forces.apply(fields);
#pragma once

#include <array>
#include <vector>

#include "host/stages/wind/WindPart.hpp"

namespace fw::host {

class BodyForces : public WindPart {
 public:
  explicit BodyForces(const WindPartContext& context);
  /// The gusts' list (one FwGust each, at least one buffer's worth) and, with vorticity confinement, the
  /// vorticity and its magnitude (four floats a cell).
  static std::size_t estimate_device_bytes(const fluid::GridSpec& grid, const WindGridSetup& setup);

  /// With a mean forcing: its acceleration for the next step from the reference layer's mean wind
  /// (collective over ranks). Nothing without one.
  void update_mean_forcing(WindFields& fields, double dt);
  /// The body force and the mean forcing's acceleration, the gusts and the confinement onto fields.vel, its
  /// halo exchanged; nothing is enqueued when there is none of them.
  void apply(WindFields& fields);
  /// The mean forcing's horizontal acceleration of the last step, m/s^2 (0 when off).
  std::array<double, 2> forcing_acceleration() const { return forcing_acceleration_; }
  /// Mean u and v of the layer at the profile's reference height (linear between the two nearest cell
  /// layers, solid faces counted as 0), m/s: exact sums over ranks. Reads two layers of u and v back.
  std::array<double, 2> reference_layer_mean(WindFields& fields);

  const char* stage() const override { return "forces"; }
  std::size_t device_bytes() const override {
    return estimate_device_bytes(context_.seam.local(), context_.setup);
  }
  std::vector<HaloNeed> halo_needs() const override;
  /// The mean forcing's integral and acceleration.
  void save_state(StageState& state) override;
  void restore_state(const StageState& state) override;

 private:
  bool confines() const { return context_.setup.settings.vorticity_confinement > 0.0; }

  WindPartContext context_;
  cl::Buffer gusts_, vorticity_;
  std::array<double, 2> forcing_integral_{0, 0};      // integral of the error, m
  std::array<double, 2> forcing_acceleration_{0, 0};  // m/s^2
};

}  // namespace fw::host
