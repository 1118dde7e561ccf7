// Vertical shape of the ambient wind on inflow faces, relative to the speed at the reference height.
//
//   InflowProfile p{InflowProfile::Type::log, /*reference_height=*/10.0};
//   p.roughness_length = 0.8; p.displacement_height = 12.0;
//   double s = p.shape(25.0);      // u(25 m) / u(10 m)
//
//   uniform: 1
//   power:   (z / z_ref)^alpha
//   log:     ln((z - d) / z0) / ln((z_ref - d) / z0), and 0 where z - d <= z0   (u*/kappa ln((z-d)/z0))
// z is the height above the domain's floor, metres.
#pragma once

#include <string>
#include <vector>

namespace fw::fluid {

struct InflowProfile {
  enum class Type { uniform, power, log };
  Type type = Type::uniform;
  double reference_height = 10.0;    // m
  double alpha = 0.14;               // power-law exponent (power)
  double roughness_length = 0.1;     // z0, m (log)
  double displacement_height = 0.0;  // d, m (log)

  /// Throws std::invalid_argument("InflowProfile: ...") for non-positive heights or lengths, a reference
  /// height below d + z0 (log), or a negative exponent.
  void validate() const;
  /// u(z) / u(reference_height), dimensionless, >= 0.
  double shape(double height) const;
  /// shape() at the nz cell-centre heights (k + 0.5) h: what the kernels read.
  std::vector<float> sample_cell_centres(int nz, double h) const;
};

}  // namespace fw::fluid
