// The keys of an item of a scenario's forest.species: its name, skeleton and wood, its tree model and modes,
// its drag, its canopy, its leaves and its strength. Defaults and limits that belong to the trees (the wood
// of trees::kDefaultWood, the drag coefficients of trees::WindBasisSettings, the modal defaults of
// trees::ModalSettings, the models of trees::SpeciesDynamics, the leaves of trees::LeafSettings, the
// strength presets' words of trees/TreeStrength.hpp) are taken from there, so that each value is written
// once.
//
//   schema::key(schema::kSpeciesKeys, "forest.species[].modes.count").number;   // trees::ModalSettings{}'s
//
// Each map's keys stand in the order the loader's messages and the docs list them. Each key's prose is in
// SpeciesKeys.cpp (species_docs).
#pragma once

#include <span>
#include <string>
#include <string_view>
#include <vector>

#include "io/schema/Bounds.hpp"
#include "io/schema/Key.hpp"
#include "kernels/shared_types.h"
#include "trees/LeafSettings.hpp"
#include "trees/Material.hpp"
#include "trees/ModalBasis.hpp"
#include "trees/StandDensity.hpp"
#include "trees/TreeDynamics.hpp"
#include "trees/WindBasis.hpp"

namespace fw::io::schema {

/// In the order of trees::FlutterModel (trees::to_string gives the same words).
inline constexpr std::string_view kLeafModelWords[] = {"none", "pseudo_branch", "stochastic"};
inline constexpr trees::FlutterModel kLeafModels[] = {
    trees::FlutterModel::none, trees::FlutterModel::pseudo_branch, trees::FlutterModel::stochastic};

/// In the order of trees::TreeDynamics (trees::dynamics_name gives the same words).
inline constexpr std::string_view kDynamicsWords[] = {"modal", "rigid_bodies", "springs"};
inline constexpr trees::TreeDynamics kDynamicsModels[] = {
    trees::TreeDynamics::modal, trees::TreeDynamics::rigid_bodies, trees::TreeDynamics::springs};

/// The generator's presets (trees::preset_names), known at run time.
std::vector<std::string> preset_words();

/// The strength presets, soil groups and rooting depths of trees/TreeStrength.hpp (preset_name, soil_name,
/// rooting_name), in the order of their enums.
std::vector<std::string> strength_preset_words();
std::vector<std::string> soil_group_words();
std::vector<std::string> rooting_depth_words();

// Defaults owned elsewhere:
inline constexpr trees::WindBasisSettings kDragDefaults{};
inline constexpr trees::LeafSettings kLeafDefaults{};
inline constexpr trees::SpeciesDynamics kDynamicsDefaults{};
/// springs.max_angle_deg stays below a right angle, as trees::SpeciesDynamics::validate checks (a bend past
/// it has no meaning for one element turning about its base). TreeDynamics.cpp keeps its limit to itself, so
/// it is written here too; tests/io/ScenarioSchema_test.cpp holds the two equal.
inline constexpr double kSpringMaxAngleBelowDeg = 90.0;
/// strength.knot_factor is at most 1 (clear wood), as trees::TreeStrength::validate checks. TreeStrength.cpp
/// keeps its limit to itself, so it is written here too; tests/io/ScenarioSchema_test.cpp holds the two
/// equal.
inline constexpr double kMaxKnotFactor = 1.0;

inline constexpr Key kSpeciesKeys[] = {
    {.path = "forest.species[].name", .type = Type::text, .required = true, .noun = "a species name"},
    {.path = "forest.species[].skeleton", .type = Type::choice, .required = true},
    {.path = "forest.species[].skeleton.generate"},
    {.path = "forest.species[].skeleton.generate.preset",
     .type = Type::word,
     .required = true,
     .run_time_words = preset_words},
    {.path = "forest.species[].skeleton.generate.height",
     .type = Type::number,
     .unit = "m",
     .bound = Bound::non_negative,
     .at_most = bounds::kMaxTreeHeight,
     .number = 0.0},
    {.path = "forest.species[].skeleton.generate.seed", .type = Type::seed},
    {.path = "forest.species[].skeleton.file", .type = Type::file, .noun = "a file path"},
    {.path = "forest.species[].skeleton.qsm", .type = Type::file, .noun = "a file path"},
    {.path = "forest.species[].material"},
    {.path = "forest.species[].material.youngs_modulus",
     .type = Type::number,
     .unit = "Pa",
     .at_least = bounds::kMinModulus,
     .at_most = bounds::kMaxModulus,
     .number = trees::kDefaultWood.youngs_modulus},
    {.path = "forest.species[].material.shear_modulus",
     .type = Type::number,
     .unit = "Pa",
     .at_least = bounds::kMinModulus,
     .at_most = bounds::kMaxModulus,
     .number = trees::kDefaultWood.shear_modulus},
    {.path = "forest.species[].material.density",
     .type = Type::number,
     .unit = "kg/m^3",
     .at_least = bounds::kMinDensity,
     .at_most = bounds::kMaxDensity,
     .number = trees::kDefaultWood.density},
    {.path = "forest.species[].dynamics",
     .type = Type::word,
     .words = kDynamicsWords,
     .word = word_of(kDynamicsWords, kDynamicsModels, kDynamicsDefaults.model)},
    {.path = "forest.species[].modes"},
    {.path = "forest.species[].modes.count",
     .type = Type::integer,
     .lowest = 1,
     .highest = bounds::kMaxModes,
     .number = double(trees::ModalSettings{}.mode_count)},  // clang refuses the narrowing unspelt
    {.path = "forest.species[].modes.damping_ratio",
     .type = Type::number,
     .bound = Bound::non_negative,
     .at_most = bounds::kMaxDampingRatio,
     .number = trees::Damping{}.ratios.front()},
    {.path = "forest.species[].modes.wind_samples",
     .type = Type::integer,
     .lowest = 1,
     .highest = FW_MAX_TREE_SAMPLES,
     .number = 3},
    {.path = "forest.species[].rigid_bodies"},
    {.path = "forest.species[].rigid_bodies.damping_ratio",
     .type = Type::number,
     .bound = Bound::non_negative,
     .at_most = bounds::kMaxDampingRatio,
     .number = kDynamicsDefaults.rigid_bodies.damping_ratio},
    {.path = "forest.species[].springs"},
    {.path = "forest.species[].springs.max_angle_deg",
     .type = Type::number,
     .unit = "degrees",
     .bound = Bound::positive,
     .below = kSpringMaxAngleBelowDeg,
     .number = kDynamicsDefaults.springs.max_angle_deg},
    {.path = "forest.species[].springs.sway_amplitude",
     .type = Type::number,
     .bound = Bound::non_negative,
     .at_most = bounds::kMaxGain,
     .number = kDynamicsDefaults.springs.sway_amplitude},
    {.path = "forest.species[].springs.sway_frequency",
     .type = Type::number,
     .unit = "Hz",
     .bound = Bound::positive,
     .at_most = bounds::kMaxMotionFrequency,
     .number = kDynamicsDefaults.springs.sway_frequency_hz},
    {.path = "forest.species[].drag_coefficient",
     .type = Type::number,
     .bound = Bound::non_negative,
     .at_most = bounds::kMaxDragCoefficient,
     .number = kDragDefaults.branch_drag_coefficient},
    {.path = "forest.species[].canopy"},
    {.path = "forest.species[].canopy.leaf_area_index",
     .type = Type::number,
     .unit = "m^2/m^2",
     .bound = Bound::non_negative,
     .at_most = trees::StandDensity::kMaxLeafAreaIndex,
     .number = 0.0},
    {.path = "forest.species[].canopy.drag_coefficient",
     .type = Type::number,
     .bound = Bound::non_negative,
     .at_most = bounds::kMaxDragCoefficient,
     .number = kDragDefaults.leaf_drag_coefficient},
    {.path = "forest.species[].leaves"},
    {.path = "forest.species[].leaves.model",
     .type = Type::word,
     .words = kLeafModelWords,
     .word = word_of(kLeafModelWords, kLeafModels, kLeafDefaults.model)},
    {.path = "forest.species[].leaves.area",
     .type = Type::number,
     .unit = "m^2",
     .bound = Bound::positive,
     .at_most = bounds::kMaxLeafArea,
     .number = kLeafDefaults.area},
    {.path = "forest.species[].leaves.fraction",
     .type = Type::number,
     .bound = Bound::positive,
     .at_most = trees::LeafSettings::kMaxFraction,
     .number = kLeafDefaults.fraction},
    {.path = "forest.species[].leaves.mass_per_area",
     .type = Type::number,
     .unit = "kg/m^2",
     .bound = Bound::positive,
     .at_most = bounds::kMaxLeafMassPerArea,
     .number = kLeafDefaults.mass_per_area},
    {.path = "forest.species[].leaves.frequency",
     .type = Type::number,
     .unit = "Hz",
     .bound = Bound::positive,
     .at_most = bounds::kMaxMotionFrequency,
     .number = kLeafDefaults.frequency},
    {.path = "forest.species[].leaves.damping_ratio",
     .type = Type::number,
     .bound = Bound::non_negative,
     .below = trees::LeafSettings::kDampingRatioBelow,
     .number = kLeafDefaults.damping_ratio},
    {.path = "forest.species[].leaves.petiole_strength",
     .type = Type::number,
     .unit = "N",
     .bound = Bound::positive,
     .at_most = bounds::kMaxPetioleStrength,
     .number = kLeafDefaults.petiole_strength},
    {.path = "forest.species[].leaves.strength_spread",
     .type = Type::number,
     .bound = Bound::non_negative,
     .at_most = bounds::kMaxLogSpread,
     .number = kLeafDefaults.strength_spread},
    {.path = "forest.species[].leaves.flight_drag_coefficient",
     .type = Type::number,
     .bound = Bound::positive,
     .at_most = bounds::kMaxDragCoefficient,
     .number = kLeafDefaults.flight_drag_coefficient},
    {.path = "forest.species[].leaves.amplitudes",
     .type = Type::point3,
     .unit = "degrees",
     .bound = Bound::non_negative,
     .at_most = trees::LeafSettings::kMaxAmplitudeDeg,
     .components = kLeafDefaults.amplitudes_deg,
     .noun = "[W_H, W_V, W_R]"},
    {.path = "forest.species[].leaves.roll_coupling",
     .type = Type::number,
     .at_least = -bounds::kMaxGain,
     .at_most = bounds::kMaxGain,
     .number = kLeafDefaults.roll_coupling},
    {.path = "forest.species[].leaves.reference_speed",
     .type = Type::number,
     .unit = "m/s",
     .bound = Bound::positive,
     .at_most = bounds::kMaxWindSpeed,
     .number = kLeafDefaults.reference_speed},
    {.path = "forest.species[].leaves.seed", .type = Type::seed},
    // The defaults of soil and rooting are trees::strength_preset's (tests/io/ScenarioSchema_test.cpp); the
    // numbers have none: a preset's, else required.
    {.path = "forest.species[].strength"},
    {.path = "forest.species[].strength.preset", .type = Type::word, .run_time_words = strength_preset_words},
    {.path = "forest.species[].strength.soil",
     .type = Type::word,
     .run_time_words = soil_group_words,
     .word = "A"},
    {.path = "forest.species[].strength.rooting",
     .type = Type::word,
     .run_time_words = rooting_depth_words,
     .word = "mean"},
    {.path = "forest.species[].strength.modulus_of_rupture",
     .type = Type::number,
     .unit = "Pa",
     .at_least = bounds::kMinModulusOfRupture,
     .at_most = bounds::kMaxModulusOfRupture},
    {.path = "forest.species[].strength.knot_factor",
     .type = Type::number,
     .bound = Bound::positive,
     .at_most = kMaxKnotFactor},
    {.path = "forest.species[].strength.green_density",
     .type = Type::number,
     .unit = "kg/m^3",
     .at_least = bounds::kMinGreenDensity,
     .at_most = bounds::kMaxGreenDensity},
    {.path = "forest.species[].strength.anchorage",
     .type = Type::number,
     .unit = "N m/kg",
     .at_least = bounds::kMinAnchorage,
     .at_most = bounds::kMaxAnchorage},
};

/// The prose of each key of kSpeciesKeys (SpeciesKeys.cpp), which schema::docs (io/ScenarioSchema.hpp) finds
/// by its path.
std::span<const KeyDocs> species_docs();

}  // namespace fw::io::schema
