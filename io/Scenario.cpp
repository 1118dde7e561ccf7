#include "io/Scenario.hpp"

#include <fmt/format.h>
#include <yaml-cpp/yaml.h>

#include <algorithm>
#include <cerrno>
#include <charconv>
#include <cmath>
#include <cstring>
#include <fstream>
#include <iterator>
#include <limits>
#include <map>
#include <numbers>
#include <sstream>
#include <utility>

#include "fluid/SubgridStress.hpp"
#include "fluid/TurbulenceBox.hpp"
#include "kernels/shared_types.h"

namespace fw::io {

ScenarioError::ScenarioError(std::string file, int line, std::string key, const std::string& message)
    : std::invalid_argument(fmt::format("{}:{}: {}: {}", file, line, key, message)),
      file_(std::move(file)),
      line_(line),
      key_(std::move(key)) {}

std::string to_string(BoundaryChoice choice) {
  switch (choice) {
    case BoundaryChoice::automatic:
      return "auto";
    case BoundaryChoice::inflow:
      return "inflow";
    case BoundaryChoice::outflow:
      return "outflow";
    case BoundaryChoice::slip:
      return "slip";
    case BoundaryChoice::no_slip:
      return "no_slip";
    case BoundaryChoice::periodic:
      return "periodic";
    case BoundaryChoice::rough:
      return "rough";
  }
  return "?";
}

namespace {

/// sin and cos of an angle in degrees, exactly 0 and +-1 at whole multiples of 90 degrees. sin(degrees * pi /
/// 180) is not: at 270 degrees the cosine comes out as -1.8e-16, which would make a wind along x cross the
/// south face (an "auto" face parallel to the wind must resolve to outflow, see Scenario::grid_spec).
std::array<double, 2> sin_cos_degrees(double degrees) {
  constexpr double nan = std::numeric_limits<double>::quiet_NaN();
  if (!std::isfinite(degrees)) return {nan, nan};
  double reduced = std::fmod(degrees, 360.0);  // exact
  if (reduced < 0.0) reduced += 360.0;
  const double quadrant = std::round(reduced / 90.0);                          // 0..4
  const double rest = (reduced - 90.0 * quadrant) * std::numbers::pi / 180.0;  // within +-45 degrees
  const double s = std::sin(rest), c = std::cos(rest);
  switch (int(quadrant) % 4) {
    case 0:
      return {s, c};
    case 1:
      return {c, -s};
    case 2:
      return {-s, -c};
    default:
      return {-c, s};
  }
}

}  // namespace

std::array<double, 3> Scenario::wind_vector(double t) const {
  return io::wind_vector(wind, t);
}

std::array<double, 3> wind_vector(const WindSource& wind, double t) {
  const double speed = wind.speed(t);
  // Meteorological: the direction is where the wind comes FROM, so it blows toward direction + 180 degrees.
  const auto [sin_theta, cos_theta] = sin_cos_degrees(wind.direction(t));
  return {-speed * sin_theta, -speed * cos_theta, 0.0};
}

fluid::GridSpec Scenario::grid_spec(double t) const {
  fluid::GridSpec spec;
  spec.nx = domain.cells[0];
  spec.ny = domain.cells[1];
  spec.nz = domain.cells[2];
  spec.h = domain.cell_size;
  spec.origin = domain.origin;
  const std::array<double, 3> wind_now = wind_vector(t);
  for (int face = 0; face < 6; ++face) {
    switch (boundaries[face]) {
      case BoundaryChoice::automatic: {
        // The wind enters through a minimum face when it points along +axis, through a maximum face when
        // -axis.
        const double along = wind_now[face / 2];
        const bool enters = face % 2 == 0 ? along > 0.0 : along < 0.0;
        spec.boundary[face] = enters ? fluid::BoundaryType::inflow : fluid::BoundaryType::outflow;
        break;
      }
      case BoundaryChoice::inflow:
        spec.boundary[face] = fluid::BoundaryType::inflow;
        break;
      case BoundaryChoice::outflow:
        spec.boundary[face] = fluid::BoundaryType::outflow;
        break;
      case BoundaryChoice::slip:
        spec.boundary[face] = fluid::BoundaryType::slip;
        break;
      case BoundaryChoice::no_slip:
        spec.boundary[face] = fluid::BoundaryType::no_slip;
        break;
      case BoundaryChoice::periodic:
        spec.boundary[face] = fluid::BoundaryType::periodic;
        break;
      case BoundaryChoice::rough:  // a slip wall; the log-law wall stress is a stage of its own
        spec.boundary[face] = fluid::BoundaryType::slip;
        break;
    }
  }
  return spec;
}

std::optional<double> Scenario::resolved_probe_interval() const {
  if (output.probe_interval) return output.probe_interval;
  if (wind.turbulence) return std::nullopt;  // every solver step, for spectra
  return output.interval;
}

std::array<double, 3> TurbulenceSettings::standard_deviations(double speed) const {
  if (sigma) return *sigma;
  const double sigma_u = intensity.value_or(0.0) * speed;
  return {sigma_u, sigma_u, sigma_u};
}

fluid::WindSettings Scenario::wind_settings() const {
  fluid::WindSettings settings;
  settings.advection = solver.advection;
  settings.pressure.solver = solver.pressure;
  settings.pressure.tolerance = solver.tolerance;
  settings.pressure.max_iterations = solver.max_iterations;
  settings.pressure.jacobi_iterations = solver.jacobi_iterations;
  settings.vorticity_confinement = solver.vorticity_confinement;
  settings.smagorinsky_constant = solver.smagorinsky_constant;
  settings.wall_roughness_length = ground_roughness_length;
  if (time.dt) {
    settings.dt = *time.dt;
    settings.cfl = 0.0;
  } else {
    settings.cfl = time.cfl;
  }
  return settings;
}

namespace {

using Vec2 = std::array<double, 2>;
using Vec3 = std::array<double, 3>;

constexpr const char* kTopLevel = "(top level)";

/// A value in the file: the node, its dotted key and the 1-based line to blame.
struct Field {
  YAML::Node node;
  std::string key;
  int line = 1;
};

int line_of(const YAML::Node& node, int fallback) {
  const YAML::Mark mark = node.Mark();
  return mark.is_null() || mark.line < 0 ? fallback : mark.line + 1;
}

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

/// The ", got ..." part of a message: a scalar's text quoted, a short list of scalars as [a, b], else
/// what kind of node it is.
std::string shown(const YAML::Node& node) {
  switch (node.Type()) {
    case YAML::NodeType::Scalar:
      return "'" + printable(node.Scalar()) + "'";
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

std::optional<double> parse_double(const std::string& text) {
  std::string_view view = text;
  // from_chars takes a leading '-' but not '+', which YAML numbers may have.
  if (!view.empty() && view.front() == '+') view.remove_prefix(1);
  if (view.empty() || view.front() == '+' || (view.front() == '-' && text.front() == '+'))
    return std::nullopt;
  double value = 0.0;
  const auto [end, error] = std::from_chars(view.data(), view.data() + view.size(), value);
  if (error != std::errc() || end != view.data() + view.size() || !std::isfinite(value)) return std::nullopt;
  return value;
}

template <typename Integer>
std::optional<Integer> parse_integer(const std::string& text) {
  std::string_view view = text;
  if (!view.empty() && view.front() == '+') view.remove_prefix(1);
  if (view.empty() || view.front() == '+' || (view.front() == '-' && text.front() == '+'))
    return std::nullopt;
  Integer value{};
  const auto [end, error] = std::from_chars(view.data(), view.data() + view.size(), value);
  if (error != std::errc() || end != view.data() + view.size()) return std::nullopt;
  return value;
}

using schema::Bound;
using schema::Key;

/// The key of the table a field of the file stands for ("forest.species[0].modes" -> forest.species[].modes).
const Key& key_of(const Field& field) {
  const std::string path = schema::generic_path(field.key);
  const Key* key = schema::find(path);
  if (!key) throw std::logic_error("Scenario: the loader reads " + path + ", which the schema lacks");
  return *key;
}

/// A number with the range and unit of `owner` (the components of a point, say), as the table's number key.
std::string number_expected(const Key& owner) {
  return schema::expected(Key{.path = owner.path,
                              .type = schema::Type::number,
                              .unit = owner.unit,
                              .bound = owner.bound,
                              .at_most = owner.at_most,
                              .below = owner.below});
}

class Loader;

/// The keys of one map, checked against its keys in the schema (unknown and duplicate keys are errors, and
/// so are missing required keys). A null value (`solver:` with nothing after it) counts as an empty map.
/// With a variant (wind.profile's type), keys that apply to another variant are unknown; without one, all
/// are allowed and only the keys of every variant are required.
class MapFields {
 public:
  MapFields(const Loader& loader, const Field& map, const std::string* variant = nullptr);

  std::optional<Field> get(const std::string& name) const {
    const auto found = fields_.find(name);
    if (found == fields_.end()) return std::nullopt;
    return found->second;
  }
  /// The field, or an error at the map's line: "WHAT expected (required), got nothing", WHAT from the
  /// schema and `reason` (why it is needed here) after it.
  Field require(const std::string& name, const std::string& reason = "") const;
  std::size_t size() const { return fields_.size(); }
  const Field& self() const { return self_; }
  std::string path(const std::string& name) const {
    return self_.key.empty() || self_.key == kTopLevel ? name : self_.key + "." + name;
  }
  /// Names given, in file order.
  const std::vector<std::string>& given() const { return order_; }

 private:
  const Loader& loader_;
  Field self_;
  std::map<std::string, Field> fields_;
  std::vector<std::string> order_;
};

class Loader {
 public:
  Loader(std::string file, std::filesystem::path folder)
      : file_(std::move(file)), folder_(std::move(folder)) {}

  [[noreturn]] void fail(const Field& field, const std::string& message) const {
    throw ScenarioError(file_, field.line, field.key.empty() ? kTopLevel : field.key, message);
  }
  /// "WHAT expected, got VALUE".
  [[noreturn]] void expected(const Field& field, const std::string& what) const {
    fail(field, what + " expected, got " + shown(field.node));
  }
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

  int integer(const Field& field) const {
    const Key& key = key_of(field);
    if (!field.node.IsScalar()) expected(field);
    const auto value = parse_integer<long long>(field.node.Scalar());
    if (!value || *value < key.lowest || *value > key.highest) expected(field);
    return int(*value);
  }

  std::uint64_t seed(const Field& field) const {
    if (!field.node.IsScalar()) expected(field);
    const auto value = parse_integer<std::uint64_t>(field.node.Scalar());
    if (!value) expected(field);
    return *value;
  }

  bool boolean(const Field& field) const {
    if (field.node.IsScalar()) {
      const std::string& text = field.node.Scalar();
      if (text == "true" || text == "True" || text == "TRUE") return true;
      if (text == "false" || text == "False" || text == "FALSE") return false;
    }
    expected(field);
  }

  std::string text(const Field& field) const {
    if (!field.node.IsScalar() || field.node.Scalar().empty()) expected(field);
    return field.node.Scalar();
  }

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
  double component(const Field& list, std::size_t i, const Key& key) const {
    return number(child(list, list.node[i], fmt::format("{}[{}]", list.key, i)), key, number_expected(key));
  }

  Expression expression(const Field& field) const {
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

  /// A path relative to the scenario folder (or absolute) naming a readable regular file.
  std::filesystem::path readable_file(const Field& field) const {
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

  /// A list (null counts as empty); each item keyed KEY[i].
  std::vector<Field> items(const Field& field) const {
    std::vector<Field> out;
    if (field.node.IsNull()) return out;
    if (!field.node.IsSequence()) expected(field);
    for (std::size_t i = 0; i < field.node.size(); ++i)
      out.push_back(child(field, field.node[i], fmt::format("{}[{}]", field.key, i)));
    return out;
  }

  /// A list of distinct words of the key's vocabulary, in the file's order.
  std::vector<std::string> word_set(const Field& field) const {
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

  const std::filesystem::path& folder() const { return folder_; }

 private:
  /// A number in the range of `key`: its sign bound and its upper limit.
  double number(const Field& field, const Key& key, const std::string& what) const {
    if (!field.node.IsScalar()) expected(field, what);
    const std::optional<double> value = parse_double(field.node.Scalar());
    if (!value || (key.bound == Bound::positive && !(*value > 0.0)) ||
        (key.bound == Bound::non_negative && !(*value >= 0.0)) || !(*value <= key.at_most) ||
        !(*value < key.below))
      expected(field, what);
    return *value;
  }

  /// One of the vocabulary of `key` (a word key, or a word_set key for one of its items).
  std::string word(const Field& field, const Key& key) const {
    const std::vector<std::string> vocabulary = schema::words(key);
    if (field.node.IsScalar()) {
      const auto found = std::find(vocabulary.begin(), vocabulary.end(), field.node.Scalar());
      if (found != vocabulary.end()) return *found;
    }
    expected(field, "one of " + join(vocabulary, " | "));
  }

  std::string file_;
  std::filesystem::path folder_;
};

bool applies(const Key& key, const std::string* variant) {
  return !variant || key.only_with.empty() || key.only_with == *variant;
}

MapFields::MapFields(const Loader& loader, const Field& map, const std::string* variant)
    : loader_(loader), self_(map) {
  const std::string parent = schema::generic_path(map.key);
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
      require(std::string(key->path.substr(key->path.rfind('.') + 1)));
  }
}

Field MapFields::require(const std::string& name, const std::string& reason) const {
  if (auto field = get(name)) return *field;
  const Field missing{self_.node, path(name), self_.line};
  const std::string what = schema::expected(key_of(missing)) + (reason.empty() ? "" : ", " + reason);
  loader_.fail(missing, what + " expected (required), got nothing");
}

std::string axis_name(std::size_t axis) {
  return std::string(1, "xyz"[axis]);
}

/// The enum value of a word the loader read, from a vocabulary and its values aligned by position.
template <typename Enum, std::size_t N>
Enum value(const std::string_view (&words)[N], const Enum (&values)[N], const std::string& word) {
  return schema::value_of(words, values, word);
}

// --- sections --------------------------------------------------------------------------------------------

void read_time(const Loader& loader, const Field& field, TimeSettings& time) {
  const MapFields map(loader, field);
  time.end = loader.number(map.require("end"));
  if (const auto dt = map.get("dt")) {
    const Key& key = key_of(*dt);
    if (!(dt->node.IsScalar() && dt->node.Scalar() == key.word)) {  // the word: auto
      const std::optional<double> step = dt->node.IsScalar() ? parse_double(dt->node.Scalar()) : std::nullopt;
      if (!step || !(*step > 0.0)) loader.expected(*dt);
      time.dt = *step;
    }
  }
  if (const auto cfl = map.get("cfl")) time.cfl = loader.number(*cfl);
}

void read_domain(const Loader& loader, const Field& field, DomainSettings& domain) {
  const MapFields map(loader, field);
  if (const auto origin = map.get("origin")) domain.origin = loader.vector<3>(*origin);
  const Field size = map.require("size");
  domain.size = loader.vector<3>(size);
  domain.cell_size = loader.number(map.require("cell_size"));
  double total = 1.0;
  for (std::size_t axis = 0; axis < 3; ++axis) {
    const double cells = domain.size[axis] / domain.cell_size;
    const double whole = std::round(cells);
    const double tolerance = schema::kCellMultipleTolerance * domain.size[axis];
    if (whole < 1.0 || std::abs(whole * domain.cell_size - domain.size[axis]) > tolerance) {
      loader.expected(
          loader.child(size, size.node[axis], fmt::format("{}[{}]", size.key, axis)),
          fmt::format("a whole multiple of cell_size ({} m) along {}", domain.cell_size, axis_name(axis)));
    }
    if (whole > double(std::numeric_limits<int>::max())) total = std::numeric_limits<double>::infinity();
    domain.cells[axis] = int(std::min(whole, double(std::numeric_limits<int>::max())));
    total *= whole;
  }
  // Face arrays hold (nx + 1)(ny + 1)(nz + 1) values at most, indexed by 32-bit ints on the device.
  const double faces = (domain.cells[0] + 1.0) * (domain.cells[1] + 1.0) * (domain.cells[2] + 1.0);
  if (!(total < std::numeric_limits<double>::infinity()) || faces > double(fluid::GridSpec::kMaxFaces)) {
    loader.expected(map.require("cell_size"),
                    fmt::format("a cell size giving (nx + 1)(ny + 1)(nz + 1) <= {} (size / cell_size "
                                "gives {:.3g} cells)",
                                fluid::GridSpec::kMaxFaces, total));
  }
}

void read_boundaries(const Loader& loader, const Field& field, Scenario& scenario) {
  const std::vector<std::string> faces = schema::child_names("boundaries");  // in the order of FW_FACE_*
  const MapFields map(loader, field);
  std::array<std::optional<Field>, 6> given;
  const std::string rough = to_string(BoundaryChoice::rough);
  for (int face = 0; face < 6; ++face) {
    given[face] = map.get(faces[face]);
    if (!given[face]) continue;
    const Field& choice = *given[face];
    if (face != FW_FACE_GROUND && choice.node.IsScalar() && choice.node.Scalar() == rough)
      loader.expected(choice, schema::expected(key_of(choice)) + " (rough is for the ground only)");
    scenario.boundaries[face] = value(schema::kBoundaryWords, kBoundaryChoices, loader.word(choice));
  }
  if (const auto roughness = map.get("roughness_length")) {
    const double z0 = loader.number(*roughness);
    if (scenario.boundaries[FW_FACE_GROUND] != BoundaryChoice::rough) {
      loader.expected(*roughness, fmt::format("nothing unless boundaries.ground is rough (it is '{}')",
                                              to_string(scenario.boundaries[FW_FACE_GROUND])));
    }
    const double first_centre = fluid::wall_centre_height(scenario.domain.cell_size);
    if (!(z0 < first_centre)) {
      loader.expected(*roughness,
                      fmt::format("{} below cell_size / 2 = {} m (the log law is evaluated at the "
                                  "first cell centre)",
                                  schema::expected(key_of(*roughness)), first_centre));
    }
    scenario.ground_roughness_length = z0;
  }
  for (int axis = 0; axis < 3; ++axis) {
    const int low = 2 * axis, high = 2 * axis + 1;
    const bool low_periodic = scenario.boundaries[low] == BoundaryChoice::periodic;
    const bool high_periodic = scenario.boundaries[high] == BoundaryChoice::periodic;
    if (low_periodic != high_periodic) {
      const int face = low_periodic ? low : high, other = low_periodic ? high : low;
      loader.expected(
          *given[face],
          fmt::format("periodic on both {} and {} (a pair), or neither; {} is '{}', so not periodic",
                      faces[low], faces[high], faces[other], to_string(scenario.boundaries[other])));
    }
    const int cells = scenario.domain.cells[axis];
    if (low_periodic && cells > 1 && cells % 2 != 0) {
      loader.expected(*given[low], fmt::format("periodic only along an axis with an even cell count; {} has "
                                               "{} cells",
                                               axis_name(axis), cells));
    }
  }
}

/// Every value of the expression over the run is finite, and >= 0 where its key's bound says so.
void check_time_series(const Loader& loader, const Field& field, const Expression& expression, double end) {
  const bool non_negative = key_of(field).bound == Bound::non_negative;
  // Sampled densely over the run so that a formula that goes bad mid-run fails at load, not at step 10^5.
  const int samples = expression.is_constant() ? 1 : 1001;
  for (int i = 0; i < samples; ++i) {
    const double t = samples == 1 ? 0.0 : end * i / (samples - 1);
    const double value = expression(t);
    if (!std::isfinite(value) || (non_negative && value < 0.0)) {
      loader.expected(field,
                      fmt::format("a value that is finite{} for 0 <= t <= {} s (it gives {} at t = {} s)",
                                  non_negative ? " and >= 0" : "", end, value, t));
    }
  }
}

/// The default turbulence box spans this many length scales along x and y.
constexpr double kDefaultBoxLengthScales = 8.0;

TurbulenceSettings read_turbulence(const Loader& loader, const Field& field, const Scenario& scenario) {
  const MapFields map(loader, field);  // length_scale is required
  TurbulenceSettings turbulence;
  if (const auto model = map.get("model"))
    turbulence.model = value(schema::kTurbulenceModelWords, kTurbulenceModels, loader.word(*model));

  // Exactly one of intensity and sigma; with both, the one given second is blamed.
  const auto intensity = map.get("intensity");
  const auto sigma = map.get("sigma");
  if (intensity && sigma) {
    const bool sigma_second = std::find(map.given().begin(), map.given().end(), "sigma") >
                              std::find(map.given().begin(), map.given().end(), "intensity");
    const Field& second = sigma_second ? *sigma : *intensity;
    const Field& first = sigma_second ? *intensity : *sigma;
    loader.fail(second, fmt::format("exactly one of intensity and sigma expected, got both ({} on line {})",
                                    sigma_second ? "intensity" : "sigma", first.line));
  }
  if (!intensity && !sigma) map.require("intensity", "or sigma (exactly one of intensity and sigma)");
  if (intensity) turbulence.intensity = loader.number(*intensity);
  if (sigma) turbulence.sigma = loader.vector<3>(*sigma);

  turbulence.length_scale = loader.number(map.require("length_scale"));
  turbulence.seed = scenario.seed;
  if (const auto seed = map.get("seed")) turbulence.seed = loader.seed(*seed);
  if (const auto unresolved = map.get("unresolved")) turbulence.unresolved = loader.boolean(*unresolved);
  if (const auto cutoff = map.get("cutoff_cells")) turbulence.cutoff_cells = loader.number(*cutoff);

  // The box counts cells of the grid: a given size rounds to an even count of at least
  // kMinTurbulenceBoxCells; the default takes powers of two (fast FFTs) that cover the domain and, along x
  // and y, kDefaultBoxLengthScales length scales. The fluid::TurbulenceBox that a run builds from it has
  // kTurbulencePointsPerCell points per cell along each axis, and at most TurbulenceBoxSpec::kMaxPoints in
  // all: the limit counts those points, so that a box this accepts is one the run can build.
  const double h = scenario.domain.cell_size;
  const double per_cell = fluid::kTurbulencePointsPerCell;
  const double most_points = double(fluid::TurbulenceBoxSpec::kMaxPoints);
  const double fewest_cells = schema::kMinTurbulenceBoxCells;
  const auto box_size = map.get("box_size");
  std::array<double, 3> cells{};
  if (box_size) {
    const std::array<double, 3> size = loader.vector<3>(*box_size);
    for (std::size_t axis = 0; axis < 3; ++axis)
      cells[axis] = std::max(fewest_cells, 2.0 * std::round(size[axis] / (2.0 * h)));
  } else {
    for (std::size_t axis = 0; axis < 3; ++axis) {
      double target = scenario.domain.cells[axis];
      if (axis < 2) target = std::max(target, kDefaultBoxLengthScales * turbulence.length_scale / h);
      double count = fewest_cells;
      while (count < target && count * per_cell <= most_points) count *= 2.0;
      cells[axis] = count;
    }
  }
  const double points = cells[0] * cells[1] * cells[2] * per_cell * per_cell * per_cell;
  if (!(points <= most_points)) {
    const std::string box = fmt::format("{:.0f} x {:.0f} x {:.0f} cells of {} m, {:.3g} points", cells[0],
                                        cells[1], cells[2], h, points);
    const std::string limit =
        fmt::format("at most {:.0f} points in all, {:.0f} per cell along each axis", most_points, per_cell);
    if (box_size) {
      loader.expected(*box_size, fmt::format("{} of {} (this box is {})", schema::expected(key_of(*box_size)),
                                             limit, box));
    }
    const Field missing{field.node, field.key + ".box_size", field.line};
    loader.fail(missing, fmt::format("{} of {} expected (required here: the default box, {:.0f} length_scale "
                                     "along x and y, is {}), got nothing",
                                     schema::expected(key_of(missing)), limit, kDefaultBoxLengthScales, box));
  }
  for (std::size_t axis = 0; axis < 3; ++axis) {
    turbulence.box_cells[axis] = int(cells[axis]);
    turbulence.box_size[axis] = cells[axis] * h;
  }
  turbulence.box_size_given = box_size.has_value();
  return turbulence;
}

bool sides_periodic(const Scenario& scenario) {
  for (const int face : {FW_FACE_WEST, FW_FACE_EAST, FW_FACE_SOUTH, FW_FACE_NORTH})
    if (scenario.boundaries[face] != BoundaryChoice::periodic) return false;
  return true;
}

void read_wind(const Loader& loader, const Field& field, Scenario& scenario) {
  WindSource& wind = scenario.wind;
  const MapFields map(loader, field);
  const Field speed = map.require("speed");
  wind.speed = loader.expression(speed);
  check_time_series(loader, speed, wind.speed, scenario.time.end);
  const Field direction = map.require("direction");
  wind.direction = loader.expression(direction);
  check_time_series(loader, direction, wind.direction, scenario.time.end);
  if (const auto height = map.get("reference_height")) wind.reference_height = loader.number(*height);

  wind.profile = fluid::InflowProfile{};
  wind.profile.type =
      value(schema::kProfileWords, schema::kProfileTypes, std::string(schema::key("wind.profile.type").word));
  wind.profile.alpha = schema::key("wind.profile.alpha").number;
  wind.profile.displacement_height = schema::key("wind.profile.displacement_height").number;
  wind.profile.reference_height = wind.reference_height;
  if (const auto profile_field = map.get("profile")) {
    // The allowed keys depend on the type, so read the type first.
    const MapFields any(loader, *profile_field);
    const std::string type = loader.word(any.require("type"));
    const MapFields profile(loader, *profile_field, &type);
    wind.profile.type = value(schema::kProfileWords, schema::kProfileTypes, type);
    if (const auto alpha = profile.get("alpha")) wind.profile.alpha = loader.number(*alpha);
    if (const auto roughness = profile.get("roughness_length"))
      wind.profile.roughness_length = loader.number(*roughness);
    const auto displacement = profile.get("displacement_height");
    if (displacement) wind.profile.displacement_height = loader.number(*displacement);
    if (wind.profile.type == fluid::InflowProfile::Type::log) {
      // The log law is only defined above d + z0, and the reference height is where it equals `speed`.
      const double floor = wind.profile.displacement_height + wind.profile.roughness_length;
      if (!(wind.reference_height > floor)) {
        loader.expected(
            displacement ? *displacement : profile.require("roughness_length"),
            fmt::format(
                "displacement_height + roughness_length (now {} m) below wind.reference_height ({} m)", floor,
                wind.reference_height));
      }
    }
  }

  if (const auto turbulence = map.get("turbulence"))
    wind.turbulence = read_turbulence(loader, *turbulence, scenario);

  // A domain without inflow (all four sides periodic) is driven by the mean forcing, given or not.
  const bool periodic = sides_periodic(scenario);
  if (const auto forcing_field = map.get("forcing")) {
    if (!periodic) {
      int open = FW_FACE_WEST;
      while (scenario.boundaries[open] == BoundaryChoice::periodic) ++open;
      const std::vector<std::string> faces = schema::child_names("boundaries");
      loader.expected(
          *forcing_field,
          fmt::format("forcing only in a domain whose west, east, south and north are all periodic "
                      "(boundaries.{} is '{}')",
                      faces[open], to_string(scenario.boundaries[open])));
    }
    const MapFields forcing(loader, *forcing_field);
    wind.forcing = ForcingSettings{};
    if (const auto tau = forcing.get("relaxation_time")) wind.forcing->relaxation_time = loader.number(*tau);
  } else if (periodic) {
    wind.forcing = ForcingSettings{};
  }
}

/// The roughness length of a rough ground that boundaries.roughness_length leaves out: the log profile's,
/// else the schema's default; it too must lie below h / 2. `boundaries` is the file's boundaries map.
void resolve_ground_roughness(const Loader& loader, const Field& boundaries, Scenario& scenario) {
  if (scenario.boundaries[FW_FACE_GROUND] != BoundaryChoice::rough || scenario.ground_roughness_length > 0.0)
    return;
  const bool from_profile = scenario.wind.profile.type == fluid::InflowProfile::Type::log;
  const double z0 = from_profile ? scenario.wind.profile.roughness_length
                                 : schema::key("boundaries.roughness_length").number;
  const double first_centre = fluid::wall_centre_height(scenario.domain.cell_size);
  if (!(z0 < first_centre)) {
    const Field missing{boundaries.node, "boundaries.roughness_length", boundaries.line};
    const std::string default_text =
        from_profile ? fmt::format("the default, wind.profile.roughness_length, is {} m", z0)
                     : fmt::format("the default without a log profile is {} m", z0);
    loader.fail(missing,
                fmt::format("{} below cell_size / 2 = {} m expected (required here: {}), got nothing",
                            schema::expected(key_of(missing)), first_centre, default_text));
  }
  scenario.ground_roughness_length = z0;
}

void read_events(const Loader& loader, const Field& field, Scenario& scenario) {
  for (const Field& item : loader.items(field)) {
    const MapFields kind(loader, item);
    const MapFields map(loader, kind.require("gust"));
    GustEvent gust;
    gust.start = loader.number(map.require("start"));
    gust.duration = loader.number(map.require("duration"));
    gust.peak_speed = loader.number(map.require("peak_speed"));
    gust.center = loader.vector<3>(map.require("center"));
    gust.radius = loader.number(map.require("radius"));
    gust.travel_with_wind = true;
    if (const auto travel = map.get("travel")) {
      const Key& key = key_of(*travel);
      if (travel->node.IsSequence() && travel->node.size() == 3) {
        gust.travel_with_wind = false;
        for (std::size_t i = 0; i < 3; ++i) gust.travel[i] = loader.component(*travel, i, key);
      } else if (!(travel->node.IsScalar() && travel->node.Scalar() == key.word)) {  // the word: with_wind
        loader.expected(*travel);
      }
    }
    if (gust.travel_with_wind) gust.travel = scenario.wind_vector(gust.start);
    scenario.events.push_back(gust);
  }
}

/// The one key of a map that must hold exactly one of its schema's keys (an obstacle, a skeleton source).
std::string the_one_key(const Loader& loader, const MapFields& map) {
  if (map.size() != 1) {
    const std::string parent = schema::generic_path(map.self().key);
    loader.fail(map.self(), fmt::format("a map with exactly one of the keys {} expected, got {}",
                                        join(schema::child_names(parent), ", "),
                                        map.size() == 0 ? std::string("none") : join(map.given(), " and ")));
  }
  return map.given().front();
}

void read_obstacles(const Loader& loader, const Field& field, Scenario& scenario) {
  for (const Field& item : loader.items(field)) {
    const MapFields kind(loader, item);
    const std::string shape = the_one_key(loader, kind);
    const MapFields map(loader, *kind.get(shape));
    if (shape == "box") {
      fluid::SolidBox box;
      box.name = loader.text(map.require("name"));
      box.center = loader.vector<3>(map.require("center"));
      box.size = loader.vector<3>(map.require("size"));
      if (const auto yaw = map.get("yaw")) box.yaw_rad = radians(loader.number(*yaw));
      scenario.obstacles.emplace_back(box);
    } else if (shape == "cylinder") {
      fluid::SolidCylinder cylinder;
      cylinder.name = loader.text(map.require("name"));
      cylinder.base = loader.vector<3>(map.require("base"));
      cylinder.radius = loader.number(map.require("radius"));
      cylinder.height = loader.number(map.require("height"));
      scenario.obstacles.emplace_back(cylinder);
    } else {
      fluid::SolidSphere sphere;
      sphere.name = loader.text(map.require("name"));
      sphere.center = loader.vector<3>(map.require("center"));
      sphere.radius = loader.number(map.require("radius"));
      scenario.obstacles.emplace_back(sphere);
    }
  }
}

void read_terrain(const Loader& loader, const Field& field, Scenario& scenario) {
  const MapFields map(loader, field);
  TerrainSettings terrain;
  const Field heightmap = map.require("heightmap");
  terrain.heightmap = loader.readable_file(heightmap);
  // The format comes from the content (fluid/Heightmap.hpp); cell size and height scale matter for PGM only.
  char magic[2] = {0, 0};
  std::ifstream(terrain.heightmap, std::ios::binary).read(magic, 2);
  const bool pgm = magic[0] == 'P' && (magic[1] == '2' || magic[1] == '5');
  const auto cell_size = map.get("cell_size");
  const auto max_height = map.get("max_height");
  if (cell_size) terrain.cell_size = loader.number(*cell_size);
  if (max_height) terrain.max_height = loader.number(*max_height);
  const std::string reason = "needed for a PGM heightmap";
  if (pgm && !cell_size) map.require("cell_size", reason);
  if (pgm && !max_height) map.require("max_height", reason);
  try {
    terrain.map = fluid::Heightmap::read(terrain.heightmap.string(), pgm ? terrain.cell_size : 1.0,
                                         pgm ? terrain.max_height : 0.0);
  } catch (const std::exception& error) {
    loader.expected(heightmap, fmt::format("a PGM or ESRI ASCII grid ({})", error.what()));
  }
  if (pgm) {
    // An image has no georeference: its south-west corner goes to the domain's, wherever the origin is.
    const fluid::Heightmap& image = *terrain.map;
    std::vector<double> heights;
    heights.reserve(std::size_t(image.columns()) * std::size_t(image.rows()));
    for (int row = 0; row < image.rows(); ++row)
      for (int column = 0; column < image.columns(); ++column) heights.push_back(image.sample(column, row));
    const double half = 0.5 * image.cell_size();
    terrain.map = fluid::Heightmap(image.columns(), image.rows(), image.cell_size(),
                                   {scenario.domain.origin[0] + half, scenario.domain.origin[1] + half},
                                   std::move(heights));
  }
  scenario.terrain = std::move(terrain);
}

bool inside(double value, double low, double high) {
  return value >= low && value <= high;
}

std::string horizontal_extent(const DomainSettings& domain) {
  const Vec3 top = domain.max_corner();
  return fmt::format("[{}, {}] x [{}, {}] m", domain.origin[0], top[0], domain.origin[1], top[1]);
}

int species_index(const Loader& loader, const Field& field, const std::vector<Species>& species) {
  const std::string name = loader.text(field);
  for (std::size_t i = 0; i < species.size(); ++i)
    if (species[i].name == name) return int(i);
  std::vector<std::string> names;
  for (const Species& s : species) names.push_back(s.name);
  const std::string what = schema::expected(key_of(field));
  loader.expected(
      field, names.empty() ? what + " (forest.species is empty)" : what + ", one of " + join(names, ", "));
}

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

Vec2 region_corner(const Loader& loader, const Field& field, const DomainSettings& domain) {
  const Vec2 corner = loader.vector<2>(field);
  const Vec3 top = domain.max_corner();
  if (!inside(corner[0], domain.origin[0], top[0]) || !inside(corner[1], domain.origin[1], top[1]))
    loader.expected(field,
                    "a point [x, y] inside the domain's horizontal extent " + horizontal_extent(domain));
  return corner;
}

Stand read_stand(const Loader& loader, const Field& item, const Scenario& scenario) {
  const MapFields map(loader, item);
  Stand stand;
  const Field species = map.require("species");
  stand.layout.species = species_index(loader, species, scenario.forest.species);
  stand.species = scenario.forest.species[stand.layout.species].name;

  const MapFields region(loader, map.require("region"));
  const Vec2 min = region_corner(loader, region.require("min"), scenario.domain);
  const Field max_field = region.require("max");
  const Vec2 max = region_corner(loader, max_field, scenario.domain);
  if (!(max[0] > min[0]) || !(max[1] > min[1]))
    loader.expected(max_field,
                    fmt::format("a point north-east of min [{}, {}] (x and y both larger)", min[0], min[1]));
  stand.layout.min = {min[0], min[1]};
  stand.layout.max = {max[0], max[1]};

  stand.layout.layout =
      value(schema::kLayoutWords, schema::kLayouts, std::string(schema::key("forest.stands[].layout").word));
  if (const auto layout = map.get("layout"))
    stand.layout.layout = value(schema::kLayoutWords, schema::kLayouts, loader.word(*layout));
  const Field spacing = map.require("spacing");
  stand.layout.spacing = loader.number(spacing);
  stand.layout.scale_min = schema::key("forest.stands[].scale.min").number;
  stand.layout.scale_max = schema::key("forest.stands[].scale.max").number;
  if (const auto scale_field = map.get("scale")) {
    const MapFields scale(loader, *scale_field);
    if (const auto low = scale.get("min")) stand.layout.scale_min = loader.number(*low);
    if (const auto high = scale.get("max")) {
      stand.layout.scale_max = loader.number(*high);
      if (stand.layout.scale_max < stand.layout.scale_min)
        loader.expected(*high, fmt::format("a number >= scale.min ({})", stand.layout.scale_min));
    } else if (stand.layout.scale_max < stand.layout.scale_min) {
      loader.expected(*scale.get("min"),
                      fmt::format("a number <= scale.max ({}, the default)", stand.layout.scale_max));
    }
  }
  // Unless the file gives one: the global seed plus the stand's index.
  stand.layout.seed = scenario.seed + scenario.forest.stands.size();
  if (const auto seed = map.get("seed")) stand.layout.seed = loader.seed(*seed);
  try {
    stand.layout.validate();  // what is left to fail: too many trees for the region and spacing
  } catch (const std::invalid_argument& error) {
    loader.expected(spacing, fmt::format("a spacing the region can hold ({})", error.what()));
  }
  return stand;
}

PlacedTreeSettings read_tree(const Loader& loader, const Field& item, const Scenario& scenario) {
  const MapFields map(loader, item);
  PlacedTreeSettings tree;
  tree.species_index = species_index(loader, map.require("species"), scenario.forest.species);
  tree.species = scenario.forest.species[tree.species_index].name;

  const Field position = map.require("position");
  if (!position.node.IsSequence() || (position.node.size() != 2 && position.node.size() != 3))
    loader.expected(position);
  for (std::size_t i = 0; i < position.node.size(); ++i)
    tree.position[i] = loader.component(position, i, key_of(position));
  const DomainSettings& domain = scenario.domain;
  const Vec3 top = domain.max_corner();
  if (!inside(tree.position[0], domain.origin[0], top[0]) ||
      !inside(tree.position[1], domain.origin[1], top[1]))
    loader.expected(position,
                    "a position inside the domain's horizontal extent " + horizontal_extent(domain));
  tree.height_given = position.node.size() == 3;
  if (tree.height_given && !inside(tree.position[2], domain.origin[2], top[2])) {
    loader.expected(loader.child(position, position.node[2], position.key + "[2]"),
                    fmt::format("a height inside the domain's [{}, {}] m", domain.origin[2], top[2]));
  }
  if (!tree.height_given) {
    // On the ground: the terrain surface, whose heights count from the domain floor.
    tree.position[2] = domain.origin[2];
    if (scenario.terrain)
      tree.position[2] += scenario.terrain->map->height_at(tree.position[0], tree.position[1]);
  }
  if (const auto yaw = map.get("yaw")) tree.yaw_rad = radians(loader.number(*yaw));
  if (const auto scale = map.get("scale")) tree.scale = loader.number(*scale);
  return tree;
}

void read_forest(const Loader& loader, const Field& field, Scenario& scenario) {
  const MapFields map(loader, field);
  ForestSettings& forest = scenario.forest;
  if (const auto coupling = map.get("two_way_coupling")) forest.two_way_coupling = loader.boolean(*coupling);
  if (const auto integrator = map.get("integrator"))
    forest.integrator = value(schema::kIntegratorWords, schema::kIntegrators, loader.word(*integrator));
  if (const auto correction = map.get("strong_wind_correction"))
    forest.strong_wind_correction = loader.boolean(*correction);
  if (const auto species = map.get("species"))
    for (const Field& item : loader.items(*species))
      forest.species.push_back(read_species(loader, item, forest.species, scenario.seed));
  if (const auto stands = map.get("stands"))
    for (const Field& item : loader.items(*stands))
      forest.stands.push_back(read_stand(loader, item, scenario));
  if (const auto trees = map.get("trees"))
    for (const Field& item : loader.items(*trees)) forest.trees.push_back(read_tree(loader, item, scenario));
}

void read_solver(const Loader& loader, const Field& field, SolverSettings& solver) {
  const MapFields map(loader, field);
  if (const auto pressure = map.get("pressure"))
    solver.pressure = value(schema::kPressureWords, schema::kPressureSolvers, loader.word(*pressure));
  if (const auto tolerance = map.get("tolerance")) solver.tolerance = loader.number(*tolerance);
  if (const auto iterations = map.get("max_iterations")) solver.max_iterations = loader.integer(*iterations);
  if (const auto iterations = map.get("jacobi_iterations"))
    solver.jacobi_iterations = loader.integer(*iterations);
  if (const auto advection = map.get("advection"))
    solver.advection = value(schema::kAdvectionWords, schema::kAdvectionSchemes, loader.word(*advection));
  if (const auto epsilon = map.get("vorticity_confinement"))
    solver.vorticity_confinement = loader.number(*epsilon);
  if (const auto smagorinsky = map.get("smagorinsky_constant"))
    solver.smagorinsky_constant = loader.number(*smagorinsky);
}

bool probe_name(const std::string& name) {
  return !name.empty() && std::all_of(name.begin(), name.end(), [](unsigned char c) {
    return (c >= 'A' && c <= 'Z') || (c >= 'a' && c <= 'z') || (c >= '0' && c <= '9') || c == '_';
  });
}

/// Where output.directory's default names the scenario.
constexpr std::string_view kScenarioNamePlaceholder = "<scenario>";

void read_output(const Loader& loader, const Field& field, Scenario& scenario) {
  OutputSettings& output = scenario.output;
  const MapFields map(loader, field);
  std::string directory(schema::key("output.directory").word);
  if (const std::size_t at = directory.find(kScenarioNamePlaceholder); at != std::string::npos)
    directory.replace(at, kScenarioNamePlaceholder.size(), scenario.name);
  if (const auto given = map.get("directory")) directory = loader.text(*given);
  // Against the working directory, not the scenario folder: a run writes where it is started.
  output.directory = std::filesystem::absolute(std::filesystem::path(directory)).lexically_normal();
  if (const auto interval = map.get("interval")) output.interval = loader.number(*interval);
  if (const auto probe_interval = map.get("probe_interval")) {
    const Key& key = key_of(*probe_interval);
    if (!(probe_interval->node.IsScalar() && probe_interval->node.Scalar() == key.word)) {  // the word: auto
      const std::optional<double> every =
          probe_interval->node.IsScalar() ? parse_double(probe_interval->node.Scalar()) : std::nullopt;
      if (!every || !(*every > 0.0)) loader.expected(*probe_interval);
      output.probe_interval = *every;
    }
  }
  if (const auto vtk_field = map.get("vtk")) {
    const MapFields vtk(loader, *vtk_field);
    if (const auto wind = vtk.get("wind")) output.vtk_wind = loader.boolean(*wind);
    if (const auto trees = vtk.get("trees")) output.vtk_trees = loader.boolean(*trees);
    if (const auto fields = vtk.get("fields")) output.vtk_fields = loader.word_set(*fields);
  }
  if (const auto vdb_field = map.get("vdb")) {
    const MapFields vdb(loader, *vdb_field);
    if (const auto enabled = vdb.get("enabled")) output.vdb_enabled = loader.boolean(*enabled);
    if (const auto grids = vdb.get("grids")) output.vdb_grids = loader.word_set(*grids);
  }
  if (const auto leaves_field = map.get("leaves")) {
    const MapFields leaves(loader, *leaves_field);
    if (const auto attached = leaves.get("attached")) {
      // A word (all, none) or a stride N >= 1.
      const Key& key = key_of(*attached);
      const std::vector<std::string> words = schema::words(key);
      const bool word = attached->node.IsScalar() &&
                        std::find(words.begin(), words.end(), attached->node.Scalar()) != words.end();
      if (word) {
        output.leaves_attached_stride =
            value(schema::kLeafStrideWords, schema::kLeafStrides, loader.word(*attached));
      } else {
        const auto stride =
            attached->node.IsScalar() ? parse_integer<long long>(attached->node.Scalar()) : std::nullopt;
        if (!stride || *stride < key.lowest || *stride > key.highest) loader.expected(*attached);
        output.leaves_attached_stride = int(*stride);
      }
    }
    if (const auto vtk = leaves.get("vtk")) output.vtk_leaves = loader.boolean(*vtk);
  }
  if (const auto probes = map.get("probes")) {
    for (const Field& item : loader.items(*probes)) {
      const MapFields probe_map(loader, item);
      Probe probe;
      const Field name = probe_map.require("name");
      probe.name = loader.text(name);
      const std::string what = schema::expected(key_of(name));
      if (!probe_name(probe.name)) loader.expected(name, what + " of letters, digits and _");
      for (const Probe& other : output.probes)
        if (other.name == probe.name) loader.expected(name, what + " not used before");
      const Field position = probe_map.require("position");
      probe.position = loader.vector<3>(position);
      const Vec3 top = scenario.domain.max_corner();
      for (int axis = 0; axis < 3; ++axis) {
        if (!inside(probe.position[axis], scenario.domain.origin[axis], top[axis])) {
          loader.expected(position,
                          fmt::format("a position inside the domain [{}, {}] x [{}, {}] x [{}, {}] m",
                                      scenario.domain.origin[0], top[0], scenario.domain.origin[1], top[1],
                                      scenario.domain.origin[2], top[2]));
        }
      }
      output.probes.push_back(probe);
    }
  }
}

std::string read_whole_file(const std::filesystem::path& file) {
  const std::string name = file.string();
  std::error_code error;
  if (std::filesystem::is_directory(file, error))
    throw ScenarioError(name, 0, "(file)", "a readable scenario file expected, got a directory");
  std::ifstream in(file, std::ios::binary);
  if (!in) {
    throw ScenarioError(
        name, 0, "(file)",
        fmt::format("a readable scenario file expected, got '{}' ({})", name,
                    std::filesystem::exists(file, error) ? std::strerror(errno) : "no such file"));
  }
  std::ostringstream text;
  text << in.rdbuf();
  if (in.bad()) throw ScenarioError(name, 0, "(file)", "a readable scenario file expected, got a read error");
  return text.str();
}

}  // namespace

Scenario load_scenario(const std::filesystem::path& file) {
  Scenario scenario;
  const std::string name = file.string();
  scenario.file = file;
  scenario.folder = std::filesystem::absolute(file).parent_path().lexically_normal();
  scenario.text = read_whole_file(file);

  std::vector<YAML::Node> documents;
  try {
    documents = YAML::LoadAll(scenario.text);
  } catch (const YAML::Exception& error) {
    throw ScenarioError(name, error.mark.is_null() ? 1 : error.mark.line + 1, "(yaml)",
                        "valid YAML expected, got a syntax error: " + error.msg);
  }
  const Loader loader(name, scenario.folder);
  if (documents.size() > 1) {
    loader.fail(Field{documents[1], "(yaml)", line_of(documents[1], 1)},
                fmt::format("one YAML document expected, got {}", documents.size()));
  }
  const Field root{documents.empty() ? YAML::Node() : documents.front(), "", 1};
  if (!root.node.IsMap()) {
    std::vector<std::string> required;
    for (const Key* key : schema::children(""))
      if (key->required) required.emplace_back(key->path);
    loader.expected(root, "a map of scenario keys (" + join(required, ", ") + ", ...)");
  }
  const MapFields top(loader, root);

  const Field scenario_name = top.require("scenario");
  scenario.name = loader.text(scenario_name);
  if (scenario.name.find_first_of("/\\") != std::string::npos || scenario.name == "." ||
      scenario.name == ".." ||
      std::any_of(scenario.name.begin(), scenario.name.end(), [](unsigned char c) { return c < 0x20; })) {
    // The name becomes a folder name (out/<scenario>).
    loader.expected(scenario_name, schema::expected(key_of(scenario_name)) +
                                       " usable as a folder name (no / or \\, not . or ..)");
  }
  if (const auto seed = top.get("seed")) scenario.seed = loader.seed(*seed);
  read_time(loader, top.require("time"), scenario.time);
  read_domain(loader, top.require("domain"), scenario.domain);
  const auto boundaries = top.get("boundaries");
  if (boundaries) read_boundaries(loader, *boundaries, scenario);
  read_wind(loader, top.require("wind"), scenario);
  if (boundaries) resolve_ground_roughness(loader, *boundaries, scenario);
  if (const auto events = top.get("events")) read_events(loader, *events, scenario);
  if (const auto obstacles = top.get("obstacles")) read_obstacles(loader, *obstacles, scenario);
  if (const auto terrain = top.get("terrain")) read_terrain(loader, *terrain, scenario);
  if (const auto forest = top.get("forest")) read_forest(loader, *forest, scenario);
  if (const auto solver = top.get("solver")) read_solver(loader, *solver, scenario.solver);
  read_output(loader, top.get("output").value_or(Field{YAML::Node(YAML::NodeType::Null), "output", 1}),
              scenario);
  return scenario;
}

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
