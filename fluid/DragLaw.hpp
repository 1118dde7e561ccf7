// How the canopy's drag coefficient varies with the wind: leaves and twigs streamline in strong wind, so
// the drag grows more slowly than u^2 (Vogel 1984; for terrestrial and aquatic canopies a power law of the
// local speed with an exponent between 0 and -4/3, Pan, Chamecki & Isard 2014 found it matters for the stress
// that strong events carry).
//
//   fw::fluid::DragLaw law{-0.5, 5.0};              // C_D ~ |u|^-0.5, the species' C_D at 5 m/s
//   double cd = species_cd * law.factor(speed);     // on the air and on the trees alike
//
// C_D(|u|) = C_D0 (max(|u|, kSpeedFloor U_ref) / U_ref)^exponent: the species' drag coefficients C_D0 hold
// at the reference speed U_ref. Below kSpeedFloor U_ref the power law is not extended (at low speeds the
// drag turns viscous and the coefficient stops growing), so the factor stays finite at rest. Exponent 0 (the
// default) is the constant drag coefficient: factor 1 at every speed.
#pragma once

#include "kernels/shared_types.h"

namespace fw::fluid {

struct DragLaw {
  double exponent = 0.0;         ///< Vogel exponent beta, in [kLowestExponent, 0]
  double reference_speed = 1.0;  ///< U_ref, m/s, > 0: where the species' C_D hold

  /// The steepest streamlining measured for plants (Vogel 1984: -4/3 for strongly reconfiguring ones).
  static constexpr double kLowestExponent = -4.0 / 3.0;
  /// Below this fraction of U_ref the coefficient is held at its value there.
  static constexpr double kSpeedFloor = 0.1;

  bool constant() const { return exponent == 0.0; }
  /// C_D(speed) / C_D0.
  double factor(double speed) const;
  /// Throws std::invalid_argument("DragLaw: ...") for an exponent outside [kLowestExponent, 0] or a
  /// reference speed that is not finite and > 0.
  void validate() const;
  FwDragLaw to_device() const;
};

}  // namespace fw::fluid
