// The scenario schema at run time: every key a scenario file may hold, over all its sections, with its type,
// unit, default, allowed values and meaning, each defined once (issue 9, "The schema in one place"). Each
// section's keys are a constexpr table in a header of their own (io/schema/TimeKeys.hpp, WindKeys.hpp, ...;
// io/schema/Key.hpp says how they are laid out), and each key's prose in the .cpp beside it, so that a file
// that reads one section compiles that section's keys and nothing of the others or of the docs. The loader
// (io/scenario/) takes from here its unknown-key checks, its required keys and the "... expected" part of its
// messages; the defaults of the io::Scenario structs are read from the section tables at compile time; and
// the key tables of docs/scenario.md are generated from here (render_scenario_docs;
// tests/io/ScenarioSchema_test.cpp fails when the committed page differs).
//
//   const fw::io::schema::Key* found = fw::io::schema::find("forest.species[].modes.count");
//   fw::io::schema::expected(*found);                                   // "an integer >= 1"
//   fw::io::schema::child_names("wind.profile");                        // type, alpha, roughness_length, ...
//   fw::io::schema::docs(*found).description;                           // what docs/scenario.md says of it
//
// Paths are dotted, with "[]" for the items of a list: "forest.species[].canopy.leaf_area_index". A file's
// key "forest.species[2].modes" is generic_path'd to "forest.species[].modes" before a lookup. Defaults that
// belong to another part of the program (the pressure tolerance of fluid::PressureSettings, the wood of
// trees::kDefaultWood, the drag coefficients of trees::WindBasisSettings, the modal defaults of
// trees::ModalSettings, the leaves of trees::LeafSettings) are taken from there, so that each value is
// written once. So are the limits: a number's upper limit (at_most, below) and the numbers a constraint
// names (KeyDocs::limits) come from the type that checks them again at run time
// (trees::LeafSettings::kMaxFraction, fluid::GridSpec::kMaxFaces, ...), and the loader, its messages and the
// docs all read them from there.
#pragma once

#include <cstddef>
#include <string>
#include <string_view>
#include <vector>

#include "io/schema/Key.hpp"

namespace fw::io::schema {

/// Every key of every section, in table order: the top level's, then each section's in the order of the
/// file's sections (the order of the docs and of the loader's messages).
std::vector<const Key*> all_keys();

/// The key at a generic path, or nullptr.
const Key* find(std::string_view path);

/// A file's dotted key with its list indices dropped: "forest.species[2].modes" -> "forest.species[].modes".
std::string generic_path(std::string_view key);
/// A generic path's key in item `index` of its (first) list: ("forest.stands[].spacing", 2) ->
/// "forest.stands[2].spacing". Where messages past the loader name a key of the file.
std::string item_path(std::string_view path, std::size_t index);

/// The keys directly below a map's generic path ("" for the top level, "events[]" for an event), in table
/// order.
std::vector<const Key*> children(std::string_view parent);
std::vector<std::string> child_names(std::string_view parent);

/// What the docs print of a key: its KeyDocs, from its section's prose.
const KeyDocs& docs(const Key& key);

/// The vocabulary of a word or word_set key.
std::vector<std::string> words(const Key& key);

/// The "... expected" part of the loader's messages for a value of this key, e.g. "a number > 0 (s)".
std::string expected(const Key& key);

/// A number as the docs and the messages write it: plain in the range people read at a glance (0.05,
/// 12000), else the shorter of the shortest scientific form with a plain exponent (1e9, 3.85e9, 1e-3) and
/// the whole number in full (2147483647).
std::string number_text(double value);

/// docs/scenario.md with each block between a line "<!-- schema: SECTION -->" and the next line
/// "<!-- end schema -->" replaced by the key table of SECTION: a generic path ("time", "forest.species[]") or
/// "(top level)". A key goes to the longest SECTION it equals or lies below ("forest.species[].name" to
/// "forest.species[]", "forest.species" to "forest"); "(top level)" takes the top-level keys no other SECTION
/// takes. Throws std::invalid_argument for a marker left open, a SECTION without keys, or a key of the table
/// that no SECTION takes (so every key is documented).
std::string render_scenario_docs(std::string_view page);

}  // namespace fw::io::schema
