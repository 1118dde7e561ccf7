// How much a tree can take before it fails (docs/damage.md): the wood's strength against stem breakage and
// the root-soil plate's anchorage against overturning, as ForestGALES models them (Gardiner et al. 2000,
// 2008; Hale et al. 2015), with the species presets of its published table.
//
//   fw::trees::TreeStrength sitka = fw::trees::strength_preset(fw::trees::StrengthPreset::sitka_spruce);
//   double M_b = fw::trees::breaking_moment(sitka, 0.26);          // N m, the stem 0.26 m across
//   double M_o = fw::trees::overturning_moment(sitka, 0.45);       // N m, a stem of 0.45 m^3
//   double u_h = fw::trees::hale_critical_wind(std::min(M_b, M_o), 0.25, 20.0);   // m/s, canopy top
//
// The math:
//   - breakage at a stem section of diameter d: M_b = f_knot MOR pi d^3 / 32, the moment whose outer-fibre
//     stress sigma = 32 M / (pi d^3) reaches the knot-weakened modulus of rupture;
//   - overturning: M_o = C_reg W_stem, W_stem = green density x stem volume (kg), C_reg (N m/kg) the
//     regression through zero of tree-pulling tests (Nicoll et al. 2006) for the species, soil and rooting;
//   - Hale et al. (2012): the largest root moment in an hour is T_C u_h^2 with T_C = 111.6 dbh^2 h (SI), u_h
//     the hour's mean wind at the canopy top, so the critical mean wind of a critical moment M is
//     sqrt(M / T_C).
#pragma once

#include <optional>
#include <string_view>

namespace fw::trees {

/// A species' strength, SI units.
struct TreeStrength {
  double modulus_of_rupture = 0.0;  ///< MOR, Pa
  double knot_factor = 1.0;         ///< f_knot in (0, 1]: the loss of strength to knots
  double green_density = 0.0;       ///< kg/m^3 of green stem wood (what anchors: W_stem)
  double anchorage = 0.0;           ///< C_reg, N m/kg of green stem weight

  /// Throws std::invalid_argument("TreeStrength: ...") naming the first value that is not finite and
  /// positive, or a knot factor above 1.
  void validate() const;
};

/// The presets of ForestGALES's published species table (docs/damage.md, "Presets").
enum class StrengthPreset { sitka_spruce, norway_spruce, scots_pine, birch };
/// The soil groups of the table: A free-draining mineral, B gleyed mineral, C peaty mineral, D deep peat.
enum class SoilGroup { A, B, C, D };
/// Rooting depth; the table gives shallow and deep only for soil A.
enum class RootingDepth { shallow, mean, deep };

/// The scenario words: "sitka_spruce", ...; "A".."D"; "shallow", "mean", "deep".
const char* preset_name(StrengthPreset preset);
std::optional<StrengthPreset> parse_strength_preset(std::string_view word);
const char* soil_name(SoilGroup soil);
std::optional<SoilGroup> parse_soil_group(std::string_view word);
const char* rooting_name(RootingDepth rooting);
std::optional<RootingDepth> parse_rooting_depth(std::string_view word);

/// Whether the table has an anchorage for this soil and rooting (shallow and deep: soil A only).
bool has_anchorage(SoilGroup soil, RootingDepth rooting);

/// The preset's strength on the given soil and rooting. Throws std::invalid_argument("TreeStrength: ...")
/// for a soil and rooting the table has no value of (has_anchorage).
TreeStrength strength_preset(StrengthPreset preset, SoilGroup soil = SoilGroup::A,
                             RootingDepth rooting = RootingDepth::mean);

/// M_b = f_knot MOR pi d^3 / 32, N m, for a section of diameter d (m).
double breaking_moment(const TreeStrength& strength, double diameter);
/// M_o = C_reg x green density x stem volume (m^3), N m.
double overturning_moment(const TreeStrength& strength, double stem_volume);
/// The outer-fibre bending stress 32 M / (pi d^3), Pa, of a moment M (N m) on a section of diameter d (m).
double outer_fibre_stress(double moment, double diameter);

/// Hale et al. (2012): T_C = 111.6 dbh^2 h, N m per (m/s)^2, for dbh and h in metres.
inline constexpr double kHaleCoefficient = 111.6;
double hale_turning_coefficient(double dbh, double height);
/// The mean canopy-top wind whose peak root moment by Hale's relation is `moment` (N m): sqrt(M / T_C).
double hale_critical_wind(double moment, double dbh, double height);

}  // namespace fw::trees
