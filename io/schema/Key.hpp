// One key of the scenario schema, and the compile-time look-ups over a section's table of them. Each section
// of a scenario file has its table in a header of its own beside this one (io/schema/TimeKeys.hpp,
// WindKeys.hpp, ...), so that a file that reads one section compiles that section's keys only; the prose the
// docs print for each key (KeyDocs) is in the .cpp beside that header. io/ScenarioSchema.hpp looks keys up
// over every section at run time.
//
//   #include "io/schema/TimeKeys.hpp"
//   constexpr double cfl = fw::io::schema::key(fw::io::schema::kTimeKeys, "time.cfl").number;   // 0.8
//   fw::io::schema::key(fw::io::schema::kTimeKeys, "time", "cfl");   // the same key, below its map
//
// A table holds the keys below its section's path ("time.end", "time.dt", ...); the key that names the
// section's map ("time") is a key of the map that holds it, the top level's (io/schema/TopLevelKeys.hpp). So
// does every map: "wind.turbulence" is a wind key, "forest.species" a forest key, and the keys of its items
// ("forest.species[].name") are the species section's.
#pragma once

#include <array>
#include <cstddef>
#include <limits>
#include <span>
#include <string>
#include <string_view>
#include <vector>

namespace fw::io::schema {

/// What a key holds. The loader reads each type with one function, and the docs' type column names it.
enum class Type {
  map,                    ///< a map of the keys below it
  choice,                 ///< a map with exactly one of the keys below it
  list,                   ///< a list of maps of the keys below PATH[]
  choice_list,            ///< a list of maps, each with exactly one of the keys below PATH[]
  text,                   ///< a non-empty string
  file,                   ///< a readable file, relative to the scenario's folder
  directory,              ///< a folder, relative to the working directory
  number,                 ///< a finite decimal number
  number_or_auto,         ///< a number, or the word auto (no number)
  integer,                ///< a whole number within [lowest, highest]
  integer_or_word,        ///< a whole number within [lowest, highest], or one of words
  seed,                   ///< an unsigned 64-bit integer
  boolean,                ///< true or false
  word,                   ///< one of words
  word_set,               ///< a list of distinct words of words
  point2,                 ///< [x, y]
  point3,                 ///< [x, y, z]
  point2_or_3,            ///< [x, y] or [x, y, z]
  expression,             ///< a number or a muparser expression of t
  velocity_or_with_wind,  ///< [vx, vy, vz], or the word with_wind
};

/// The sign a number (or each number of a point, or each value of an expression) must have.
enum class Bound { any, positive, non_negative };

using Words = std::span<const std::string_view>;

inline constexpr double kNoNumberLimit = std::numeric_limits<double>::infinity();

/// What the loader and the defaults of the io::Scenario structs read of a key. What only the docs print is
/// its KeyDocs.
struct Key {
  std::string_view path{};
  Type type = Type::map;
  std::string_view unit{};  ///< SI unit; empty when dimensionless or not a quantity
  bool required = false;
  Bound bound = Bound::any;
  double at_least = -kNoNumberLimit;  ///< number, point: each value must be >= this
  double at_most = kNoNumberLimit;    ///< number, point: each value must be <= this
  double below = kNoNumberLimit;      ///< number, point: each value must be < this
  long long lowest = 0;               ///< integer: the smallest value allowed
  long long highest = 0;              ///< integer: the largest value allowed
  Words words{};                      ///< word, word_set: the vocabulary
  /// word: a vocabulary known only at run time (replaces words).
  std::vector<std::string> (*run_time_words)() = nullptr;
  double number = 0.0;                   ///< default of number, integer (and of every component of point3)
  std::span<const double> components{};  ///< default of point3 per component, where they differ (not number)
  bool flag = false;                     ///< default of boolean
  /// default of word, number_or_auto, integer_or_word, velocity_or_with_wind, directory
  std::string_view word{};
  Words chosen{};  ///< default of word_set
  /// text, file, directory, list: what the value is, in messages; point2, point3: its components' names
  /// ("[x, y, z]" when empty)
  std::string_view noun{};
  std::string_view only_with{};  ///< the key applies only where its sibling `type` is this word
};

/// What docs/scenario.md prints of a key beyond what its Key says: one row of its table. Each section's
/// prose is in the .cpp beside its table (io/schema/TimeKeys.cpp, ...).
struct KeyDocs {
  std::string_view path{};          ///< the Key's
  std::string_view default_note{};  ///< the default in words, where it is not a plain value
  std::string_view allowed{};       ///< replaces the allowed values derived from the type
  /// what is allowed beyond the type's own rule; {0}, {1}, {2} stand for the numbers in `limits`
  std::string_view constraint{};
  std::array<double, 3> limits{};  ///< the numbers `constraint` names, taken from the type that checks them
  /// Why a value past the key's bounds cannot be meant (io/schema/BoundReasons.hpp): every number's key has
  /// bounds (io/schema/Bounds.hpp), and the docs print them with this.
  std::string_view bounds_why{};
  std::string_view description{};  ///< the meaning
};

/// The word of `value` in a vocabulary and its values, aligned by position (a default owned elsewhere).
template <typename Enum, std::size_t N>
constexpr std::string_view word_of(const std::string_view (&words)[N], const Enum (&values)[N], Enum value) {
  for (std::size_t i = 0; i < N; ++i)
    if (values[i] == value) return words[i];
  throw "not a value of the vocabulary";
}

/// The value of `word` (a key's default word, say) in a vocabulary and its values, aligned by position.
template <typename Enum, std::size_t N>
constexpr Enum value_of(const std::string_view (&words)[N], const Enum (&values)[N], std::string_view word) {
  for (std::size_t i = 0; i < N; ++i)
    if (words[i] == word) return values[i];
  throw "not a word of the vocabulary";
}

/// A vocabulary as strings (the defaults of the io::Scenario structs).
inline std::vector<std::string> strings(Words words) {
  return {words.begin(), words.end()};
}

// --- look-ups in one section's table -----------------------------------------------------------------------

/// The key at a generic path in `keys`, at compile time: a path not in the table does not compile.
consteval const Key& key(std::span<const Key> keys, std::string_view path) {
  for (const Key& entry : keys)
    if (entry.path == path) return entry;
  throw "not a key of this section of the scenario schema";
}

/// The key `name` below the map at generic path `parent` ("" for the top level) in `keys`, or nullptr;
/// `name` may reach further down ("canopy.leaf_area_index"). Usable at compile time.
constexpr const Key* find(std::span<const Key> keys, std::string_view parent, std::string_view name) {
  for (const Key& entry : keys) {
    const std::string_view path = entry.path;
    if (parent.empty() ? path == name
                       : path.size() == parent.size() + 1 + name.size() && path.starts_with(parent) &&
                             path[parent.size()] == '.' && path.ends_with(name))
      return &entry;
  }
  return nullptr;
}

/// The key `name` below the map at `parent` in `keys`, at compile time: a name the map lacks does not
/// compile. The loader's readers name their keys so (io/scenario/Reader.hpp).
///   schema::key(kSpeciesKeys, "forest.species[]", "modes")   // the key forest.species[].modes
consteval const Key& key(std::span<const Key> keys, std::string_view parent, std::string_view name) {
  if (const Key* found = find(keys, parent, name)) return *found;
  throw "not a key of this map in this section of the scenario schema";
}

/// Whether `keys` holds keys of the map at generic path `parent`: the top level (""), a map or choice key,
/// or the items of a list ("forest.species[]"). Not a key of the map itself, which its own parent's table
/// holds.
consteval bool holds_keys(std::span<const Key> keys, std::string_view parent) {
  for (const Key& entry : keys) {
    const std::string_view path = entry.path;
    if (parent.empty()
            ? path.find_first_of(".[") == std::string_view::npos
            : path.size() > parent.size() + 1 && path.starts_with(parent) && path[parent.size()] == '.' &&
                  path.substr(parent.size() + 1).find_first_of(".[") == std::string_view::npos)
      return true;
  }
  return false;
}

}  // namespace fw::io::schema
