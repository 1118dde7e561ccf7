// The elastic and inertial properties of a tree species' wood, as used by the FEM beam model.
//
//   fw::trees::Material wood{1.2e10, 4.6e9, 650.0};    // E, G in Pa; rho in kg/m^3
//   wood.validate();                                   // throws std::invalid_argument("Material: ...")
//   fw::trees::kDefaultWood;                           // the wood of a species that names none
//
// All three values are SI. The model is isotropic: one Young's modulus for axial stretch and bending, one
// shear modulus for torsion.
#pragma once

#include <cmath>
#include <cstdio>
#include <stdexcept>
#include <string>

namespace fw::trees {

struct Material {
  double youngs_modulus = 0.0;  ///< E, Pa
  double shear_modulus = 0.0;   ///< G, Pa
  double density = 0.0;         ///< rho, kg/m^3

  /// Throws std::invalid_argument("Material: ...") naming the first value that is not finite and positive.
  void validate() const {
    check("youngs_modulus (E, Pa)", youngs_modulus);
    check("shear_modulus (G, Pa)", shear_modulus);
    check("density (rho, kg/m^3)", density);
  }

 private:
  static void check(const char* name, double value) {
    if (!std::isfinite(value) || !(value > 0.0)) {
      char shown[32];
      std::snprintf(shown, sizeof shown, "%g", value);
      throw std::invalid_argument(std::string("Material: ") + name + " must be finite and positive, got " +
                                  shown);
    }
  }
};

/// The default wood of every species (trees::SpeciesSettings, the scenario's `material`): Diener's wood,
/// G = E / 2.6.
inline constexpr Material kDefaultWood{1.0e10, 3.85e9, 900.0};

}  // namespace fw::trees
