// The wind section of a scenario (docs/scenario.md, "wind"): the ambient wind's speed and direction over
// time, its vertical profile, its synthetic turbulence and the mean forcing of a periodic domain. Defaults
// are the schema's (io/schema/WindKeys.hpp).
//
//   fw::io::WindSource wind;   // reference_height 10 m, a uniform profile, no turbulence
//   fw::io::wind_vector(wind, 60.0);   // m/s at the reference height, x east, y north
#pragma once

#include <array>
#include <cstdint>
#include <optional>

#include "fluid/InflowProfile.hpp"
#include "io/Expression.hpp"
#include "io/schema/WindKeys.hpp"

namespace fw::io {

/// The spectral model of wind.turbulence.
enum class TurbulenceModel { von_karman };

/// In the order of schema::kTurbulenceModelWords.
inline constexpr TurbulenceModel kTurbulenceModels[] = {TurbulenceModel::von_karman};

/// wind.turbulence: a periodic box of synthetic turbulence, swept through the inflow faces at the ambient
/// wind (Taylor) and added to the initial field; plus, optionally, Stam's unresolved modal forcing per tree.
struct TurbulenceSettings {
  TurbulenceModel model = schema::value_of(schema::kTurbulenceModelWords, kTurbulenceModels,
                                           schema::key(schema::kWindKeys, "wind.turbulence.model").word);
  /// sigma_u / wind.speed at reference_height, dimensionless, >= 0; sigma_v = sigma_w = sigma_u. Exactly one
  /// of intensity and sigma is set.
  std::optional<double> intensity;
  /// [sigma_u, sigma_v, sigma_w], m/s, each > 0, fixed over time (along-wind, across-wind, vertical).
  std::optional<std::array<double, 3>> sigma;
  double length_scale = 0.0;  ///< L_u, the longitudinal integral length scale, m, > 0
  /// The box's cells along x, y, z, each even and >= schema::kMinTurbulenceBoxCells, resolved at load (from
  /// box_size, else computed). The fluid::TurbulenceBox a run builds has fluid::kTurbulencePointsPerCell
  /// points per cell along each axis (h / 2 apart), at most TurbulenceBoxSpec::kMaxPoints in all.
  std::array<int, 3> box_cells{0, 0, 0};
  /// box_cells * domain.cell_size, m: the box's period along x, y, z (a given box_size, rounded).
  std::array<double, 3> box_size{0, 0, 0};
  bool box_size_given = false;  ///< whether the file gave box_size
  std::uint64_t seed = 0;       ///< the file's, else the scenario's top-level seed
  /// Stam's modal forcing per tree
  bool unresolved = schema::key(schema::kWindKeys, "wind.turbulence.unresolved").flag;
  /// The smallest resolved eddy in cells (> 0): wavenumbers above 2 pi / (cutoff_cells h) are unresolved.
  double cutoff_cells = schema::key(schema::kWindKeys, "wind.turbulence.cutoff_cells").number;

  /// [sigma_u, sigma_v, sigma_w], m/s, for the wind speed `speed` (m/s) at the reference height: intensity
  /// times speed on all three, or sigma as given.
  std::array<double, 3> standard_deviations(double speed) const;
};

/// wind.forcing: the mean body force of a domain whose four sides are all periodic (no inflow), a PI
/// controller that holds the horizontal mean wind at reference_height at the ambient wind.
struct ForcingSettings {
  /// tau, s, > 0
  double relaxation_time = schema::key(schema::kWindKeys, "wind.forcing.relaxation_time").number;
};

struct WindSource {
  Expression speed;      ///< m/s at reference_height, a function of t (s)
  Expression direction;  ///< degrees the wind blows FROM, clockwise from north, a function of t
  /// m above the domain floor
  double reference_height = schema::key(schema::kWindKeys, "wind.reference_height").number;
  /// Vertical shape; profile.reference_height == reference_height. Defaults: the schema's wind.profile.*
  /// (roughness_length has none).
  fluid::InflowProfile profile;
  /// Synthetic turbulence; nullopt (no wind.turbulence) for a laminar wind.
  std::optional<TurbulenceSettings> turbulence;
  /// Set exactly when west, east, south and north are all periodic (wind.forcing given or not); nullopt
  /// otherwise (the file may give wind.forcing only then).
  std::optional<ForcingSettings> forcing;
};

/// The ambient wind of `wind` at the reference height at time t (s), m/s: WindScenario::wind_vector without
/// the rest of the scenario, for whoever keeps only the wind.
std::array<double, 3> wind_vector(const WindSource& wind, double t);

}  // namespace fw::io
