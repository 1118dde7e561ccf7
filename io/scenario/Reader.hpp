// What the scenario loader's section readers (io/scenario/*.cpp) share: a value of the file with the key and
// line to blame (Field), one map of the file read against its keys in the schema (Section), and the Loader
// that reads each scalar as its key in the schema says and throws ScenarioError ("FILE:LINE: KEY: what was
// expected, got VALUE"). Internal to forestwind_io; io/Scenario.hpp and the section structs of io/settings/
// are the public headers.
//
// A reader names its map by its section's table and its schema path, and each key by its name in that map,
// all checked against that table at compile time: a key the schema lacks (a typo, a key not added to the
// table) does not compile, and a reader compiles only the tables it names (io/schema/Key.hpp).
//
//   void read_time(const Loader& loader, const Field& field, TimeSettings& time) {
//     const Section<schema::kTimeKeys, "time"> map(loader, field);   // unknown, duplicate, missing keys
//     time.end = loader.number(map.require<"end">());                // "a number > 0 (s) expected, got '-1'"
//     if (const auto cfl = map.get<"cfl">()) time.cfl = loader.number(*cfl);
//   }
//
// Lists: an item of forest.species is a Section<schema::kSpeciesKeys, "forest.species[]">, whose keys are
// "name", "skeleton", ....
#pragma once

#include <yaml-cpp/yaml.h>

#include <algorithm>
#include <array>
#include <cstddef>
#include <cstdint>
#include <filesystem>
#include <map>
#include <optional>
#include <string>
#include <string_view>
#include <utility>
#include <vector>

#include "io/Expression.hpp"
#include "io/ScenarioSchema.hpp"
#include "io/schema/Key.hpp"

namespace fw::io::reader {

using Vec2 = std::array<double, 2>;
using Vec3 = std::array<double, 3>;
using schema::Bound;
using schema::Key;

/// The key of messages about the file's top-level map.
inline constexpr const char* kTopLevel = "(top level)";

/// A value in the file: the node, its dotted key and the 1-based line to blame.
struct Field {
  YAML::Node node;
  std::string key;
  int line = 1;
};

/// The 1-based line of a node, or `fallback` where the node has none.
int line_of(const YAML::Node& node, int fallback);

/// The ", got ..." part of a message: a scalar's text quoted, a short list of scalars as [a, b], else
/// what kind of node it is.
std::string shown(const YAML::Node& node);

std::string join(const std::vector<std::string>& words, const char* separator);

/// The key of the table a field of the file stands for ("forest.species[0].modes" -> forest.species[].modes).
const Key& key_of(const Field& field);

/// A number with the range and unit of `owner` (the components of a point, say), as the table's number key.
std::string number_expected(const Key& owner);

/// Whether `a` stands before `b` in the file.
bool comes_before(const Field& a, const Field& b);

/// A generic path of the schema as a template argument: Section<kSpeciesKeys, "forest.species[]">,
/// get<"name">().
template <std::size_t N>
struct SchemaPath {
  char text[N]{};
  consteval SchemaPath(const char (&path)[N]) { std::copy_n(path, N, text); }
  constexpr std::string_view view() const { return {text, N - 1}; }
};

class Loader;
template <const auto& Keys, SchemaPath Path>
class Section;

/// The keys of one map, checked against its keys in the schema (unknown and duplicate keys are errors, and
/// so are missing required keys). A null value (`solver:` with nothing after it) counts as an empty map.
/// With a variant (wind.profile's type), keys that apply to another variant are unknown; without one, all
/// are allowed and only the keys of every variant are required. Readers use it through Section, which
/// names the keys at compile time.
class MapFields {
 public:
  /// `parent`: the map's generic path in the schema; the field's key must stand for it.
  MapFields(const Loader& loader, const Field& map, std::string_view parent, const std::string* variant);

  void exactly_one() const;  // see Section::exactly_one

 private:
  template <const auto& Keys, SchemaPath Path>
  friend class Section;

  std::optional<Field> get(const std::string& name) const;
  /// The field, or an error at the map's line: "WHAT expected (required), got nothing", WHAT from the
  /// schema and `reason` (why it is needed here) after it.
  Field require(const std::string& name, const std::string& reason) const;
  /// A key (or a key below one) the file leaves out, blamed on the map's line.
  Field missing(const std::string& name) const;
  std::string path(const std::string& name) const {
    return self_.key.empty() || self_.key == kTopLevel ? name : self_.key + "." + name;
  }

  const Loader& loader_;
  Field self_;
  std::map<std::string, Field> fields_;
  std::vector<std::string> order_;  // names given, in file order
};

/// One map of the file at the schema path Path, whose keys are in the section table Keys, read as MapFields
/// reads it. Its keys are named by their name in the map; get<"cfl">() in a Section<kTimeKeys, "time">
/// compiles only while kTimeKeys has time.cfl.
template <const auto& Keys, SchemaPath Path>
class Section {
  static_assert(schema::holds_keys(Keys, Path.view()), "Section: not a map of this section of the schema");

 public:
  /// `map`: a field whose key stands for Path (std::logic_error otherwise: the reader is wrong, not the
  /// file).
  Section(const Loader& loader, const Field& map, const std::string* variant = nullptr)
      : fields_(loader, map, Path.view(), variant) {}

  /// The key Name of this map, or nullopt when the file leaves it out.
  template <SchemaPath Name>
  std::optional<Field> get() const {
    return fields_.get(name<Name>());
  }
  /// The key Name, or an error at the map's line (see MapFields::require).
  template <SchemaPath Name>
  Field require(const std::string& reason = "") const {
    return fields_.require(name<Name>(), reason);
  }
  /// The key Name (or one below it, "canopy.leaf_area_index") that the file leaves out, blamed on the map's
  /// line: for a message that it is required here.
  template <SchemaPath Name>
  Field missing() const {
    constexpr std::string_view path = schema::key(Keys, Path.view(), Name.view()).path;
    return fields_.missing(std::string(path.substr(path.size() - Name.view().size())));
  }

  /// Fails unless the map holds exactly one key (an obstacle: box, cylinder or sphere; a skeleton source).
  void exactly_one() const { fields_.exactly_one(); }

 private:
  /// Name, as the schema spells it below Path; it must be a key of this very map.
  template <SchemaPath Name>
  static std::string name() {
    static_assert(Name.view().find('.') == std::string_view::npos, "get and require take a key of this map");
    constexpr std::string_view path = schema::key(Keys, Path.view(), Name.view()).path;
    return std::string(path.substr(path.size() - Name.view().size()));
  }

  MapFields fields_;
};

/// Reads the values of one scenario file, each as its key in the schema says, and throws its errors.
class Loader {
 public:
  Loader(std::string file, std::filesystem::path folder)
      : file_(std::move(file)), folder_(std::move(folder)) {}

  /// The scenario file, as its messages name it.
  const std::string& file() const { return file_; }

  [[noreturn]] void fail(const Field& field, const std::string& message) const;
  /// "WHAT expected, got VALUE".
  [[noreturn]] void expected(const Field& field, const std::string& what) const;
  /// "WHAT expected, got VALUE" with WHAT from the field's key in the schema.
  [[noreturn]] void expected(const Field& field) const { expected(field, schema::expected(key_of(field))); }

  Field child(const Field& parent, const YAML::Node& node, const std::string& key) const {
    return Field{node, key, line_of(node, parent.line)};
  }

  // --- scalars, each as its key in the schema says -------------------------------------------------------

  double number(const Field& field) const {
    const Key& key = key_of(field);
    return number(field, key, schema::expected(key));
  }
  /// A number in the key's range, or nullopt for the key's word (auto).
  std::optional<double> number_or_word(const Field& field) const;
  int integer(const Field& field) const;
  std::uint64_t seed(const Field& field) const;
  bool boolean(const Field& field) const;
  std::string text(const Field& field) const;
  /// One of the key's words.
  std::string word(const Field& field) const { return word(field, key_of(field)); }

  template <std::size_t N>
  std::array<double, N> vector(const Field& field) const {
    const Key& key = key_of(field);
    if (!field.node.IsSequence() || field.node.size() != N) expected(field);
    std::array<double, N> values{};
    for (std::size_t i = 0; i < N; ++i) values[i] = component(field, i, key);
    return values;
  }

  /// Item i of a list of numbers, with the range and unit of the list's key.
  double component(const Field& list, std::size_t i, const Key& key) const;

  Expression expression(const Field& field) const;

  /// A path relative to the scenario folder (or absolute) naming a readable regular file.
  std::filesystem::path readable_file(const Field& field) const;

  /// A list (null counts as empty); each item keyed KEY[i].
  std::vector<Field> items(const Field& field) const;

  /// A list of distinct words of the key's vocabulary, in the file's order.
  std::vector<std::string> word_set(const Field& field) const;

  const std::filesystem::path& folder() const { return folder_; }

 private:
  /// A number in the range of `key`: its sign bound and its upper limit.
  double number(const Field& field, const Key& key, const std::string& what) const;
  /// One of the vocabulary of `key` (a word key, or a word_set key for one of its items).
  std::string word(const Field& field, const Key& key) const;

  std::string file_;
  std::filesystem::path folder_;
};

/// The enum value of a word the loader read, from a vocabulary and its values aligned by position.
template <typename Enum, std::size_t N>
Enum value(const std::string_view (&words)[N], const Enum (&values)[N], const std::string& word) {
  return schema::value_of(words, values, word);
}

/// "x", "y" or "z".
std::string axis_name(std::size_t axis);

/// low <= value <= high.
inline bool inside(double value, double low, double high) {
  return value >= low && value <= high;
}

}  // namespace fw::io::reader
