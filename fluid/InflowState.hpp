// What the prescribed velocity on inflow faces needs at one moment: the ambient wind, the profile's shape
// and, when on, the synthetic turbulence swept through the inflow plane (docs/design.md, "Turbulence"). The
// CPU reference reads it through value(); the device kernels get the same numbers through FwStep and their
// `inflow` buffer (kernels/common.cl inflow_face_value).
//
//   fw::fluid::InflowState inflow;
//   inflow.ambient = {10, 0, 0};                       // m/s at the reference height
//   inflow.profile = profile.sample_cell_centres(spec.nz, spec.h);
//   inflow.turbulence = box; inflow.turbulence_sigma = 1.5; inflow.turbulence_offset = {30, 0, 0};
//   double u = inflow.value(spec, 0, 0, j, k);        // the inflow face (0, j, k) of u, m/s
//
// value(c, i, j, k) = ambient_c * shape(k) + sigma * taper(k) * box_c(x_face - offset), with the box's
// unit-sigma fluctuations sampled trilinearly and periodically (fluid/TurbulenceBox) and
// taper = min(1, shape / FW_TURBULENCE_FULL_SHAPE) (kernels/shared_types.h): full sigma wherever the mean
// wind is at least half the reference speed (sigma_u is nearly constant with height in a surface layer), none
// where the mean profile is zero (below z0 + d of a log law).
#pragma once

#include <array>
#include <memory>
#include <vector>

#include "fluid/GridSpec.hpp"
#include "fluid/TurbulenceBox.hpp"

namespace fw::fluid {

struct InflowState {
  std::array<float, 3> ambient{0, 0, 0};            // m/s at the reference height
  std::vector<float> profile;                       // nz shape factors at cell-centre heights (InflowProfile)
  std::shared_ptr<const TurbulenceBox> turbulence;  // unit-sigma box; null: no turbulence
  float turbulence_sigma = 0.0f;                    // sigma_u now, m/s
  std::array<float, 3> turbulence_offset{0, 0, 0};  // how far the frozen box has travelled, m

  bool turbulent() const { return turbulence && turbulence_sigma != 0.0f; }
  /// The prescribed value of component c at face index (i, j, k) (a ghost index may lie outside the grid),
  /// with the profile taken at height index `level` (clamped to 0 .. nz-1), m/s.
  double value(const GridSpec& spec, int c, int i, int j, int k, int level) const;
};

}  // namespace fw::fluid
