// The wind's boundaries: the inflow's profile and its synthetic turbulence (Taylor's frozen box swept
// through the inflow faces at the ambient wind), and each face's rule (inflow, outflow, slip, periodic,
// solids) enforced on the velocity. The initial field is the inflow's everywhere.
//
//   fw::host::WindBoundaries boundaries(context, mask);
//   boundaries.advance(dt);              // the box travels ambient * dt; the step's inflow to the kernels
//   boundaries.enforce(fields.vel);
#pragma once

#include <array>
#include <vector>

#include "fluid/InflowState.hpp"
#include "fluid/MacVelocity.hpp"
#include "host/stages/wind/WindPart.hpp"

namespace fw::host {

class WindBoundaries : public WindPart {
 public:
  WindBoundaries(const WindPartContext& context, cl::Buffer& mask);
  /// The inflow buffer on `grid` (inflow_buffer_values): the profile, and with a turbulence box of `box`
  /// its values and the prescribed shell. box: null for a laminar inflow.
  static std::size_t estimate_device_bytes(const fluid::GridSpec& grid, const fluid::TurbulenceBoxSpec* box);
  /// The part of that a turbulence box adds: its values and the shell.
  static std::size_t turbulence_bytes(const fluid::GridSpec& grid, const fluid::TurbulenceBoxSpec& box);

  /// The inflow now: the setup's ambient wind and profile, the box, its sigma and how far it has travelled.
  fluid::InflowState inflow_state() const;
  /// sigma_u of the inflow turbulence from now on, m/s (finite, >= 0, else std::invalid_argument).
  void set_turbulence_sigma(double sigma_m_s);
  /// The box travels the ambient wind times dt (s), within one box length.
  void advance(double dt);
  /// The step's inflow (the ambient wind, the box's sigma and offset) to the kernels.
  void upload_step_inflow();
  /// Every face's boundary rule on vel, and the periodic seam's copy across ranks.
  void enforce(DeviceVelocity& vel);
  /// The inflow's profile, and its turbulence where there is some, on every face of the block: a
  /// turbulent run starts developed.
  fluid::MacVelocity initial_field() const;

  const char* stage() const override { return "boundaries"; }
  std::size_t device_bytes() const override;
  std::vector<HaloNeed> halo_needs() const override { return {{HaloField::faces, 1}}; }
  /// The box's sigma and offset.
  void save_state(StageState& state) override;
  void restore_state(const StageState& state) override;

 private:
  WindPartContext context_;
  cl::Buffer& mask_;
  std::vector<float> profile_shape_;  // the profile at the nz cell-centre heights, sampled once
  cl::Buffer inflow_;                 // inflow_buffer_values
  double turbulence_sigma_ = 0.0;     // m/s
  std::array<double, 3> turbulence_offset_{0, 0, 0};  // m, within one box length
};

}  // namespace fw::host
