// forest.species: skeletons, wood, tree model (dynamics and its keys), modes, drag, canopy, leaves and
// strength of each species. The checks that need the skeleton (check_species_skeleton) are io/Scenario.cpp's.
#include "io/scenario/Species.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <optional>
#include <stdexcept>
#include <string>
#include <vector>

namespace fw::io::reader {

namespace {

/// forest.species[].skeleton: exactly one of generate, file and qsm. `seed`: the generator's, unless the file
/// gives one.
SkeletonSource read_skeleton(const Loader& loader, const Field& field, std::uint64_t seed) {
  const Section<schema::kSpeciesKeys, "forest.species[].skeleton"> map(loader, field);
  map.exactly_one();
  SkeletonSource skeleton;
  if (const auto generate_field = map.get<"generate">()) {
    const Section<schema::kSpeciesKeys, "forest.species[].skeleton.generate"> generate(loader,
                                                                                       *generate_field);
    skeleton.kind = SkeletonSource::Kind::generate;
    skeleton.generate.preset = loader.word(generate.require<"preset">());
    skeleton.key = generate_field->key;
    skeleton.line = generate_field->line;
    if (const auto height = generate.get<"height">()) {
      skeleton.key = height->key;
      skeleton.line = height->line;
      skeleton.generate.height = loader.number(*height);
      // 0 stands for the preset's own height; any other height is a tree's.
      if (skeleton.generate.height > 0.0 && skeleton.generate.height < schema::bounds::kMinTreeHeight)
        loader.expected(*height,
                        fmt::format("{}: 0 (the preset's height) or at least {} m",
                                    schema::expected(key_of(*height)), schema::bounds::kMinTreeHeight));
    }
    skeleton.generate.seed = seed;
    if (const auto given = generate.get<"seed">()) skeleton.generate.seed = loader.seed(*given);
  }
  if (const auto file = map.get<"file">()) {
    skeleton.kind = SkeletonSource::Kind::file;
    skeleton.path = loader.readable_file(*file);
    skeleton.key = file->key;
    skeleton.line = file->line;
  }
  if (const auto qsm = map.get<"qsm">()) {
    skeleton.kind = SkeletonSource::Kind::qsm;
    skeleton.path = loader.readable_file(*qsm);
    skeleton.key = qsm->key;
    skeleton.line = qsm->line;
  }
  return skeleton;
}

void read_material(const Loader& loader, const Field& field, trees::Material& material) {
  const Section<schema::kSpeciesKeys, "forest.species[].material"> map(loader, field);
  if (const auto e = map.get<"youngs_modulus">()) material.youngs_modulus = loader.number(*e);
  if (const auto g = map.get<"shear_modulus">()) material.shear_modulus = loader.number(*g);
  if (const auto rho = map.get<"density">()) material.density = loader.number(*rho);
  // Each within its bounds, the three can still make no wood (io/schema/Bounds.hpp): the map is to blame.
  const double stretch = material.youngs_modulus / material.density;
  const double shear = material.shear_modulus / material.density;
  if (!(stretch >= schema::bounds::kMinSpecificModulus &&
        shear >= schema::bounds::kMinSpecificShearModulus)) {
    loader.fail(field,
                fmt::format("a wood with youngs_modulus / density >= {} and shear_modulus / density >= {} "
                            "m^2/s^2 expected (wood: 5e6 to 3e7 and 5e5 to 3e6), got {:.3g} and {:.3g}",
                            schema::number_text(schema::bounds::kMinSpecificModulus),
                            schema::number_text(schema::bounds::kMinSpecificShearModulus), stretch, shear));
  }
}

void read_modes(const Loader& loader, const Field& field, ModeSettings& modes) {
  const Section<schema::kSpeciesKeys, "forest.species[].modes"> map(loader, field);
  if (const auto count = map.get<"count">()) {
    modes.count = loader.integer(*count);
    modes.count_line = count->line;
  }
  if (const auto zeta = map.get<"damping_ratio">()) modes.damping_ratio = loader.number(*zeta);
  if (const auto samples = map.get<"wind_samples">()) modes.wind_samples = loader.integer(*samples);
}

/// forest.species[].rigid_bodies over trees::RigidBodySettings' defaults (the schema's).
void read_rigid_bodies(const Loader& loader, const Field& field, trees::RigidBodySettings& rigid_bodies) {
  const Section<schema::kSpeciesKeys, "forest.species[].rigid_bodies"> map(loader, field);
  if (const auto zeta = map.get<"damping_ratio">()) rigid_bodies.damping_ratio = loader.number(*zeta);
}

/// forest.species[].springs over trees::SpringSettings' defaults (the schema's).
void read_springs(const Loader& loader, const Field& field, trees::SpringSettings& springs) {
  const Section<schema::kSpeciesKeys, "forest.species[].springs"> map(loader, field);
  if (const auto angle = map.get<"max_angle_deg">()) springs.max_angle_deg = loader.number(*angle);
  if (const auto amplitude = map.get<"sway_amplitude">()) springs.sway_amplitude = loader.number(*amplitude);
  if (const auto frequency = map.get<"sway_frequency">())
    springs.sway_frequency_hz = loader.number(*frequency);
}

/// A key of one model's settings (`modes` of modal, `rigid_bodies`, `springs`) on a species that another
/// model moves is refused, not ignored: it would tune what does not move the tree. `dynamics`: the species'
/// dynamics key, where the file gives it.
void refuse_other_model(const Loader& loader, const std::optional<Field>& model_key,
                        trees::TreeDynamics owner, trees::TreeDynamics model,
                        const std::optional<Field>& dynamics) {
  if (!model_key || owner == model) return;
  const std::string name = model_key->key.substr(model_key->key.rfind('.') + 1);
  const std::string where = dynamics ? fmt::format("on line {}", dynamics->line) : std::string("the default");
  loader.fail(*model_key,
              fmt::format("a key of the {} model, but this species' dynamics is {} ({}); leave {} out or set "
                          "dynamics: {}",
                          trees::dynamics_name(owner), trees::dynamics_name(model), where, name,
                          trees::dynamics_name(owner)));
}

/// forest.species[].dynamics and its model's keys over trees::SpeciesDynamics' defaults (the schema's); `map`
/// is the species `item`.
trees::SpeciesDynamics read_dynamics(const Loader& loader, const Field& item,
                                     const Section<schema::kSpeciesKeys, "forest.species[]">& map) {
  trees::SpeciesDynamics dynamics;
  const auto word = map.get<"dynamics">();
  if (word) dynamics.model = value(schema::kDynamicsWords, schema::kDynamicsModels, loader.word(*word));
  const auto rigid_bodies = map.get<"rigid_bodies">();
  const auto springs = map.get<"springs">();
  refuse_other_model(loader, map.get<"modes">(), trees::TreeDynamics::modal, dynamics.model, word);
  refuse_other_model(loader, rigid_bodies, trees::TreeDynamics::rigid_bodies, dynamics.model, word);
  refuse_other_model(loader, springs, trees::TreeDynamics::springs, dynamics.model, word);
  if (rigid_bodies) read_rigid_bodies(loader, *rigid_bodies, dynamics.rigid_bodies);
  if (springs) read_springs(loader, *springs, dynamics.springs);
  try {
    dynamics
        .validate();  // passes: the keys' ranges are SpeciesDynamics' own (tests/io/ScenarioSchema_test.cpp)
  } catch (const std::invalid_argument& error) {
    const Field& blamed = springs ? *springs : rigid_bodies ? *rigid_bodies : item;
    loader.expected(blamed,
                    fmt::format("tree model settings trees::SpeciesDynamics accepts ({})", error.what()));
  }
  return dynamics;
}

/// forest.species[].leaves over trees::LeafSettings' defaults (the schema's); `seed` unless the file gives
/// one.
trees::LeafSettings read_leaves(const Loader& loader, const Field& field, std::uint64_t seed) {
  const Section<schema::kSpeciesKeys, "forest.species[].leaves"> map(loader, field);
  trees::LeafSettings leaves;
  if (const auto model = map.get<"model">())
    leaves.model = value(schema::kLeafModelWords, schema::kLeafModels, loader.word(*model));
  if (const auto area = map.get<"area">()) leaves.area = loader.number(*area);
  if (const auto fraction = map.get<"fraction">()) leaves.fraction = loader.number(*fraction);
  if (const auto sigma = map.get<"mass_per_area">()) leaves.mass_per_area = loader.number(*sigma);
  if (const auto frequency = map.get<"frequency">()) leaves.frequency = loader.number(*frequency);
  if (const auto zeta = map.get<"damping_ratio">()) leaves.damping_ratio = loader.number(*zeta);
  if (const auto strength = map.get<"petiole_strength">()) leaves.petiole_strength = loader.number(*strength);
  if (const auto spread = map.get<"strength_spread">()) leaves.strength_spread = loader.number(*spread);
  if (const auto drag = map.get<"flight_drag_coefficient">())
    leaves.flight_drag_coefficient = loader.number(*drag);
  if (const auto amplitudes = map.get<"amplitudes">()) leaves.amplitudes_deg = loader.vector<3>(*amplitudes);
  if (const auto roll = map.get<"roll_coupling">()) leaves.roll_coupling = loader.number(*roll);
  if (const auto speed = map.get<"reference_speed">()) leaves.reference_speed = loader.number(*speed);
  leaves.seed = seed;
  if (const auto given = map.get<"seed">()) leaves.seed = loader.seed(*given);
  try {
    leaves.validate();  // passes: the keys' ranges are LeafSettings' own (tests/io/ScenarioSchema_test.cpp)
  } catch (const std::invalid_argument& error) {
    loader.expected(field, fmt::format("leaf settings trees::LeafSettings accepts ({})", error.what()));
  }
  return leaves;
}

/// forest.species[].strength into `species`: a preset's values on its soil and rooting with the numbers given
/// over them, or the four numbers, each required, without a preset.
void read_strength(const Loader& loader, const Field& field, Species& species) {
  const Section<schema::kSpeciesKeys, "forest.species[].strength"> map(loader, field);
  const auto preset_word = map.get<"preset">();
  const auto soil_word = map.get<"soil">();
  const auto rooting_word = map.get<"rooting">();
  const auto anchorage = map.get<"anchorage">();
  // Soil and rooting choose the preset's anchorage and nothing else: without a preset, or beside an
  // anchorage given, they would choose nothing.
  for (const std::optional<Field>& chooser : {soil_word, rooting_word}) {
    if (!chooser) continue;
    const std::string name = chooser->key.substr(chooser->key.rfind('.') + 1);
    if (!preset_word)
      loader.expected(
          *chooser,
          fmt::format("{} only beside a preset (soil and rooting choose a preset's anchorage)", name));
    if (anchorage)
      loader.expected(*chooser, fmt::format("{} only without anchorage (anchorage on line {} replaces the "
                                            "anchorage soil and rooting choose)",
                                            name, anchorage->line));
  }

  trees::TreeStrength strength;
  std::string preset_text;
  if (preset_word) {
    const trees::StrengthPreset preset = *trees::parse_strength_preset(loader.word(*preset_word));
    trees::SoilGroup soil =
        *trees::parse_soil_group(schema::key(schema::kSpeciesKeys, "forest.species[].strength.soil").word);
    trees::RootingDepth rooting = *trees::parse_rooting_depth(
        schema::key(schema::kSpeciesKeys, "forest.species[].strength.rooting").word);
    if (soil_word) soil = *trees::parse_soil_group(loader.word(*soil_word));
    if (rooting_word) rooting = *trees::parse_rooting_depth(loader.word(*rooting_word));
    // Only a rooting given can miss: the default has an anchorage on every soil.
    if (!trees::has_anchorage(soil, rooting)) {
      std::vector<std::string> fit;
      for (const std::string& word : schema::rooting_depth_words())
        if (trees::has_anchorage(soil, *trees::parse_rooting_depth(word))) fit.push_back(word);
      loader.expected(rooting_word.value_or(field),
                      fmt::format("one of {} (the table has no anchorage for {} rooting on soil {}{})",
                                  join(fit, " | "), trees::rooting_name(rooting), trees::soil_name(soil),
                                  soil_word ? fmt::format(", line {}", soil_word->line) : std::string()));
    }
    strength = trees::strength_preset(preset, soil, rooting);
    preset_text = anchorage ? std::string(trees::preset_name(preset))
                            : fmt::format("{} (soil {}, {} rooting)", trees::preset_name(preset),
                                          trees::soil_name(soil), trees::rooting_name(rooting));
  }

  // Without a preset every number is needed; the first missing one, in the table's order, is named.
  const std::string reason = "needed without a preset";
  const auto modulus_of_rupture =
      preset_word ? map.get<"modulus_of_rupture">() : map.require<"modulus_of_rupture">(reason);
  const auto knot_factor = preset_word ? map.get<"knot_factor">() : map.require<"knot_factor">(reason);
  const auto green_density = preset_word ? map.get<"green_density">() : map.require<"green_density">(reason);
  if (!preset_word) map.require<"anchorage">(reason);
  std::vector<std::string> given;
  const auto read = [&](const std::optional<Field>& number, double& value) {
    if (!number) return;
    value = loader.number(*number);
    given.push_back(number->key.substr(number->key.rfind('.') + 1));
  };
  read(modulus_of_rupture, strength.modulus_of_rupture);
  read(knot_factor, strength.knot_factor);
  read(green_density, strength.green_density);
  read(anchorage, strength.anchorage);
  // Passes: the keys' ranges lie within TreeStrength's (tests/io/ScenarioSchema_test.cpp).
  try {
    strength.validate();
  } catch (const std::invalid_argument& error) {
    loader.expected(field, fmt::format("a strength trees::TreeStrength accepts ({})", error.what()));
  }
  species.strength = strength;
  species.strength_line = field.line;
  species.strength_source = !preset_word    ? std::string("given")
                            : given.empty() ? preset_text
                                            : fmt::format("{} given over {}", join(given, ", "), preset_text);
}

}  // namespace

// global_seed + 1 + its index seeds a species' generator, global_seed + kLeafSeedOffset + its index its
// leaves, unless the file gives a seed.
Species read_species(const Loader& loader, const Field& item, const std::vector<Species>& earlier,
                     std::uint64_t global_seed) {
  const Section<schema::kSpeciesKeys, "forest.species[]"> map(loader, item);
  Species species;
  species.line = species.modes.count_line = species.strength_line = item.line;
  const Field name = map.require<"name">();
  species.name = loader.text(name);
  for (const Species& other : earlier)
    if (other.name == species.name)
      loader.expected(name, schema::expected(key_of(name)) + " not used before");

  species.skeleton = read_skeleton(loader, map.require<"skeleton">(), global_seed + 1 + earlier.size());
  if (const auto material = map.get<"material">()) read_material(loader, *material, species.material);
  species.dynamics = read_dynamics(loader, item, map);
  if (const auto modes = map.get<"modes">()) read_modes(loader, *modes, species.modes);
  if (const auto drag = map.get<"drag_coefficient">()) species.drag_coefficient = loader.number(*drag);

  std::optional<Field> lai;
  Field lai_missing = map.missing<"canopy.leaf_area_index">();  // on the species' line, or canopy's
  if (const auto canopy_field = map.get<"canopy">()) {
    const Section<schema::kSpeciesKeys, "forest.species[].canopy"> canopy(loader, *canopy_field);
    lai = canopy.get<"leaf_area_index">();
    lai_missing = canopy.missing<"leaf_area_index">();
    if (lai) species.canopy.leaf_area_index = loader.number(*lai);
    if (const auto drag = canopy.get<"drag_coefficient">())
      species.canopy.drag_coefficient = loader.number(*drag);
  }
  species.canopy.leaf_area_index_line = (lai ? *lai : lai_missing).line;

  species.leaves.seed = global_seed + kLeafSeedOffset + earlier.size();
  if (const auto leaves = map.get<"leaves">()) {
    species.leaves = read_leaves(loader, *leaves, species.leaves.seed);
    // The leaves sit on the canopy's foliage (trees/Foliage.hpp): without leaf area there would be none.
    if (species.leaves.has_leaves() && !(species.canopy.leaf_area_index > 0.0)) {
      const Key& key = key_of(lai_missing);
      const std::string what = schema::expected(
          Key{.path = key.path, .type = schema::Type::number, .unit = key.unit, .bound = Bound::positive});
      const std::string reason =
          fmt::format("leaves need a leaf area index > 0; {} is on line {}", leaves->key, leaves->line);
      if (lai) loader.expected(*lai, fmt::format("{} ({})", what, reason));
      loader.fail(lai_missing,
                  fmt::format("{} expected (required here: {}, and the default is {}), got nothing", what,
                              reason, key.number));
    }
  }
  if (const auto strength = map.get<"strength">()) read_strength(loader, *strength, species);
  return species;
}

}  // namespace fw::io::reader
