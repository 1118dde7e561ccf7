#include "io/scenario/Reader.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <cerrno>
#include <cmath>
#include <cstring>
#include <fstream>
#include <stdexcept>

#include "base/TextNumber.hpp"
#include "io/ScenarioError.hpp"

namespace fw::io::reader {

namespace {

/// A scalar for an error message: control bytes escaped, long texts cut.
std::string printable(const std::string& text) {
  std::string out;
  for (unsigned char c : text) {
    if (out.size() >= 80) {
      out += "...";
      break;
    }
    if (c < 0x20 || c == 0x7f)
      out += fmt::format("\\x{:02x}", c);
    else
      out += char(c);
  }
  return out;
}

bool applies(const Key& key, const std::string* variant) {
  return !variant || key.only_with.empty() || key.only_with == *variant;
}

}  // namespace

int line_of(const YAML::Node& node, int fallback) {
  const YAML::Mark mark = node.Mark();
  return mark.is_null() || mark.line < 0 ? fallback : mark.line + 1;
}

std::string shown(const YAML::Node& node) {
  switch (node.Type()) {
    case YAML::NodeType::Scalar:
      return fmt::format("'{}'", printable(node.Scalar()));  // not "'" + ...: GCC 12's -Wrestrict misfires
    case YAML::NodeType::Sequence: {
      std::string items;
      for (std::size_t i = 0; i < node.size(); ++i) {
        if (!node[i].IsScalar() || i >= 8) return "a list";
        items += (i ? ", " : "") + printable(node[i].Scalar());
      }
      return "'[" + items + "]'";
    }
    case YAML::NodeType::Map:
      return "a map";
    default:
      return "nothing";
  }
}

std::string join(const std::vector<std::string>& words, const char* separator) {
  std::string out;
  for (std::size_t i = 0; i < words.size(); ++i) out += (i ? separator : "") + words[i];
  return out;
}

const Key& key_of(const Field& field) {
  const std::string path = schema::generic_path(field.key);
  const Key* key = schema::find(path);
  if (!key) throw std::logic_error("Scenario: the loader reads " + path + ", which the schema lacks");
  return *key;
}

std::string number_expected(const Key& owner) {
  return schema::expected(Key{.path = owner.path,
                              .type = schema::Type::number,
                              .unit = owner.unit,
                              .bound = owner.bound,
                              .at_least = owner.at_least,
                              .at_most = owner.at_most,
                              .below = owner.below});
}

// --- MapFields ---------------------------------------------------------------------------------------------

MapFields::MapFields(const Loader& loader, const Field& map, std::string_view parent,
                     const std::string* variant)
    : loader_(loader), self_(map) {
  if (schema::generic_path(map.key) != parent)
    throw std::logic_error(fmt::format("Scenario: the reader of {} was given {}", parent, map.key));
  std::vector<std::string> allowed;
  for (const Key* key : schema::children(parent))
    if (applies(*key, variant)) allowed.emplace_back(key->path.substr(key->path.rfind('.') + 1));
  if (!map.node.IsNull()) {
    if (!map.node.IsMap()) loader.expected(map, "a map with the keys " + join(allowed, ", "));
    for (auto it = map.node.begin(); it != map.node.end(); ++it) {
      const YAML::Node key = it->first;
      const int key_line = line_of(key, map.line);
      if (!key.IsScalar())
        loader.fail(Field{key, map.key, key_line}, "a key name expected, got " + shown(key));
      const std::string& name = key.Scalar();
      const Field key_field{key, path(name), key_line};
      if (std::find(allowed.begin(), allowed.end(), name) == allowed.end())
        loader.expected(key_field, "one of the keys " + join(allowed, ", "));
      if (const auto first = fields_.find(name); first != fields_.end())
        loader.fail(key_field, fmt::format("each key once expected, got '{}' again (first on line {})", name,
                                           first->second.line));
      fields_.emplace(name, Field{it->second, path(name), line_of(it->second, key_line)});
      order_.push_back(name);
    }
  }
  // A key required only by some variant is checked once the variant is known.
  for (const Key* key : schema::children(parent)) {
    const bool every_variant = key->only_with.empty();
    if (key->required && (variant ? applies(*key, variant) : every_variant))
      require(std::string(key->path.substr(key->path.rfind('.') + 1)), "");
  }
}

std::optional<Field> MapFields::get(const std::string& name) const {
  const auto found = fields_.find(name);
  if (found == fields_.end()) return std::nullopt;
  return found->second;
}

Field MapFields::require(const std::string& name, const std::string& reason) const {
  if (auto field = get(name)) return *field;
  const Field absent = missing(name);
  const std::string what = schema::expected(key_of(absent)) + (reason.empty() ? "" : ", " + reason);
  loader_.fail(absent, what + " expected (required), got nothing");
}

Field MapFields::missing(const std::string& name) const {
  return Field{YAML::Node(YAML::NodeType::Null), path(name), self_.line};
}

void MapFields::exactly_one() const {
  if (fields_.size() == 1) return;
  loader_.fail(self_, fmt::format("a map with exactly one of the keys {} expected, got {}",
                                  join(schema::child_names(schema::generic_path(self_.key)), ", "),
                                  fields_.empty() ? std::string("none") : join(order_, " and ")));
}

// --- Loader ------------------------------------------------------------------------------------------------

void Loader::fail(const Field& field, const std::string& message) const {
  throw ScenarioError(file_, field.line, field.key.empty() ? kTopLevel : field.key, message);
}

void Loader::expected(const Field& field, const std::string& what) const {
  fail(field, what + " expected, got " + shown(field.node));
}

std::optional<double> Loader::number_or_word(const Field& field) const {
  const Key& key = key_of(field);
  if (field.node.IsScalar() && field.node.Scalar() == key.word) return std::nullopt;
  return number(field, key, schema::expected(key));
}

int Loader::integer(const Field& field) const {
  const Key& key = key_of(field);
  if (!field.node.IsScalar()) expected(field);
  const auto value = base::parse_number<long long>(field.node.Scalar());
  if (!value || *value < key.lowest || *value > key.highest) expected(field);
  return int(*value);
}

std::uint64_t Loader::seed(const Field& field) const {
  if (!field.node.IsScalar()) expected(field);
  const auto value = base::parse_number<std::uint64_t>(field.node.Scalar());
  if (!value) expected(field);
  return *value;
}

bool Loader::boolean(const Field& field) const {
  if (field.node.IsScalar()) {
    const std::string& text = field.node.Scalar();
    if (text == "true" || text == "True" || text == "TRUE") return true;
    if (text == "false" || text == "False" || text == "FALSE") return false;
  }
  expected(field);
}

std::string Loader::text(const Field& field) const {
  if (!field.node.IsScalar() || field.node.Scalar().empty()) expected(field);
  return field.node.Scalar();
}

double Loader::component(const Field& list, std::size_t i, const Key& key) const {
  return number(child(list, list.node[i], fmt::format("{}[{}]", list.key, i)), key, number_expected(key));
}

Expression Loader::expression(const Field& field) const {
  const std::string what = schema::expected(key_of(field));
  if (!field.node.IsScalar() || field.node.Scalar().empty()) expected(field, what);
  try {
    return Expression::parse(field.node.Scalar());
  } catch (const std::invalid_argument& error) {
    // Expression's message repeats the text, which the "got" part shows already.
    std::string detail = error.what();
    const std::string prefix = "expression \"" + field.node.Scalar() + "\": ";
    if (detail.starts_with(prefix)) detail.erase(0, prefix.size());
    expected(field, what + " (" + detail + ")");
  }
}

std::filesystem::path Loader::readable_file(const Field& field) const {
  const std::string written = text(field);
  std::filesystem::path path = written;
  if (path.is_relative()) path = (folder_ / path).lexically_normal();
  std::error_code error;
  const bool regular = std::filesystem::is_regular_file(path, error);
  std::ifstream probe;
  if (regular) probe.open(path, std::ios::binary);
  if (!regular || !probe) {
    const std::string reason = !std::filesystem::exists(path, error) ? "no such file"
                               : !regular                            ? "not a regular file"
                                                                     : std::strerror(errno);
    expected(field, fmt::format("a readable file ({}: {})", path.string(), reason));
  }
  return path;
}

std::vector<Field> Loader::items(const Field& field) const {
  std::vector<Field> out;
  if (field.node.IsNull()) return out;
  if (!field.node.IsSequence()) expected(field);
  for (std::size_t i = 0; i < field.node.size(); ++i)
    out.push_back(child(field, field.node[i], fmt::format("{}[{}]", field.key, i)));
  return out;
}

std::vector<std::string> Loader::word_set(const Field& field) const {
  const Key& key = key_of(field);
  const std::vector<std::string> vocabulary = schema::words(key);
  std::vector<std::string> chosen;
  for (const Field& item : items(field)) {
    const std::string choice = word(item, key);
    if (std::find(chosen.begin(), chosen.end(), choice) != chosen.end())
      expected(item, "each of " + join(vocabulary, ", ") + " at most once");
    chosen.push_back(choice);
  }
  return chosen;
}

double Loader::number(const Field& field, const Key& key, const std::string& what) const {
  if (!field.node.IsScalar()) expected(field, what);
  const std::optional<double> value = base::parse_finite(field.node.Scalar());
  if (!value || (key.bound == Bound::positive && !(*value > 0.0)) ||
      (key.bound == Bound::non_negative && !(*value >= 0.0)) || !(*value >= key.at_least) ||
      !(*value <= key.at_most) || !(*value < key.below))
    expected(field, what);
  return *value;
}

std::string Loader::word(const Field& field, const Key& key) const {
  const std::vector<std::string> vocabulary = schema::words(key);
  if (field.node.IsScalar()) {
    const auto found = std::find(vocabulary.begin(), vocabulary.end(), field.node.Scalar());
    if (found != vocabulary.end()) return *found;
  }
  expected(field, "one of " + join(vocabulary, " | "));
}

// --- shared by several sections ----------------------------------------------------------------------------

bool comes_before(const Field& a, const Field& b) {
  return a.node.Mark().pos < b.node.Mark().pos;
}

std::string axis_name(std::size_t axis) {
  return std::string(1, "xyz"[axis]);
}

}  // namespace fw::io::reader
