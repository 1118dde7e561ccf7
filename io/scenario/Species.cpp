// forest.species: skeletons, wood, modes, drag, canopy and leaves of each species; and the checks that need
// the skeleton (check_species_skeleton).
#include "io/scenario/Sections.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <stdexcept>

namespace fw::io::reader {

namespace {

/// forest.species[].leaves over trees::LeafSettings' defaults (the schema's); `seed` unless the file gives
/// one.
trees::LeafSettings read_leaves(const Loader& loader, const Field& field, std::uint64_t seed) {
  const MapFields map(loader, field);
  trees::LeafSettings leaves;
  if (const auto model = map.get("model"))
    leaves.model = value(schema::kLeafModelWords, schema::kLeafModels, loader.word(*model));
  const auto number = [&](const char* name, double& target) {
    const auto given = map.get(name);
    if (given) target = loader.number(*given);
    return given;
  };
  number("area", leaves.area);
  number("fraction", leaves.fraction);
  number("mass_per_area", leaves.mass_per_area);
  number("frequency", leaves.frequency);
  number("damping_ratio", leaves.damping_ratio);
  number("petiole_strength", leaves.petiole_strength);
  number("strength_spread", leaves.strength_spread);
  number("flight_drag_coefficient", leaves.flight_drag_coefficient);
  if (const auto amplitudes = map.get("amplitudes")) leaves.amplitudes_deg = loader.vector<3>(*amplitudes);
  number("roll_coupling", leaves.roll_coupling);
  number("reference_speed", leaves.reference_speed);
  leaves.seed = seed;
  if (const auto given = map.get("seed")) leaves.seed = loader.seed(*given);
  try {
    leaves.validate();  // passes: the keys' ranges are LeafSettings' own (tests/io/ScenarioSchema_test.cpp)
  } catch (const std::invalid_argument& error) {
    loader.expected(field, fmt::format("leaf settings trees::LeafSettings accepts ({})", error.what()));
  }
  return leaves;
}

}  // namespace

// global_seed + 1 + its index seeds a species' generator, global_seed + kLeafSeedOffset + its index its
// leaves, unless the file gives a seed.
Species read_species(const Loader& loader, const Field& item, const std::vector<Species>& earlier,
                     std::uint64_t global_seed) {
  const MapFields map(loader, item);
  Species species;
  species.modes.count_line = item.line;
  const Field name = map.require("name");
  species.name = loader.text(name);
  for (const Species& other : earlier)
    if (other.name == species.name)
      loader.expected(name, schema::expected(key_of(name)) + " not used before");

  const MapFields skeleton(loader, map.require("skeleton"));
  const std::string source = the_one_key(loader, skeleton);
  const Field body = *skeleton.get(source);
  if (source == "generate") {
    species.skeleton.kind = SkeletonSource::Kind::generate;
    const MapFields generate(loader, body);
    species.skeleton.generate.preset = loader.word(generate.require("preset"));
    if (const auto height = generate.get("height")) species.skeleton.generate.height = loader.number(*height);
    species.skeleton.generate.seed = global_seed + 1 + earlier.size();
    if (const auto seed = generate.get("seed")) species.skeleton.generate.seed = loader.seed(*seed);
  } else {
    species.skeleton.kind = source == "file" ? SkeletonSource::Kind::file : SkeletonSource::Kind::qsm;
    species.skeleton.path = loader.readable_file(body);
  }

  if (const auto material_field = map.get("material")) {
    const MapFields material(loader, *material_field);
    if (const auto e = material.get("youngs_modulus")) species.material.youngs_modulus = loader.number(*e);
    if (const auto g = material.get("shear_modulus")) species.material.shear_modulus = loader.number(*g);
    if (const auto rho = material.get("density")) species.material.density = loader.number(*rho);
  }
  if (const auto modes_field = map.get("modes")) {
    const MapFields modes(loader, *modes_field);
    if (const auto count = modes.get("count")) {
      species.modes.count = loader.integer(*count);
      species.modes.count_line = count->line;
    }
    if (const auto zeta = modes.get("damping_ratio")) species.modes.damping_ratio = loader.number(*zeta);
    if (const auto samples = modes.get("wind_samples")) species.modes.wind_samples = loader.integer(*samples);
  }
  if (const auto drag = map.get("drag_coefficient")) species.drag_coefficient = loader.number(*drag);
  const auto canopy_field = map.get("canopy");
  std::optional<Field> lai;
  if (canopy_field) {
    const MapFields canopy(loader, *canopy_field);
    lai = canopy.get("leaf_area_index");
    if (lai) species.canopy.leaf_area_index = loader.number(*lai);
    if (const auto drag = canopy.get("drag_coefficient"))
      species.canopy.drag_coefficient = loader.number(*drag);
  }
  species.leaves.seed = global_seed + kLeafSeedOffset + earlier.size();
  if (const auto leaves = map.get("leaves")) {
    species.leaves = read_leaves(loader, *leaves, species.leaves.seed);
    // The leaves sit on the canopy's foliage (trees/Foliage.hpp): without leaf area there would be none.
    if (species.leaves.has_leaves() && !(species.canopy.leaf_area_index > 0.0)) {
      const Field missing =
          lai ? *lai
              : Field{canopy_field ? canopy_field->node : item.node, item.key + ".canopy.leaf_area_index",
                      canopy_field ? canopy_field->line : item.line};
      const Key& key = key_of(missing);
      const std::string what = schema::expected(
          Key{.path = key.path, .type = schema::Type::number, .unit = key.unit, .bound = Bound::positive});
      const std::string reason =
          fmt::format("leaves need a leaf area index > 0; {} is on line {}", leaves->key, leaves->line);
      if (lai) loader.expected(*lai, fmt::format("{} ({})", what, reason));
      loader.fail(missing, fmt::format("{} expected (required here: {}, and the default is {}), got nothing",
                                       what, reason, key.number));
    }
  }
  return species;
}

}  // namespace fw::io::reader

namespace fw::io {

void check_species_skeleton(const Scenario& scenario, int species_index, int skeleton_nodes) {
  const Species& species = scenario.forest.species.at(std::size_t(species_index));
  // A skeleton of n nodes, root clamped, has 6 (n - 1) DOFs; the modal analysis keeps fewer modes than that.
  const long dofs = 6L * (skeleton_nodes - 1);
  if (species.modes.count >= dofs) {
    throw ScenarioError(
        scenario.file.string(), species.modes.count_line,
        fmt::format("forest.species[{}].modes.count", species_index),
        fmt::format("at most {} modes for this skeleton of {} nodes ({} DOFs) expected, got '{}'",
                    std::max(0L, dofs - 1), skeleton_nodes, dofs, species.modes.count));
  }
}

}  // namespace fw::io
