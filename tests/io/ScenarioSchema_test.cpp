#include "io/ScenarioSchema.hpp"

#include <catch2/catch.hpp>

#include <cmath>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <limits>
#include <set>
#include <span>
#include <sstream>
#include <string>
#include <utility>

#include "fluid/GridSpec.hpp"
#include "fluid/TurbulenceBox.hpp"
#include "fluid/WindSettings.hpp"
#include "io/Scenario.hpp"
#include "io/schema/BoundaryKeys.hpp"
#include "io/schema/DomainKeys.hpp"
#include "io/schema/EventKeys.hpp"
#include "io/schema/ForestKeys.hpp"
#include "io/schema/ObstacleKeys.hpp"
#include "io/schema/OutputKeys.hpp"
#include "io/schema/SolverKeys.hpp"
#include "io/schema/SpeciesKeys.hpp"
#include "io/schema/TerrainKeys.hpp"
#include "io/schema/TimeKeys.hpp"
#include "io/schema/TopLevelKeys.hpp"
#include "io/schema/WindKeys.hpp"
#include "trees/LeafSettings.hpp"
#include "trees/TreeDynamics.hpp"
#include "trees/TreeStrength.hpp"

namespace schema = fw::io::schema;

namespace {

// The committed page, next to this test's source tree (as tests/host/runtime/KernelSources_test.cpp finds
// the kernels).
std::filesystem::path docs_page() {
  return std::filesystem::path(__FILE__).parent_path().parent_path().parent_path() / "docs" / "scenario.md";
}

std::string read_text(const std::filesystem::path& path) {
  std::ifstream in(path, std::ios::binary);
  std::ostringstream text;
  text << in.rdbuf();
  return text.str();
}

/// "" when equal, else the first line that differs, on both sides (the whole page would drown the report).
std::string first_difference(const std::string& committed, const std::string& generated) {
  std::istringstream a(committed), b(generated);
  std::string left, right;
  for (int line = 1;; ++line) {
    const bool more_left = bool(std::getline(a, left)), more_right = bool(std::getline(b, right));
    if (!more_left && !more_right) return "";
    if (more_left != more_right || left != right)
      return "line " + std::to_string(line) + ":\n  committed: " + (more_left ? left : "(end)") +
             "\n  generated: " + (more_right ? right : "(end)");
  }
}

/// The key at a generic path, looked up at run time over every section.
const schema::Key& key_at(std::string_view path) {
  const schema::Key* found = schema::find(path);
  INFO("key " << path);
  REQUIRE(found != nullptr);
  return *found;
}

/// Every section's table, each from its own header: what the loader's readers and the structs' defaults
/// compile.
const std::span<const schema::Key> kSectionTables[] = {
    schema::kTopLevelKeys, schema::kTimeKeys,    schema::kDomainKeys,   schema::kBoundaryKeys,
    schema::kWindKeys,     schema::kEventKeys,   schema::kObstacleKeys, schema::kTerrainKeys,
    schema::kForestKeys,   schema::kSpeciesKeys, schema::kSolverKeys,   schema::kOutputKeys};

}  // namespace

TEST_CASE("schema: docs/scenario.md's key tables are the ones the schema generates", "[schema]") {
  const std::filesystem::path page = docs_page();
  REQUIRE(std::filesystem::exists(page));
  const std::string committed = read_text(page);
  const std::string generated = schema::render_scenario_docs(committed);
  if (generated != committed && std::getenv("FORESTWIND_UPDATE_DOCS") != nullptr) {
    std::ofstream(page, std::ios::binary) << generated;
    WARN("rewrote " << page.string());
    return;
  }
  INFO(
      "docs/scenario.md differs from the schema (io/schema/); regenerate its tables with "
      "FORESTWIND_UPDATE_DOCS=1 io_tests \"[schema]\" and commit the page");
  CHECK(first_difference(committed, generated) == "");
}

TEST_CASE("schema: every key sits below a map or list of the table, once", "[schema]") {
  std::set<std::string_view> paths;
  for (const schema::Key* entry : schema::all_keys()) {
    const schema::Key& key = *entry;
    INFO("key " << key.path);
    CHECK(paths.insert(key.path).second);  // in one section only
    CHECK_FALSE(schema::docs(key).description.empty());
    const std::size_t dot = key.path.rfind('.');
    if (dot == std::string_view::npos) continue;
    std::string_view parent = key.path.substr(0, dot);
    const bool item = parent.ends_with("[]");
    if (item) parent.remove_suffix(2);
    const schema::Key* owner = schema::find(parent);
    REQUIRE(owner != nullptr);
    if (item)
      CHECK((owner->type == schema::Type::list || owner->type == schema::Type::choice_list));
    else
      CHECK((owner->type == schema::Type::map || owner->type == schema::Type::choice));
  }
  // Every map and every list's items have keys: a section table the run-time look-up left out would leave
  // its map empty.
  for (const schema::Key* key : schema::all_keys()) {
    INFO("key " << key->path);
    if (key->type == schema::Type::map || key->type == schema::Type::choice)
      CHECK_FALSE(schema::children(key->path).empty());
    if (key->type == schema::Type::list || key->type == schema::Type::choice_list)
      CHECK_FALSE(schema::children(std::string(key->path) + "[]").empty());
  }
}

TEST_CASE("schema: every section's keys are the run-time look-up's, each with its prose", "[schema]") {
  std::size_t count = 0;
  for (const std::span<const schema::Key> keys : kSectionTables) {
    for (const schema::Key& key : keys) {
      INFO("key " << key.path);
      CHECK(schema::find(key.path) == &key);  // the very key the section's readers and defaults read
      CHECK(schema::docs(key).path == key.path);
      ++count;
    }
  }
  CHECK(schema::all_keys().size() == count);  // and no other
}

TEST_CASE("schema: the loader's messages come from the key's type, bound and unit", "[schema]") {
  CHECK(schema::expected(key_at("time.end")) == "a number > 0 and <= 1e9 (s)");
  CHECK(schema::expected(key_at("time.dt")) == "a number > 0 and <= 3600 (s) or auto");
  CHECK(schema::expected(key_at("time")) == "a map {end, dt, cfl, spin_up}");
  CHECK(schema::expected(key_at("time.spin_up")) == "a number >= 0 and <= 1e9 (s)");
  CHECK(schema::expected(key_at("domain.size")) ==
        "a list of 3 numbers [x, y, z], each > 0 and <= 40075017 (m)");
  CHECK(schema::expected(key_at("forest.species[].modes.wind_samples")) == "an integer 1..16");
  CHECK(schema::expected(key_at("forest.species[].modes.count")) == "an integer 1..1000");
  CHECK(schema::expected(key_at("solver.pressure")) == "one of multigrid | cg | jacobi");
  CHECK(schema::expected(key_at("boundaries.ground")) ==
        "one of inflow | outflow | slip | no_slip | periodic | rough");
  CHECK(schema::expected(key_at("boundaries.top")) == "one of inflow | outflow | slip | no_slip | periodic");
  CHECK(schema::expected(key_at("boundaries.west")) ==
        "one of auto | inflow | outflow | slip | no_slip | periodic");
  CHECK(schema::expected(key_at("wind.turbulence.sigma")) ==
        "a list of 3 numbers [sigma_u, sigma_v, sigma_w], each > 0 and <= 150 (m/s)");
  CHECK(schema::expected(key_at("output.probe_interval")) == "a number > 0 and <= 1e9 (s) or auto");
  CHECK(schema::child_names("wind.turbulence") == std::vector<std::string>{"model", "intensity", "sigma",
                                                                           "length_scale", "box_size", "seed",
                                                                           "unresolved", "cutoff_cells"});
  // boundaries' first six keys are the faces, in the order of FW_FACE_* (the loader indexes them so).
  CHECK(schema::child_names("boundaries") ==
        std::vector<std::string>{"west", "east", "south", "north", "ground", "top", "roughness_length"});
  CHECK(schema::expected(key_at("forest.species[].skeleton")) ==
        "a map with exactly one of the keys generate, file, qsm");
  CHECK(schema::child_names("forest.species[].modes") ==
        std::vector<std::string>{"count", "damping_ratio", "wind_samples"});
  CHECK(schema::generic_path("forest.species[12].modes.count") == "forest.species[].modes.count");
  CHECK(schema::generic_path("output.vtk.fields[1]") == "output.vtk.fields[]");
  CHECK(schema::expected(key_at("forest.species[].leaves.amplitudes")) ==
        "a list of 3 numbers [W_H, W_V, W_R], each >= 0 and <= 90 (degrees)");
  CHECK(schema::expected(key_at("forest.species[].leaves.fraction")) == "a number > 0 and <= 1");
  CHECK(schema::expected(key_at("forest.species[].leaves.damping_ratio")) == "a number >= 0 and < 1");
  CHECK(schema::expected(key_at("solver.smagorinsky_constant")) == "a number >= 0 and < 1");
  CHECK(schema::expected(key_at("forest.species[].leaves.model")) ==
        "one of none | pseudo_branch | stochastic");
  CHECK(schema::expected(key_at("output.leaves.attached")) ==
        "one of all | none or an integer 1..2147483647");
  CHECK(schema::child_names("output.leaves") == std::vector<std::string>{"attached", "vtk", "every"});
}

TEST_CASE("schema: a reader's key is looked up below its map, so that a key the map lacks cannot be read",
          "[schema]") {
  // The loader's Section<KEYS, PATH>::get<NAME>() compiles only where schema::key(KEYS, PATH, NAME) finds
  // the key; the same look-up, here at compile time too.
  using schema::holds_keys, schema::kTimeKeys, schema::kSpeciesKeys, schema::kTopLevelKeys;
  static_assert(&schema::key(kTimeKeys, "time", "cfl") == &schema::key(kTimeKeys, "time.cfl"));
  static_assert(&schema::key(kSpeciesKeys, "forest.species[]", "modes") ==
                &schema::key(kSpeciesKeys, "forest.species[].modes"));
  static_assert(&schema::key(kTopLevelKeys, "", "scenario") == &schema::key(kTopLevelKeys, "scenario"));
  static_assert(&schema::key(kSpeciesKeys, "forest.species[]", "canopy.leaf_area_index") ==
                &schema::key(kSpeciesKeys, "forest.species[].canopy.leaf_area_index"));
  static_assert(schema::find(kTimeKeys, "time", "cfll") == nullptr);  // a typo
  static_assert(schema::find(kTimeKeys, "time", "fl") == nullptr);    // a tail of a name is not the name
  static_assert(schema::find(schema::kForestKeys, "forest.species", "name") == nullptr);  // the list, not its
  static_assert(schema::find(kSpeciesKeys, "forest.species", "name") == nullptr);         // items
  static_assert(schema::find(kTopLevelKeys, "", "cfl") == nullptr);  // not at the top level
  static_assert(holds_keys(kTopLevelKeys, "") && holds_keys(kSpeciesKeys, "forest.species[]") &&
                holds_keys(schema::kWindKeys, "wind.profile") && holds_keys(schema::kEventKeys, "events[]"));
  static_assert(!holds_keys(schema::kForestKeys, "forest.species") && !holds_keys(kTimeKeys, "time.cfl") &&
                !holds_keys(kTimeKeys, "tme"));
  // A section's table holds the keys of its own maps only: not the top level's, nor another section's.
  static_assert(!holds_keys(kTimeKeys, "") && !holds_keys(schema::kWindKeys, "time") &&
                !holds_keys(schema::kForestKeys, "forest.species[]"));
  // Each key is found from its parent's path and its own name, in the table that holds it.
  for (const std::span<const schema::Key> keys : kSectionTables) {
    for (const schema::Key& key : keys) {
      INFO("key " << key.path);
      const std::size_t dot = key.path.rfind('.');
      const std::string_view parent = dot == std::string_view::npos ? "" : key.path.substr(0, dot);
      const std::string_view name = dot == std::string_view::npos ? key.path : key.path.substr(dot + 1);
      CHECK(schema::find(keys, parent, name) == &key);
    }
  }
}

TEST_CASE("schema: defaults owned elsewhere are read from their owner, once", "[schema]") {
  // One pressure tolerance for the wind grid and the scenario.
  CHECK(key_at("solver.tolerance").number == fw::fluid::kDefaultPressureTolerance);
  CHECK(fw::fluid::PressureSettings{}.tolerance == fw::fluid::kDefaultPressureTolerance);
  CHECK(fw::io::SolverSettings{}.tolerance == fw::fluid::kDefaultPressureTolerance);
  // One default wood.
  const fw::trees::Material wood = fw::io::Species{}.material;
  CHECK(wood.youngs_modulus == fw::trees::kDefaultWood.youngs_modulus);
  CHECK(wood.shear_modulus == fw::trees::kDefaultWood.shear_modulus);
  CHECK(wood.density == fw::trees::kDefaultWood.density);
  // The solver's words name fluid's own defaults, so a scenario without `solver` runs as WindSettings does.
  const fw::fluid::WindSettings wind;
  CHECK(fw::fluid::to_string(wind.pressure.solver) == key_at("solver.pressure").word);
  CHECK(fw::fluid::to_string(wind.advection) == key_at("solver.advection").word);
  const fw::io::Scenario scenario;
  CHECK(scenario.wind_settings().pressure.max_iterations == wind.pressure.max_iterations);
  CHECK(scenario.wind_settings().pressure.jacobi_iterations == wind.pressure.jacobi_iterations);
  // Foliage drag per one-sided leaf area, as the branches': 1/2 C_D = 0.2, the canopy LES C_d.
  CHECK(fw::io::CanopySettings{}.drag_coefficient == fw::trees::WindBasisSettings::kFoliageDragCoefficient);
  CHECK(fw::io::Species{}.drag_coefficient == fw::trees::WindBasisSettings::kCylinderDragCoefficient);
}

TEST_CASE("schema: limits checked elsewhere too are read from their owner, once", "[schema]") {
  CHECK(key_at("solver.smagorinsky_constant").below == fw::fluid::WindSettings::kSmagorinskyConstantBelow);
  CHECK(schema::docs(key_at("domain.cell_size")).limits[0] == double(fw::fluid::GridSpec::kMaxFaces));
  CHECK(schema::docs(key_at("forest.stands[].spacing")).limits[0] == double(fw::trees::kMaxTreesPerStand));
  CHECK(key_at("forest.species[].modes.wind_samples").highest == FW_MAX_TREE_SAMPLES);
  // The turbulence box: its points per cell and its most points are the box's own.
  CHECK(schema::docs(key_at("wind.turbulence.box_size")).limits[1] == fw::fluid::kTurbulencePointsPerCell);
  CHECK(schema::docs(key_at("wind.turbulence.box_size")).limits[2] ==
        double(fw::fluid::TurbulenceBoxSpec::kMaxPoints));
  // The smallest Smagorinsky constant the schema refuses is the smallest WindSettings refuses.
  fw::fluid::WindSettings settings;
  settings.smagorinsky_constant = key_at("solver.smagorinsky_constant").below;
  CHECK_THROWS(settings.validate());
  settings.smagorinsky_constant = std::nextafter(settings.smagorinsky_constant, 0.0);
  CHECK_NOTHROW(settings.validate());
}

TEST_CASE("schema: the leaf keys take trees::LeafSettings' defaults, words and limits", "[schema]") {
  const fw::trees::LeafSettings leaves;
  const auto number = [](const char* name) {
    return schema::find(std::string("forest.species[].leaves.") + name)->number;
  };
  CHECK(schema::value_of(schema::kLeafModelWords, schema::kLeafModels,
                         key_at("forest.species[].leaves.model").word) == leaves.model);
  CHECK(number("area") == leaves.area);
  CHECK(number("fraction") == leaves.fraction);
  CHECK(number("mass_per_area") == leaves.mass_per_area);
  CHECK(number("frequency") == leaves.frequency);
  CHECK(number("damping_ratio") == leaves.damping_ratio);
  CHECK(number("petiole_strength") == leaves.petiole_strength);
  CHECK(number("strength_spread") == leaves.strength_spread);
  CHECK(number("flight_drag_coefficient") == leaves.flight_drag_coefficient);
  CHECK(number("roll_coupling") == leaves.roll_coupling);
  CHECK(number("reference_speed") == leaves.reference_speed);
  const auto amplitudes = key_at("forest.species[].leaves.amplitudes").components;
  CHECK(std::vector<double>(amplitudes.begin(), amplitudes.end()) ==
        std::vector<double>(leaves.amplitudes_deg.begin(), leaves.amplitudes_deg.end()));
  // The model words are trees' own, in the order of the enum.
  for (std::size_t i = 0; i < std::size(schema::kLeafModels); ++i)
    CHECK(fw::trees::to_string(schema::kLeafModels[i]) == schema::kLeafModelWords[i]);
  // No `leaves` in a species: no leaves.
  CHECK_FALSE(fw::io::Species{}.leaves.has_leaves());

  // The keys' upper limits are LeafSettings' own constants...
  const auto leaf_key = [](const char* name) {
    return *schema::find(std::string("forest.species[].leaves.") + name);
  };
  CHECK(leaf_key("fraction").at_most == fw::trees::LeafSettings::kMaxFraction);
  CHECK(leaf_key("damping_ratio").below == fw::trees::LeafSettings::kDampingRatioBelow);
  CHECK(leaf_key("amplitudes").at_most == fw::trees::LeafSettings::kMaxAmplitudeDeg);
  // ... and every leaf number's range is the one LeafSettings::validate checks: the schema's limits (sign
  // bounds and upper limits) in or out as the schema says, so that a file the loader takes never fails
  // validate (which the loader still calls).
  const auto valid = [](const auto& change) {
    fw::trees::LeafSettings settings;
    change(settings);
    try {
      settings.validate();
      return true;
    } catch (const std::invalid_argument&) {
      return false;
    }
  };
  using Leaves = fw::trees::LeafSettings;
  const std::pair<const char*, double Leaves::*> numbers[] = {
      {"area", &Leaves::area},
      {"fraction", &Leaves::fraction},
      {"mass_per_area", &Leaves::mass_per_area},
      {"frequency", &Leaves::frequency},
      {"damping_ratio", &Leaves::damping_ratio},
      {"petiole_strength", &Leaves::petiole_strength},
      {"strength_spread", &Leaves::strength_spread},
      {"flight_drag_coefficient", &Leaves::flight_drag_coefficient},
      {"roll_coupling", &Leaves::roll_coupling},
      {"reference_speed", &Leaves::reference_speed}};
  const double step = 1e-12;  // relative, well above rounding and far below any limit's meaning
  for (const auto& [name, member] : numbers) {
    INFO("leaves." << name);
    const schema::Key& key = leaf_key(name);
    const auto field = member;  // clang 14 (the fuzz build) cannot capture a structured binding
    const auto with = [&](double value) { return valid([&](Leaves& s) { s.*field = value; }); };
    CHECK(with(key.bound == schema::Bound::any ? -1e6 : step) == true);
    CHECK(with(0.0) == (key.bound != schema::Bound::positive));
    CHECK(with(-step) == (key.bound == schema::Bound::any));
    // Every value the schema takes, validate takes; past the limits LeafSettings owns validate refuses too.
    // The other upper bounds are what a scenario can mean (io/schema/Bounds.hpp), within what the type takes.
    if (key.at_most < schema::kNoNumberLimit) {
      CHECK(with(key.at_most));
      if (std::string_view(name) == "fraction") CHECK_FALSE(with(key.at_most * (1.0 + step)));
    }
    if (key.at_least > -schema::kNoNumberLimit) CHECK(with(key.at_least));
    if (key.below < schema::kNoNumberLimit) {
      CHECK(with(key.below * (1.0 - step)));
      CHECK_FALSE(with(key.below));
    }
  }
  const double most = leaf_key("amplitudes").at_most;
  CHECK(valid([&](Leaves& s) { s.amplitudes_deg = {most, 0.0, 0.0}; }));
  CHECK_FALSE(valid([&](Leaves& s) { s.amplitudes_deg = {0.0, most * (1.0 + step), 0.0}; }));
  CHECK(valid([&](Leaves& s) { s.amplitudes_deg = {0.0, 0.0, 0.0}; }));
  CHECK_FALSE(valid([&](Leaves& s) { s.amplitudes_deg = {0.0, 0.0, -step}; }));

  // The output keys' defaults: every attached leaf, leaves.pvd, and the leaves grid among the VDB grids.
  const fw::io::OutputSettings output;
  CHECK(output.leaves_attached_stride == 1);
  CHECK(output.vtk_leaves);
  CHECK(output.vdb_grids == std::vector<std::string>{"vel", "speed", "leaves"});
}

TEST_CASE("schema: the tree model keys take trees::SpeciesDynamics' defaults, words and limits", "[schema]") {
  using fw::trees::SpeciesDynamics;
  const SpeciesDynamics defaults;
  const auto model_key = [](const char* path) {
    return *schema::find(std::string("forest.species[].") + path);
  };
  CHECK(schema::value_of(schema::kDynamicsWords, schema::kDynamicsModels, model_key("dynamics").word) ==
        defaults.model);
  CHECK(model_key("rigid_bodies.damping_ratio").number == defaults.rigid_bodies.damping_ratio);
  CHECK(model_key("springs.max_angle_deg").number == defaults.springs.max_angle_deg);
  CHECK(model_key("springs.sway_amplitude").number == defaults.springs.sway_amplitude);
  CHECK(model_key("springs.sway_frequency").number == defaults.springs.sway_frequency_hz);
  // The words are trees' own, in the order of the enum, and parse back to it.
  REQUIRE(std::size(schema::kDynamicsWords) == std::size(schema::kDynamicsModels));
  for (std::size_t i = 0; i < std::size(schema::kDynamicsModels); ++i) {
    CHECK(fw::trees::dynamics_name(schema::kDynamicsModels[i]) == schema::kDynamicsWords[i]);
    CHECK(fw::trees::parse_dynamics(schema::kDynamicsWords[i]) == schema::kDynamicsModels[i]);
  }
  CHECK(schema::expected(model_key("dynamics")) == "one of modal | rigid_bodies | springs");
  CHECK(schema::child_names("forest.species[].springs") ==
        std::vector<std::string>{"max_angle_deg", "sway_amplitude", "sway_frequency"});

  // Every model number's range is the one SpeciesDynamics::validate checks: the schema's limits in or out as
  // the schema says, so that a file the loader takes never fails validate (which the loader still calls).
  const auto valid = [](const auto& change) {
    SpeciesDynamics dynamics;
    change(dynamics);
    try {
      dynamics.validate();
      return true;
    } catch (const std::invalid_argument&) {
      return false;
    }
  };
  const std::pair<const char*, double* (*)(SpeciesDynamics&)> numbers[] = {
      {"rigid_bodies.damping_ratio", [](SpeciesDynamics& d) { return &d.rigid_bodies.damping_ratio; }},
      {"springs.max_angle_deg", [](SpeciesDynamics& d) { return &d.springs.max_angle_deg; }},
      {"springs.sway_amplitude", [](SpeciesDynamics& d) { return &d.springs.sway_amplitude; }},
      {"springs.sway_frequency", [](SpeciesDynamics& d) { return &d.springs.sway_frequency_hz; }}};
  const double step = 1e-12;  // relative, well above rounding and far below any limit's meaning
  for (const auto& [name, member] : numbers) {
    INFO(name);
    const schema::Key& key = model_key(name);
    const auto field = member;  // clang 14 (the fuzz build) cannot capture a structured binding
    const auto with = [&](double value) { return valid([&](SpeciesDynamics& d) { *field(d) = value; }); };
    CHECK(with(key.bound == schema::Bound::any ? -1e6 : step) == true);
    CHECK(with(0.0) == (key.bound != schema::Bound::positive));
    CHECK(with(-step) == (key.bound == schema::Bound::any));
    CHECK_FALSE(with(std::numeric_limits<double>::infinity()));
    if (key.below < schema::kNoNumberLimit) {
      CHECK(with(key.below * (1.0 - step)));
      CHECK_FALSE(with(key.below));
    }
  }
  CHECK(model_key("springs.max_angle_deg").below == schema::kSpringMaxAngleBelowDeg);
}

TEST_CASE("schema: the strength keys take trees::TreeStrength's words, defaults and limits", "[schema]") {
  namespace trees = fw::trees;
  const auto strength_key = [](const char* name) {
    return *schema::find(std::string("forest.species[].strength.") + name);
  };
  // The words are trees' own: each parses back to the value whose name it is, once.
  const auto round_trip = [](const std::vector<std::string>& words, auto parse, auto name) {
    std::set<std::string> seen;
    for (const std::string& word : words) {
      INFO(word);
      REQUIRE(parse(word).has_value());
      CHECK(name(*parse(word)) == word);
      CHECK(seen.insert(word).second);
    }
  };
  round_trip(schema::words(strength_key("preset")), trees::parse_strength_preset, trees::preset_name);
  round_trip(schema::words(strength_key("soil")), trees::parse_soil_group, trees::soil_name);
  round_trip(schema::words(strength_key("rooting")), trees::parse_rooting_depth, trees::rooting_name);
  CHECK(schema::expected(strength_key("preset")) ==
        "one of sitka_spruce | norway_spruce | scots_pine | birch");
  CHECK(schema::expected(strength_key("soil")) == "one of A | B | C | D");
  CHECK(schema::expected(strength_key("rooting")) == "one of shallow | mean | deep");
  CHECK(schema::child_names("forest.species[].strength") ==
        std::vector<std::string>{"preset", "soil", "rooting", "modulus_of_rupture", "knot_factor",
                                 "green_density", "anchorage"});
  // The default soil and rooting are trees::strength_preset's.
  const trees::SoilGroup soil = *trees::parse_soil_group(strength_key("soil").word);
  const trees::RootingDepth rooting = *trees::parse_rooting_depth(strength_key("rooting").word);
  for (const std::string& word : schema::words(strength_key("preset"))) {
    INFO(word);
    const trees::StrengthPreset preset = *trees::parse_strength_preset(word);
    CHECK(trees::strength_preset(preset).anchorage ==
          trees::strength_preset(preset, soil, rooting).anchorage);
  }

  // Every number's range lies within what TreeStrength::validate takes (which the loader still calls), and
  // knot_factor's upper limit is validate's own.
  const auto valid = [](double trees::TreeStrength::*member, double value) {
    trees::TreeStrength strength = trees::strength_preset(trees::StrengthPreset::sitka_spruce);
    strength.*member = value;
    try {
      strength.validate();
      return true;
    } catch (const std::invalid_argument&) {
      return false;
    }
  };
  using Strength = trees::TreeStrength;
  const std::pair<const char*, double Strength::*> numbers[] = {
      {"modulus_of_rupture", &Strength::modulus_of_rupture},
      {"knot_factor", &Strength::knot_factor},
      {"green_density", &Strength::green_density},
      {"anchorage", &Strength::anchorage}};
  for (const auto& [name, member] : numbers) {
    INFO("strength." << name);
    const schema::Key& key = strength_key(name);
    REQUIRE(key.at_most < schema::kNoNumberLimit);
    CHECK(valid(member, key.at_most));
    if (key.bound == schema::Bound::positive) {
      CHECK(valid(member, 1e-12 * key.at_most));
      CHECK_FALSE(valid(member, 0.0));
    } else {
      CHECK(key.at_least > 0.0);
      CHECK(valid(member, key.at_least));
    }
  }
  CHECK(strength_key("knot_factor").at_most == schema::kMaxKnotFactor);
  CHECK_FALSE(valid(&Strength::knot_factor, std::nextafter(schema::kMaxKnotFactor, 2.0)));
  // The presets lie within the keys' bounds, so that a preset's values written out load as they are.
  for (const std::string& word : schema::words(strength_key("preset"))) {
    const trees::TreeStrength preset = trees::strength_preset(*trees::parse_strength_preset(word));
    for (const auto& [name, member] : numbers) {
      INFO(word << " strength." << name);
      const schema::Key& key = strength_key(name);
      CHECK(preset.*member >= key.at_least);
      CHECK(preset.*member <= key.at_most);
    }
  }

  // forest.damage: off, and when on, a failed tree falls.
  CHECK_FALSE(key_at("forest.damage.enabled").flag);
  CHECK(key_at("forest.damage.consequences").flag);
  CHECK(schema::child_names("forest.damage") == std::vector<std::string>{"enabled", "consequences"});
}

TEST_CASE("schema: a page whose tables leave a key out, or leave a table open, is refused", "[schema]") {
  const std::string page = "# Scenario files\n<!-- schema: time -->\n<!-- end schema -->\n";
  CHECK_THROWS_WITH(schema::render_scenario_docs(page), Catch::Matchers::Contains("is in no table"));
  std::string open_table = read_text(docs_page());
  const std::string close = "<!-- end schema -->";
  open_table.erase(open_table.rfind(close), close.size());
  CHECK_THROWS_WITH(schema::render_scenario_docs(open_table), Catch::Matchers::Contains("has no " + close));
}

TEST_CASE(
    "schema: every number a scenario gives has bounds past which it cannot be meant, and the docs say why",
    "[schema]") {
  using schema::Type;
  for (const schema::Key* entry : schema::all_keys()) {
    const schema::Key& key = *entry;
    INFO("key " << key.path);
    switch (key.type) {
      case Type::number:
      case Type::number_or_auto:
      case Type::point2:
      case Type::point3:
      case Type::point2_or_3:
      case Type::expression:
      case Type::velocity_or_with_wind:
        CHECK((key.bound != schema::Bound::any || key.at_least > -schema::kNoNumberLimit));
        CHECK((key.at_most < schema::kNoNumberLimit || key.below < schema::kNoNumberLimit));
        CHECK_FALSE(schema::docs(key).bounds_why.empty());
        break;
      case Type::integer:
      case Type::integer_or_word:
        CHECK(key.lowest <= key.highest);
        CHECK_FALSE(schema::docs(key).bounds_why.empty());
        break;
      default:  // words, texts, maps; and seeds, every one of which is meant
        CHECK(schema::docs(key).bounds_why.empty());
    }
  }
  // The docs print each range with its reason.
  const std::string page = schema::render_scenario_docs(read_text(docs_page()));
  CHECK_THAT(page,
             Catch::Matchers::Contains(
                 "| `time.cfl` | number | — | `0.8` | > 0 and <= 5; why: past 5 a run with a fixed `dt`"));
}
