#include "io/ScenarioSchema.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <cmath>
#include <span>
#include <stdexcept>

#include "base/TextNumber.hpp"
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

namespace fw::io::schema {

namespace {

/// A section's table and its prose.
struct SectionTable {
  std::span<const Key> keys;
  std::span<const KeyDocs> (*docs)();
};

/// Every section, in the order of the file's sections: the order of the docs' tables, and of the keys a
/// map's messages list (a map's keys all stand in one table).
constexpr SectionTable kSections[] = {
    {kTopLevelKeys, top_level_docs}, {kTimeKeys, time_docs},       {kDomainKeys, domain_docs},
    {kBoundaryKeys, boundary_docs},  {kWindKeys, wind_docs},       {kEventKeys, event_docs},
    {kObstacleKeys, obstacle_docs},  {kTerrainKeys, terrain_docs}, {kForestKeys, forest_docs},
    {kSpeciesKeys, species_docs},    {kSolverKeys, solver_docs},   {kOutputKeys, output_docs}};

}  // namespace

std::vector<const Key*> all_keys() {
  std::vector<const Key*> out;
  for (const SectionTable& section : kSections)
    for (const Key& entry : section.keys) out.push_back(&entry);
  return out;
}

const Key* find(std::string_view path) {
  for (const SectionTable& section : kSections)
    for (const Key& entry : section.keys)
      if (entry.path == path) return &entry;
  return nullptr;
}

const KeyDocs& docs(const Key& key) {
  for (const SectionTable& section : kSections)
    for (const KeyDocs& entry : section.docs())
      if (entry.path == key.path) return entry;
  throw std::logic_error(fmt::format("scenario schema: key {} has no prose", key.path));
}

std::string generic_path(std::string_view key) {
  std::string out;
  for (std::size_t i = 0; i < key.size(); ++i) {
    out += key[i];
    if (key[i] == '[') {
      while (i + 1 < key.size() && key[i + 1] != ']') ++i;  // drop the index
    }
  }
  return out;
}

std::string item_path(std::string_view path, std::size_t index) {
  std::string key(path);
  const std::size_t brackets = key.find("[]");
  if (brackets == std::string::npos) throw std::logic_error("item_path: " + key + " lies in no list");
  key.insert(brackets + 1, std::to_string(index));
  return key;
}

namespace {

/// The last component of a path ("count" of "forest.species[].modes.count") and what lies above it.
std::string_view name_of(std::string_view path) {
  const std::size_t dot = path.rfind('.');
  return dot == std::string_view::npos ? path : path.substr(dot + 1);
}

bool below(std::string_view path, std::string_view parent) {
  if (parent.empty()) return path.find_first_of(".[") == std::string_view::npos;
  return path.size() > parent.size() + 1 && path.starts_with(parent) && path[parent.size()] == '.' &&
         path.substr(parent.size() + 1).find('.') == std::string_view::npos;
}

std::string join(const std::vector<std::string>& words, std::string_view separator,
                 std::string_view quote = "") {
  std::string out;
  for (std::size_t i = 0; i < words.size(); ++i)
    out += fmt::format("{}{}{}{}", i ? separator : "", quote, words[i], quote);
  return out;
}

std::string unit_suffix(const Key& key) {
  return key.unit.empty() ? "" : fmt::format(" ({})", key.unit);
}

std::string sign_text(Bound bound) {
  return bound == Bound::positive ? "> 0" : bound == Bound::non_negative ? ">= 0" : "";
}

}  // namespace

std::string number_text(double value) {
  constexpr double kPlainBelow = 1e5, kPlainFrom = 1e-2;  // 12000, 0.05; but 1e10 and 1e-3
  constexpr double kWholeBelow = 1e15;                    // printed exactly by {:.0f}
  const double size = std::abs(value);
  if (value == 0.0 || (size < kPlainBelow && size >= kPlainFrom)) return fmt::format("{}", value);
  std::string text;
  for (int digits = 0; digits <= std::numeric_limits<double>::max_digits10; ++digits) {
    text = fmt::format("{:.{}e}", value, digits);
    if (base::parse_number<double>(text) == value) break;
  }
  const std::size_t e = text.find('e');
  std::string exponent = text.substr(e + 1);
  const bool negative = exponent.front() == '-';
  exponent.erase(0, exponent.find_first_not_of("+-0"));
  text = text.substr(0, e + 1) + (negative ? "-" : "") + exponent;
  const std::string whole = fmt::format("{:.0f}", value);
  return value == std::round(value) && size < kWholeBelow && whole.size() < text.size() ? whole : text;
}

namespace {

/// The range a number (or each number of a point) must lie in: "> 0", ">= 0 and < 1", "<= 90", or "" for
/// any number.
std::string range_text(const Key& key) {
  std::vector<std::string> parts;
  if (key.bound != Bound::any) parts.push_back(sign_text(key.bound));
  if (key.at_least > -kNoNumberLimit) parts.push_back(">= " + number_text(key.at_least));
  if (key.at_most < kNoNumberLimit) parts.push_back("<= " + number_text(key.at_most));
  if (key.below < kNoNumberLimit) parts.push_back("< " + number_text(key.below));
  return join(parts, " and ");
}

/// The docs' constraint with its {0}, {1}, {2} replaced by their limits as number_text writes them
/// (2147483647, 1e9, 1e-6).
std::string constraint_text(const KeyDocs& prose) {
  std::array<std::string, 3> limits;
  for (std::size_t i = 0; i < limits.size(); ++i) limits[i] = number_text(prose.limits[i]);
  return fmt::format(fmt::runtime(prose.constraint), limits[0], limits[1], limits[2]);
}

/// "[x, y]", "[x, y, z]".
std::string point_names(int count) {
  return count == 2 ? "[x, y]" : "[x, y, z]";
}

int point_size(Type type) {
  return type == Type::point2 ? 2 : 3;
}

/// The generic path of the list whose items a key of a list item belongs to ("events" for "events[].gust").
std::string_view parent_of(std::string_view path) {
  const std::size_t dot = path.rfind('.');
  if (dot == std::string_view::npos) return {};
  std::string_view parent = path.substr(0, dot);
  if (parent.ends_with("[]")) parent.remove_suffix(2);
  return parent;
}

}  // namespace

std::vector<const Key*> children(std::string_view parent) {
  std::vector<const Key*> out;
  for (const SectionTable& section : kSections)
    for (const Key& entry : section.keys)
      if (below(entry.path, parent)) out.push_back(&entry);
  return out;
}

std::vector<std::string> child_names(std::string_view parent) {
  std::vector<std::string> out;
  for (const Key* child : children(parent)) out.emplace_back(name_of(child->path));
  return out;
}

std::vector<std::string> words(const Key& key) {
  if (key.run_time_words) return key.run_time_words();
  return {key.words.begin(), key.words.end()};
}

std::string expected(const Key& key) {
  switch (key.type) {
    case Type::map:
      return fmt::format("a map {{{}}}", join(child_names(key.path), ", "));
    case Type::choice:
      return "a map with exactly one of the keys " + join(child_names(key.path), ", ");
    case Type::list:
    case Type::choice_list:
    case Type::text:
      return std::string(key.noun);
    case Type::file:
      return key.noun.empty() ? "a file path" : std::string(key.noun);
    case Type::directory:
      return key.noun.empty() ? "a directory path" : std::string(key.noun);
    case Type::number: {
      const std::string range = range_text(key);
      return "a number" + (range.empty() ? "" : " " + range) + unit_suffix(key);
    }
    case Type::number_or_auto: {
      const std::string range = range_text(key);
      return "a number" + (range.empty() ? "" : " " + range) + unit_suffix(key) + " or auto";
    }
    case Type::integer:
      return fmt::format("an integer {}..{}", key.lowest, key.highest);
    case Type::integer_or_word:
      return fmt::format(
          "one of {} or {}", join(words(key), " | "),
          expected(
              Key{.path = key.path, .type = Type::integer, .lowest = key.lowest, .highest = key.highest}));
    case Type::seed:
      return fmt::format("an integer 0..{}", std::numeric_limits<std::uint64_t>::max());
    case Type::boolean:
      return "true or false";
    case Type::word:
      return "one of " + join(words(key), " | ");
    case Type::word_set:
      return "a list of " + join(words(key), ", ");
    case Type::point2:
    case Type::point3: {
      const int size = point_size(key.type);
      const std::string range = range_text(key);
      return fmt::format("a list of {} numbers {}{}{}", size, key.noun.empty() ? point_names(size) : key.noun,
                         range.empty() ? "" : ", each " + range, unit_suffix(key));
    }
    case Type::point2_or_3:
      return "a list [x, y] or [x, y, z]" + unit_suffix(key);
    case Type::expression:
      return "a number or a muparser expression of t" + unit_suffix(key);
    case Type::velocity_or_with_wind:
      return "with_wind or a list of 3 numbers [vx, vy, vz]" + unit_suffix(key);
  }
  return "?";
}

// --- docs
// ----------------------------------------------------------------------------------------------------

namespace {

std::string doc_type(const Key& key) {
  switch (key.type) {
    case Type::map:
    case Type::choice:
      return "map";
    case Type::list:
    case Type::choice_list:
      return "list";
    case Type::text:
      return "string";
    case Type::file:
      return "file path";
    case Type::directory:
      return "path";
    case Type::number:
      return "number";
    case Type::number_or_auto:
      return "number or `auto`";
    case Type::integer:
    case Type::seed:
      return "integer";
    case Type::integer_or_word:
      return "word or integer";
    case Type::boolean:
      return "boolean";
    case Type::word:
      return "word";
    case Type::word_set:
      return "list of words";
    case Type::point2:
    case Type::point3:
      return fmt::format("list of {} numbers `{}`", point_size(key.type),
                         key.noun.empty() ? point_names(point_size(key.type)) : std::string(key.noun));
    case Type::point2_or_3:
      return "list `[x, y]` or `[x, y, z]`";
    case Type::expression:
      return "number or expression of `t`";
    case Type::velocity_or_with_wind:
      return "`with_wind` or list of 3 numbers `[vx, vy, vz]`";
  }
  return "?";
}

std::string doc_default(const Key& key) {
  if (const std::string_view note = docs(key).default_note; !note.empty()) return std::string(note);
  if (key.required)
    return key.only_with.empty() ? "required" : fmt::format("required for `{}`", key.only_with);
  const Key* parent = find(parent_of(key.path));
  if (parent && (parent->type == Type::choice || parent->type == Type::choice_list)) return "—";
  switch (key.type) {
    case Type::map:
    case Type::choice:
      return "all defaults below";
    case Type::list:
    case Type::choice_list:
      return "`[]` (none)";
    case Type::number:
    case Type::integer:
      return fmt::format("`{}`", number_text(key.number));
    case Type::point3: {
      if (!key.components.empty()) {
        std::vector<std::string> components;
        for (const double component : key.components) components.push_back(number_text(component));
        return fmt::format("`[{}]`", join(components, ", "));
      }
      const std::string component = number_text(key.number);
      return fmt::format("`[{0}, {0}, {0}]`", component);
    }
    case Type::boolean:
      return key.flag ? "`true`" : "`false`";
    case Type::word:
    case Type::number_or_auto:
    case Type::integer_or_word:
    case Type::velocity_or_with_wind:
    case Type::directory:
      return fmt::format("`{}`", key.word);
    case Type::word_set:
      return fmt::format("`[{}]`", join({key.chosen.begin(), key.chosen.end()}, ", "));
    case Type::seed:
      return "`0`";
    default:
      return "—";
  }
}

std::string doc_allowed(const Key& key) {
  const KeyDocs& prose = docs(key);
  if (!prose.allowed.empty()) return std::string(prose.allowed);
  std::string allowed;
  switch (key.type) {
    case Type::map:
      allowed = "keys " + join(child_names(key.path), ", ", "`");
      break;
    case Type::choice:
      allowed = "exactly one of " + join(child_names(key.path), ", ", "`");
      break;
    case Type::list:
      allowed = "maps with keys " + join(child_names(std::string(key.path) + "[]"), ", ", "`");
      break;
    case Type::choice_list: {
      std::vector<std::string> items;
      for (const std::string& name : child_names(std::string(key.path) + "[]"))
        items.push_back(fmt::format("`- {}: {{...}}`", name));
      allowed = "items " + join(items, ", ");
      break;
    }
    case Type::text:
    case Type::directory:
      allowed = "non-empty";
      break;
    case Type::file:
      allowed = "a readable file; relative to the scenario's folder";
      break;
    case Type::number:
      allowed = range_text(key).empty() ? "any" : range_text(key);
      break;
    case Type::number_or_auto:
      allowed = range_text(key) + ", or the word `auto`";
      break;
    case Type::integer:
      allowed = fmt::format("{}..{}", key.lowest, key.highest);
      break;
    case Type::integer_or_word:
      allowed =
          fmt::format("{}, or an integer {}..{}", join(words(key), " \\| ", "`"), key.lowest, key.highest);
      break;
    case Type::seed:
      allowed = fmt::format("0..{}", std::numeric_limits<std::uint64_t>::max());
      break;
    case Type::boolean:
      allowed = "`true` \\| `false`";
      break;
    case Type::word:
      allowed = join(words(key), " \\| ", "`");
      break;
    case Type::word_set:
      allowed = "each of " + join(words(key), ", ", "`") + " at most once; file order is kept";
      break;
    case Type::point2:
    case Type::point3:
    case Type::point2_or_3:
      allowed = range_text(key).empty() ? "any" : "each " + range_text(key);
      break;
    case Type::expression:
      allowed = fmt::format("finite{} for 0 <= t <= `time.end`",
                            range_text(key).empty() ? "" : ", " + range_text(key));
      break;
    case Type::velocity_or_with_wind:
      allowed = "the word `with_wind` or 3 numbers, each " + range_text(key);
      break;
  }
  if (!prose.constraint.empty()) allowed += "; " + constraint_text(prose);
  if (!prose.bounds_why.empty()) allowed += fmt::format("; why: {}", prose.bounds_why);
  if (!key.only_with.empty()) allowed += fmt::format("; `{}` only", key.only_with);
  return allowed;
}

std::string table(const std::vector<const Key*>& keys) {
  std::string out =
      "| key | type | unit | default | allowed | meaning |\n"
      "|---|---|---|---|---|---|\n";
  for (const Key* key : keys) {
    out += fmt::format("| `{}` | {} | {} | {} | {} | {} |\n", key->path, doc_type(*key),
                       key->unit.empty() ? "—" : key->unit, doc_default(*key), doc_allowed(*key),
                       docs(*key).description);
  }
  return out;
}

constexpr std::string_view kTopLevelSection = "(top level)";
constexpr std::string_view kOpenMarker = "<!-- schema: ";
constexpr std::string_view kMarkerEnd = " -->";
constexpr std::string_view kCloseMarker = "<!-- end schema -->";

/// How well a section takes a key: the length of the section when the key equals it or lies below it, 0 for
/// the top level's own keys, -1 otherwise.
long claim(std::string_view section, std::string_view path) {
  if (section == kTopLevelSection) return path.find_first_of(".[") == std::string_view::npos ? 0 : -1;
  const bool takes = path == section || (path.starts_with(section) &&
                                         (path[section.size()] == '.' || path[section.size()] == '['));
  return takes ? long(section.size()) : -1;
}

}  // namespace

std::string render_scenario_docs(std::string_view page) {
  // First the sections named by the markers, so that each key goes to the most specific one.
  std::vector<std::string> sections;
  for (std::size_t at = page.find(kOpenMarker); at != std::string_view::npos;
       at = page.find(kOpenMarker, at + 1)) {
    const std::size_t name = at + kOpenMarker.size();
    const std::size_t end = page.find(kMarkerEnd, name);
    if (end == std::string_view::npos)
      throw std::invalid_argument("scenario docs: a schema marker is not closed");
    sections.emplace_back(page.substr(name, end - name));
  }
  std::vector<std::vector<const Key*>> taken(sections.size());
  for (const Key* key : all_keys()) {
    long best = -1;
    std::size_t best_section = 0;
    for (std::size_t s = 0; s < sections.size(); ++s) {
      const long score = claim(sections[s], key->path);
      if (score > best) best = score, best_section = s;
    }
    if (best < 0)
      throw std::invalid_argument(
          fmt::format("scenario docs: key {} is in no table (add a <!-- schema: ... --> block)", key->path));
    taken[best_section].push_back(key);
  }

  std::string out;
  std::size_t copied = 0;
  for (std::size_t s = 0; s < sections.size(); ++s) {
    if (taken[s].empty())
      throw std::invalid_argument(fmt::format("scenario docs: section {} has no keys", sections[s]));
    const std::size_t open = page.find(kOpenMarker, copied);
    const std::size_t open_end = page.find('\n', open);
    const std::size_t close = page.find(kCloseMarker, open_end);
    if (open_end == std::string_view::npos || close == std::string_view::npos)
      throw std::invalid_argument(
          fmt::format("scenario docs: section {} has no {}", sections[s], kCloseMarker));
    out += page.substr(copied, open_end + 1 - copied);
    out += table(taken[s]);
    copied = close;
  }
  out += page.substr(copied);
  return out;
}

}  // namespace fw::io::schema
