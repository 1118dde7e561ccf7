// trees/TreeStrength: the critical moments and Hale's critical wind of ForestGALES's published worked
// example, and the presets as the table gives them.
#include "trees/TreeStrength.hpp"

#include <catch2/catch.hpp>

#include <cmath>
#include <stdexcept>

using fw::trees::RootingDepth;
using fw::trees::SoilGroup;
using fw::trees::StrengthPreset;
using fw::trees::TreeStrength;

TEST_CASE("TreeStrength: the worked Sitka spruce of h 20 m and dbh 0.25 m has the published critical moments",
          "[trees]") {
  // ../shared/papers/wind-damage-forestgales.md, "Worked example": M_b ~ 57 kN m with d = 1.03 dbh at the
  // base; T_C ~ 139.5; the critical mean wind 18.5-19 m/s with ForestGALES's deflection loading factor 1.14.
  const TreeStrength sitka = fw::trees::strength_preset(StrengthPreset::sitka_spruce);
  CHECK(sitka.modulus_of_rupture == 34e6);
  CHECK(sitka.knot_factor == 1.0);
  CHECK(sitka.green_density == 850.0);
  CHECK(sitka.anchorage == 156.2);
  const double m_b = fw::trees::breaking_moment(sitka, 1.03 * 0.25);
  CHECK(m_b == Approx(57.0e3).epsilon(0.01));  // the example rounds to 1 kN m of 57
  CHECK(fw::trees::hale_turning_coefficient(0.25, 20.0) == Approx(139.5).epsilon(1e-12));
  const double lean = 1.14;
  const double u_crit = fw::trees::hale_critical_wind(m_b / lean, 0.25, 20.0);
  CHECK(u_crit > 18.5);
  CHECK(u_crit < 19.0);
  // The stress of the critical moment is the knot-weakened MOR, to rounding.
  CHECK(fw::trees::outer_fibre_stress(m_b, 1.03 * 0.25) == Approx(sitka.knot_factor * 34e6).epsilon(1e-12));
  // M_o = C_reg W_stem: 61 kN m in the example is a stem of 61e3 / (156.2 x 850) = 0.459 m^3.
  CHECK(fw::trees::overturning_moment(sitka, 0.459) == Approx(61.0e3).epsilon(0.01));
}

TEST_CASE(
    "TreeStrength: the presets give the table's anchorage by soil and rooting, and refuse what it lacks",
    "[trees]") {
  using fw::trees::strength_preset;
  CHECK(strength_preset(StrengthPreset::norway_spruce, SoilGroup::A, RootingDepth::shallow).anchorage ==
        126.0);
  CHECK(strength_preset(StrengthPreset::norway_spruce, SoilGroup::A, RootingDepth::deep).anchorage == 146.6);
  CHECK(strength_preset(StrengthPreset::scots_pine, SoilGroup::B).anchorage == 126.7);
  CHECK(strength_preset(StrengthPreset::sitka_spruce, SoilGroup::D).anchorage == 172.1);
  CHECK(strength_preset(StrengthPreset::scots_pine).knot_factor == 0.85);
  CHECK(strength_preset(StrengthPreset::birch).modulus_of_rupture == 53.6e6);
  CHECK_THROWS_AS(strength_preset(StrengthPreset::sitka_spruce, SoilGroup::C, RootingDepth::deep),
                  std::invalid_argument);
  for (const char* word : {"sitka_spruce", "norway_spruce", "scots_pine", "birch"})
    CHECK(std::string(fw::trees::preset_name(*fw::trees::parse_strength_preset(word))) == word);
  CHECK_FALSE(fw::trees::parse_strength_preset("oak"));
  CHECK(fw::trees::parse_soil_group("C") == SoilGroup::C);
  CHECK(fw::trees::parse_rooting_depth("deep") == RootingDepth::deep);
}

TEST_CASE("TreeStrength: validate names a value that is not finite and positive, and a knot factor above 1",
          "[trees]") {
  TreeStrength strength = fw::trees::strength_preset(StrengthPreset::scots_pine);
  CHECK_NOTHROW(strength.validate());
  strength.knot_factor = 1.2;
  CHECK_THROWS_WITH(strength.validate(), Catch::Contains("knot_factor"));
  strength.knot_factor = 1.0;
  strength.anchorage = std::nan("");
  CHECK_THROWS_WITH(strength.validate(), Catch::Contains("anchorage"));
}
