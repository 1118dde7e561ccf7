// A species' leaves: the scenario keys `forest.species[].leaves` (docs/leaves.md has the model and the
// reasons for each default). Units: SI; angles in degrees where the scenario gives them, radians inside.
//
//   fw::trees::LeafSettings leaves;          // broadleaf defaults, pseudo-branch flutter
//   leaves.area = 0.004;                     // m^2 per leaf, one-sided
//   leaves.validate();                       // throws std::invalid_argument("LeafSettings: ...")
#pragma once

#include <array>
#include <cstdint>
#include <string>

#include "trees/Gravity.hpp"

namespace fw::trees {

enum class FlutterModel {
  none,           ///< no leaves (a winter tree)
  pseudo_branch,  ///< Oliapuram's one damped rotational degree of freedom, driven by the normal wind
  stochastic,     ///< Ota/Yildiz's three wind-scaled sine angles
};

/// "none", "pseudo_branch", "stochastic".
std::string to_string(FlutterModel model);

struct LeafSettings {
  FlutterModel model = FlutterModel::pseudo_branch;
  double area = 0.004;                               ///< a, one-sided area of one leaf, m^2 (> 0)
  double fraction = 1.0;                             ///< share of the foliage's leaves simulated, (0, 1]
  double mass_per_area = 0.1;                        ///< sigma, kg/m^2 (> 0)
  double frequency = 3.0;                            ///< f_leaf, flutter frequency, Hz (> 0)
  double damping_ratio = 0.05;                       ///< zeta of the pseudo-branch, [0, 1)
  double petiole_strength = 1.0;                     ///< median of the log-normal petiole strength, N (> 0)
  double strength_spread = 0.5;                      ///< its log-standard deviation (>= 0)
  double flight_drag_coefficient = 1.0;              ///< C_D of a tumbling leaf in flight (> 0)
  std::array<double, 3> amplitudes_deg{20, 30, 15};  ///< W_H, W_V, W_R of the stochastic model, degrees
  double roll_coupling = 0.5;                        ///< a: theta_R gains a theta_H
  double reference_speed = 10.0;                     ///< U_ref, m/s: full amplitudes at and above it (> 0)
  std::uint64_t seed = 1;                            ///< the species' leaves (positions, angles, strengths)

  // The upper limits of the ranges above, written once: validate() checks them, and the scenario schema
  // (io/schema/SpeciesKeys.hpp) takes them for its keys, its messages and docs/scenario.md.
  static constexpr double kMaxFraction = 1.0;  ///< fraction <= this: every leaf of the foliage
  /// damping_ratio < this: at critical damping the pseudo-branch no longer oscillates.
  static constexpr double kDampingRatioBelow = 1.0;
  /// Each amplitude <= this, degrees: the stochastic angles tilt the blade, and beyond a right angle they
  /// would fold it over.
  static constexpr double kMaxAmplitudeDeg = 90.0;

  /// Throws std::invalid_argument("LeafSettings: <key> ...") for a value outside the ranges above.
  void validate() const;
  bool has_leaves() const { return model != FlutterModel::none; }
};

// Constants of the model (docs/leaves.md).
inline constexpr double kAirDensity = 1.2;  ///< rho, kg/m^3 (as the wind grid's drag convention)
inline constexpr double kLeafNormalForceCoefficient = 1.2;  ///< C_n of a flat plate broadside
inline constexpr double kLeafTumbleStrouhal = 0.1;  ///< St of the tumbling rate, Omega = 2 pi St |u - v| / l
inline constexpr double kPetioleLengthPerSide = 0.5;  ///< l_p / l

}  // namespace fw::trees
