// An item of a scenario's forest.species (docs/scenario.md, "forest.species[]"): where its skeleton comes
// from, its wood, tree model, modes, drag, canopy, leaves and strength. Defaults are the schema's
// (io/schema/SpeciesKeys.hpp), which takes them from the trees' own types where they are defined.
//
//   fw::io::Species species;    // the default wood, modal dynamics, no leaves
//   species.modes.count;        // trees::ModalSettings' default
#pragma once

#include <cstdint>
#include <filesystem>
#include <optional>
#include <string>

#include "io/schema/SpeciesKeys.hpp"
#include "trees/LeafSettings.hpp"
#include "trees/Material.hpp"
#include "trees/TreeDynamics.hpp"
#include "trees/TreeGenerator.hpp"
#include "trees/TreeStrength.hpp"

namespace fw::io {

/// Where a species' skeleton comes from: exactly one of the three.
struct SkeletonSource {
  enum class Kind { generate, file, qsm };
  Kind kind = Kind::generate;
  trees::GeneratorSettings generate;  ///< Kind::generate: preset, height (m, 0 = preset default), seed
  std::filesystem::path path;         ///< Kind::file (.tree) or Kind::qsm (TreeQSM text); resolved, exists
  /// The file's dotted key that sets the skeleton (skeleton.file, skeleton.qsm, skeleton.generate.height, or
  /// skeleton.generate when it gives no height) and its line: what the planner's checks of the skeleton
  /// name.
  std::string key;
  int line = 0;
};

struct ModeSettings {
  /// lowest modes kept, >= 1
  int count = int(schema::key(schema::kSpeciesKeys, "forest.species[].modes.count").number);
  /// zeta per mode, >= 0
  double damping_ratio = schema::key(schema::kSpeciesKeys, "forest.species[].modes.damping_ratio").number;
  /// Height bands with their own projection, 1..FW_MAX_TREE_SAMPLES.
  int wind_samples = int(schema::key(schema::kSpeciesKeys, "forest.species[].modes.wind_samples").number);
  int count_line = 0;  ///< line of `count` in the file (of the species entry when not given)
};

struct CanopySettings {
  /// One-sided m^2 leaf per m^2 ground, >= 0 (0: no leaves).
  double leaf_area_index =
      schema::key(schema::kSpeciesKeys, "forest.species[].canopy.leaf_area_index").number;
  /// C_D of the leaves per one-sided leaf area (the branches' convention), >= 0.
  double drag_coefficient =
      schema::key(schema::kSpeciesKeys, "forest.species[].canopy.drag_coefficient").number;
  int leaf_area_index_line = 0;  ///< the line of leaf_area_index (of canopy, or the species, when not given)
};

/// A species' leaves seed when the file gives none: the global seed + kLeafSeedOffset + the species' index
/// (apart from the stands' seed + k and the skeletons' seed + 1 + k).
inline constexpr std::uint64_t kLeafSeedOffset = std::uint64_t(1) << 32;

struct Species {
  std::string name;  ///< unique among the species
  int line = 0;      ///< the species entry's line in the file
  SkeletonSource skeleton;
  trees::Material material{
      schema::key(schema::kSpeciesKeys, "forest.species[].material.youngs_modulus").number,
      schema::key(schema::kSpeciesKeys, "forest.species[].material.shear_modulus").number,
      /// E, G (Pa), rho (kg/m^3)
      schema::key(schema::kSpeciesKeys, "forest.species[].material.density").number};
  /// forest.species[].dynamics and the keys of its model (rigid_bodies, springs) over trees::SpeciesDynamics'
  /// defaults (the schema's); validated. The keys of another model are errors, `modes` included: every
  /// species' modes are still computed from `modes` (its defaults, for the other models).
  trees::SpeciesDynamics dynamics;
  ModeSettings modes;
  /// C_D of the branches (cylinders in cross flow) per frontal area, >= 0.
  double drag_coefficient = schema::key(schema::kSpeciesKeys, "forest.species[].drag_coefficient").number;
  CanopySettings canopy;
  /// forest.species[].leaves: the file's keys over trees::LeafSettings' defaults (the schema's), seed
  /// resolved (kLeafSeedOffset). Model none (no leaves) when the file has no `leaves`; with leaves,
  /// canopy.leaf_area_index > 0.
  trees::LeafSettings leaves{.model = trees::FlutterModel::none};
  /// forest.species[].strength: a preset's values on its soil and rooting with the numbers given over them,
  /// or the four numbers given; validated. nullopt when the file has no `strength` (required when
  /// forest.damage.enabled is true).
  std::optional<trees::TreeStrength> strength;
  int strength_line = 0;  ///< the line of `strength` (of the species entry when not given)
  /// Where the strength comes from, for reports: "sitka_spruce (soil A, mean rooting)", "given", or the keys
  /// given over a preset, "knot_factor given over norway_spruce (soil A, mean rooting)". Empty without one.
  std::string strength_source;
};

}  // namespace fw::io
