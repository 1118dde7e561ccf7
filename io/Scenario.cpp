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
    }
  }
  return spec;
}

fluid::WindSettings Scenario::wind_settings() const {
  fluid::WindSettings settings;
  settings.advection = solver.advection;
  settings.pressure.solver = solver.pressure;
  settings.pressure.tolerance = solver.tolerance;
  settings.pressure.max_iterations = solver.max_iterations;
  settings.pressure.jacobi_iterations = solver.jacobi_iterations;
  settings.vorticity_confinement = solver.vorticity_confinement;
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

enum class Sign { any, positive, non_negative };

class Loader;

/// The keys of one map, checked against the allowed names (unknown and duplicate keys are errors). A null
/// value (`solver:` with nothing after it) counts as an empty map.
class MapFields {
 public:
  MapFields(const Loader& loader, const Field& map, const std::vector<std::string>& allowed);

  std::optional<Field> get(const std::string& name) const {
    const auto found = fields_.find(name);
    if (found == fields_.end()) return std::nullopt;
    return found->second;
  }
  /// The field, or an error at the map's line: "WHAT expected (required), got nothing".
  Field require(const std::string& name, const std::string& what) const;
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

  Field child(const Field& parent, const YAML::Node& node, const std::string& key) const {
    return Field{node, key, line_of(node, parent.line)};
  }

  // --- scalars ---------------------------------------------------------------------------------------

  double number(const Field& field, Sign sign = Sign::any, const std::string& unit = "") const {
    const std::string what = fmt::format("a number{}{}",
                                         sign == Sign::positive       ? " > 0"
                                         : sign == Sign::non_negative ? " >= 0"
                                                                      : "",
                                         unit.empty() ? "" : " (" + unit + ")");
    if (!field.node.IsScalar()) expected(field, what);
    const std::optional<double> value = parse_double(field.node.Scalar());
    if (!value || (sign == Sign::positive && !(*value > 0.0)) ||
        (sign == Sign::non_negative && !(*value >= 0.0)))
      expected(field, what);
    return *value;
  }

  int integer(const Field& field, int lowest, int highest) const {
    const std::string what = highest == std::numeric_limits<int>::max()
                                 ? fmt::format("an integer >= {}", lowest)
                                 : fmt::format("an integer {}..{}", lowest, highest);
    if (!field.node.IsScalar()) expected(field, what);
    const auto value = parse_integer<long long>(field.node.Scalar());
    if (!value || *value < lowest || *value > highest) expected(field, what);
    return int(*value);
  }

  std::uint64_t seed(const Field& field) const {
    const std::string what = "an integer 0..18446744073709551615";
    if (!field.node.IsScalar()) expected(field, what);
    const auto value = parse_integer<std::uint64_t>(field.node.Scalar());
    if (!value) expected(field, what);
    return *value;
  }

  bool boolean(const Field& field) const {
    if (field.node.IsScalar()) {
      const std::string& text = field.node.Scalar();
      if (text == "true" || text == "True" || text == "TRUE") return true;
      if (text == "false" || text == "False" || text == "FALSE") return false;
    }
    expected(field, "true or false");
  }

  std::string text(const Field& field, const std::string& what) const {
    if (!field.node.IsScalar() || field.node.Scalar().empty()) expected(field, what);
    return field.node.Scalar();
  }

  /// One of words; returns its index.
  std::size_t word(const Field& field, const std::vector<std::string>& words) const {
    if (field.node.IsScalar()) {
      const auto found = std::find(words.begin(), words.end(), field.node.Scalar());
      if (found != words.end()) return std::size_t(found - words.begin());
    }
    expected(field, "one of " + join(words, " | "));
  }

  template <std::size_t N>
  std::array<double, N> vector(const Field& field, Sign sign, const std::string& unit) const {
    static const char* const kNames[] = {"x", "y", "z"};
    std::vector<std::string> names(kNames, kNames + N);
    const std::string what = fmt::format("a list of {} numbers [{}]{}{}", N, join(names, ", "),
                                         sign == Sign::positive       ? ", each > 0"
                                         : sign == Sign::non_negative ? ", each >= 0"
                                                                      : "",
                                         unit.empty() ? "" : " (" + unit + ")");
    if (!field.node.IsSequence() || field.node.size() != N) expected(field, what);
    std::array<double, N> values{};
    for (std::size_t i = 0; i < N; ++i)
      values[i] = number(child(field, field.node[i], fmt::format("{}[{}]", field.key, i)), sign, unit);
    return values;
  }

  Expression expression(const Field& field) const {
    const std::string what = "a number or a muparser expression of t";
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
    const std::string written = text(field, "a file path");
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
  std::vector<Field> items(const Field& field, const std::string& what) const {
    std::vector<Field> out;
    if (field.node.IsNull()) return out;
    if (!field.node.IsSequence()) expected(field, what);
    for (std::size_t i = 0; i < field.node.size(); ++i)
      out.push_back(child(field, field.node[i], fmt::format("{}[{}]", field.key, i)));
    return out;
  }

  /// A list of distinct words from the vocabulary, in the file's order.
  std::vector<std::string> word_set(const Field& field, const std::vector<std::string>& words) const {
    std::vector<std::string> chosen;
    for (const Field& item : items(field, "a list of " + join(words, ", "))) {
      const std::string& choice = words[word(item, words)];
      if (std::find(chosen.begin(), chosen.end(), choice) != chosen.end())
        expected(item, "each of " + join(words, ", ") + " at most once");
      chosen.push_back(choice);
    }
    return chosen;
  }

  const std::filesystem::path& folder() const { return folder_; }

 private:
  std::string file_;
  std::filesystem::path folder_;
};

MapFields::MapFields(const Loader& loader, const Field& map, const std::vector<std::string>& allowed)
    : loader_(loader), self_(map) {
  if (map.node.IsNull()) return;
  if (!map.node.IsMap()) loader.expected(map, "a map with the keys " + join(allowed, ", "));
  for (auto it = map.node.begin(); it != map.node.end(); ++it) {
    const YAML::Node key = it->first;
    const int key_line = line_of(key, map.line);
    if (!key.IsScalar()) loader.fail(Field{key, map.key, key_line}, "a key name expected, got " + shown(key));
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

Field MapFields::require(const std::string& name, const std::string& what) const {
  if (auto field = get(name)) return *field;
  loader_.fail(Field{self_.node, path(name), self_.line}, what + " expected (required), got nothing");
}

std::string axis_name(std::size_t axis) {
  return std::string(1, "xyz"[axis]);
}

// --- sections --------------------------------------------------------------------------------------------

void read_time(const Loader& loader, const Field& field, TimeSettings& time) {
  const MapFields map(loader, field, {"end", "dt", "cfl"});
  time.end = loader.number(map.require("end", "a number > 0 (s)"), Sign::positive, "s");
  if (const auto dt = map.get("dt")) {
    if (!(dt->node.IsScalar() && dt->node.Scalar() == "auto")) {
      if (!dt->node.IsScalar() || !parse_double(dt->node.Scalar()) ||
          !(*parse_double(dt->node.Scalar()) > 0.0))
        loader.expected(*dt, "a number > 0 (s) or auto");
      time.dt = *parse_double(dt->node.Scalar());
    }
  }
  if (const auto cfl = map.get("cfl")) time.cfl = loader.number(*cfl, Sign::positive);
}

void read_domain(const Loader& loader, const Field& field, DomainSettings& domain) {
  const MapFields map(loader, field, {"origin", "size", "cell_size"});
  if (const auto origin = map.get("origin")) domain.origin = loader.vector<3>(*origin, Sign::any, "m");
  const Field size = map.require("size", "a list of 3 numbers [x, y, z] (m)");
  domain.size = loader.vector<3>(size, Sign::positive, "m");
  domain.cell_size = loader.number(map.require("cell_size", "a number > 0 (m)"), Sign::positive, "m");
  double total = 1.0;
  for (std::size_t axis = 0; axis < 3; ++axis) {
    const double cells = domain.size[axis] / domain.cell_size;
    const double whole = std::round(cells);
    if (whole < 1.0 || std::abs(whole * domain.cell_size - domain.size[axis]) > 1e-6 * domain.size[axis]) {
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
  if (!(total < std::numeric_limits<double>::infinity()) || faces > 2147483647.0) {
    loader.expected(map.require("cell_size", ""),
                    fmt::format("a cell size giving (nx + 1)(ny + 1)(nz + 1) <= 2^31 - 1 (size / cell_size "
                                "gives {:.3g} cells)",
                                total));
  }
}

void read_boundaries(const Loader& loader, const Field& field, Scenario& scenario) {
  const std::vector<std::string> faces = {"west", "east", "south", "north", "ground", "top"};
  const MapFields map(loader, field, faces);
  const std::vector<std::string> side_words = {"auto", "inflow", "outflow", "slip", "no_slip", "periodic"};
  const std::vector<std::string> cap_words = {"inflow", "outflow", "slip", "no_slip", "periodic"};
  std::array<std::optional<Field>, 6> given;
  for (int face = 0; face < 6; ++face) {
    given[face] = map.get(faces[face]);
    if (!given[face]) continue;
    // "auto" follows the horizontal wind, which never crosses the ground or the top.
    const bool side = face < 4;
    const std::size_t index = loader.word(*given[face], side ? side_words : cap_words);
    scenario.boundaries[face] = BoundaryChoice(side ? index : index + 1);
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

void check_time_series(const Loader& loader, const Field& field, const Expression& expression, double end,
                       bool non_negative) {
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

void read_wind(const Loader& loader, const Field& field, Scenario& scenario) {
  WindSource& wind = scenario.wind;
  const MapFields map(loader, field, {"speed", "direction", "reference_height", "profile"});
  const Field speed = map.require("speed", "a number or a muparser expression of t (m/s)");
  wind.speed = loader.expression(speed);
  check_time_series(loader, speed, wind.speed, scenario.time.end, true);
  const Field direction = map.require("direction", "a number or a muparser expression of t (degrees)");
  wind.direction = loader.expression(direction);
  check_time_series(loader, direction, wind.direction, scenario.time.end, false);
  if (const auto height = map.get("reference_height"))
    wind.reference_height = loader.number(*height, Sign::positive, "m");

  wind.profile = fluid::InflowProfile{};
  wind.profile.type = fluid::InflowProfile::Type::uniform;
  wind.profile.alpha = 0.2;
  wind.profile.displacement_height = 0.0;
  wind.profile.reference_height = wind.reference_height;
  if (const auto profile_field = map.get("profile")) {
    // The allowed keys depend on the type, so read the type first.
    const MapFields any(loader, *profile_field, {"type", "alpha", "roughness_length", "displacement_height"});
    const std::size_t type =
        loader.word(any.require("type", "one of uniform | power | log"), {"uniform", "power", "log"});
    if (type == 0) {
      const MapFields profile(loader, *profile_field, {"type"});
    } else if (type == 1) {
      const MapFields profile(loader, *profile_field, {"type", "alpha"});
      wind.profile.type = fluid::InflowProfile::Type::power;
      if (const auto alpha = profile.get("alpha"))
        wind.profile.alpha = loader.number(*alpha, Sign::non_negative);
    } else {
      const MapFields profile(loader, *profile_field, {"type", "roughness_length", "displacement_height"});
      wind.profile.type = fluid::InflowProfile::Type::log;
      wind.profile.roughness_length =
          loader.number(profile.require("roughness_length", "a number > 0 (m)"), Sign::positive, "m");
      const auto displacement = profile.get("displacement_height");
      if (displacement)
        wind.profile.displacement_height = loader.number(*displacement, Sign::non_negative, "m");
      // The log law is only defined above d + z0, and the reference height is where it equals `speed`.
      const double floor = wind.profile.displacement_height + wind.profile.roughness_length;
      if (!(wind.reference_height > floor)) {
        loader.expected(
            displacement ? *displacement : profile.require("roughness_length", ""),
            fmt::format(
                "displacement_height + roughness_length (now {} m) below wind.reference_height ({} m)", floor,
                wind.reference_height));
      }
    }
  }
}

void read_events(const Loader& loader, const Field& field, Scenario& scenario) {
  for (const Field& item : loader.items(field, "a list of events (- gust: {...})")) {
    const MapFields kind(loader, item, {"gust"});
    const MapFields map(loader, kind.require("gust", "a gust map"),
                        {"start", "duration", "peak_speed", "center", "radius", "travel"});
    GustEvent gust;
    gust.start = loader.number(map.require("start", "a number >= 0 (s)"), Sign::non_negative, "s");
    gust.duration = loader.number(map.require("duration", "a number > 0 (s)"), Sign::positive, "s");
    gust.peak_speed =
        loader.number(map.require("peak_speed", "a number >= 0 (m/s)"), Sign::non_negative, "m/s");
    gust.center =
        loader.vector<3>(map.require("center", "a list of 3 numbers [x, y, z] (m)"), Sign::any, "m");
    gust.radius = loader.number(map.require("radius", "a number > 0 (m)"), Sign::positive, "m");
    gust.travel_with_wind = true;
    if (const auto travel = map.get("travel")) {
      if (travel->node.IsSequence()) {
        gust.travel_with_wind = false;
        gust.travel = loader.vector<3>(*travel, Sign::any, "m/s");
      } else if (!(travel->node.IsScalar() && travel->node.Scalar() == "with_wind")) {
        loader.expected(*travel, "with_wind or a list of 3 numbers [vx, vy, vz] (m/s)");
      }
    }
    if (gust.travel_with_wind) gust.travel = scenario.wind_vector(gust.start);
    scenario.events.push_back(gust);
  }
}

void read_obstacles(const Loader& loader, const Field& field, Scenario& scenario) {
  for (const Field& item : loader.items(field, "a list of obstacles (- box|cylinder|sphere: {...})")) {
    const MapFields kind(loader, item, {"box", "cylinder", "sphere"});
    if (kind.size() != 1) loader.expected(item, "a map with exactly one of the keys box, cylinder, sphere");
    const std::string shape = kind.given().front();
    const Field body = *kind.get(shape);
    if (shape == "box") {
      const MapFields map(loader, body, {"name", "center", "size", "yaw"});
      fluid::SolidBox box;
      box.name = loader.text(map.require("name", "a name"), "a name");
      box.center =
          loader.vector<3>(map.require("center", "a list of 3 numbers [x, y, z] (m)"), Sign::any, "m");
      box.size =
          loader.vector<3>(map.require("size", "a list of 3 numbers [x, y, z] (m)"), Sign::positive, "m");
      if (const auto yaw = map.get("yaw")) box.yaw_deg = loader.number(*yaw, Sign::any, "degrees");
      scenario.obstacles.emplace_back(box);
    } else if (shape == "cylinder") {
      const MapFields map(loader, body, {"name", "base", "radius", "height"});
      fluid::SolidCylinder cylinder;
      cylinder.name = loader.text(map.require("name", "a name"), "a name");
      cylinder.base =
          loader.vector<3>(map.require("base", "a list of 3 numbers [x, y, z] (m)"), Sign::any, "m");
      cylinder.radius = loader.number(map.require("radius", "a number > 0 (m)"), Sign::positive, "m");
      cylinder.height = loader.number(map.require("height", "a number > 0 (m)"), Sign::positive, "m");
      scenario.obstacles.emplace_back(cylinder);
    } else {
      const MapFields map(loader, body, {"name", "center", "radius"});
      fluid::SolidSphere sphere;
      sphere.name = loader.text(map.require("name", "a name"), "a name");
      sphere.center =
          loader.vector<3>(map.require("center", "a list of 3 numbers [x, y, z] (m)"), Sign::any, "m");
      sphere.radius = loader.number(map.require("radius", "a number > 0 (m)"), Sign::positive, "m");
      scenario.obstacles.emplace_back(sphere);
    }
  }
}

void read_terrain(const Loader& loader, const Field& field, Scenario& scenario) {
  const MapFields map(loader, field, {"heightmap", "cell_size", "max_height"});
  TerrainSettings terrain;
  const Field heightmap = map.require("heightmap", "a file path (PGM or ESRI ASCII grid)");
  terrain.heightmap = loader.readable_file(heightmap);
  // The format comes from the content (fluid/Heightmap.hpp); cell size and height scale matter for PGM only.
  char magic[2] = {0, 0};
  std::ifstream(terrain.heightmap, std::ios::binary).read(magic, 2);
  const bool pgm = magic[0] == 'P' && (magic[1] == '2' || magic[1] == '5');
  const auto cell_size = map.get("cell_size");
  const auto max_height = map.get("max_height");
  if (cell_size) terrain.cell_size = loader.number(*cell_size, Sign::positive, "m");
  if (max_height) terrain.max_height = loader.number(*max_height, Sign::non_negative, "m");
  if (pgm && !cell_size) map.require("cell_size", "a number > 0 (m), needed for a PGM heightmap");
  if (pgm && !max_height) map.require("max_height", "a number >= 0 (m), needed for a PGM heightmap");
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
  const std::string name = loader.text(field, "a species name");
  for (std::size_t i = 0; i < species.size(); ++i)
    if (species[i].name == name) return int(i);
  std::vector<std::string> names;
  for (const Species& s : species) names.push_back(s.name);
  loader.expected(field, names.empty() ? std::string("a species name (forest.species is empty)")
                                       : "a species name, one of " + join(names, ", "));
}

// global_seed + 1 + its index seeds a species' generator unless the file gives a seed.
Species read_species(const Loader& loader, const Field& item, const std::vector<Species>& earlier,
                     std::uint64_t global_seed) {
  const MapFields map(loader, item, {"name", "skeleton", "material", "modes", "drag_coefficient", "canopy"});
  Species species;
  species.modes.count_line = item.line;
  const Field name = map.require("name", "a species name");
  species.name = loader.text(name, "a species name");
  for (const Species& other : earlier)
    if (other.name == species.name) loader.expected(name, "a species name not used before");

  const Field skeleton_field = map.require("skeleton", "a map with one of generate, file, qsm");
  const MapFields skeleton(loader, skeleton_field, {"generate", "file", "qsm"});
  if (skeleton.size() != 1) {
    loader.fail(skeleton_field,
                fmt::format("exactly one of generate, file, qsm expected, got {}",
                            skeleton.size() == 0 ? std::string("none") : join(skeleton.given(), " and ")));
  }
  const std::string source = skeleton.given().front();
  const Field body = *skeleton.get(source);
  if (source == "generate") {
    species.skeleton.kind = SkeletonSource::Kind::generate;
    const MapFields generate(loader, body, {"preset", "height", "seed"});
    const std::vector<std::string> presets = trees::preset_names();
    species.skeleton.generate.preset =
        presets[loader.word(generate.require("preset", "one of " + join(presets, " | ")), presets)];
    if (const auto height = generate.get("height"))
      species.skeleton.generate.height = loader.number(*height, Sign::non_negative, "m");
    species.skeleton.generate.seed = global_seed + 1 + earlier.size();
    if (const auto seed = generate.get("seed")) species.skeleton.generate.seed = loader.seed(*seed);
  } else {
    species.skeleton.kind = source == "file" ? SkeletonSource::Kind::file : SkeletonSource::Kind::qsm;
    species.skeleton.path = loader.readable_file(body);
  }

  if (const auto material_field = map.get("material")) {
    const MapFields material(loader, *material_field, {"youngs_modulus", "shear_modulus", "density"});
    if (const auto e = material.get("youngs_modulus"))
      species.material.youngs_modulus = loader.number(*e, Sign::positive, "Pa");
    if (const auto g = material.get("shear_modulus"))
      species.material.shear_modulus = loader.number(*g, Sign::positive, "Pa");
    if (const auto rho = material.get("density"))
      species.material.density = loader.number(*rho, Sign::positive, "kg/m^3");
  }
  if (const auto modes_field = map.get("modes")) {
    const MapFields modes(loader, *modes_field, {"count", "damping_ratio", "wind_samples"});
    if (const auto count = modes.get("count")) {
      species.modes.count = loader.integer(*count, 1, std::numeric_limits<int>::max());
      species.modes.count_line = count->line;
    }
    if (const auto zeta = modes.get("damping_ratio"))
      species.modes.damping_ratio = loader.number(*zeta, Sign::non_negative);
    if (const auto samples = modes.get("wind_samples"))
      species.modes.wind_samples = loader.integer(*samples, 1, FW_MAX_TREE_SAMPLES);
  }
  if (const auto drag = map.get("drag_coefficient"))
    species.drag_coefficient = loader.number(*drag, Sign::non_negative);
  if (const auto canopy_field = map.get("canopy")) {
    const MapFields canopy(loader, *canopy_field, {"leaf_area_index", "drag_coefficient"});
    if (const auto lai = canopy.get("leaf_area_index"))
      species.canopy.leaf_area_index = loader.number(*lai, Sign::non_negative, "m^2/m^2");
    if (const auto drag = canopy.get("drag_coefficient"))
      species.canopy.drag_coefficient = loader.number(*drag, Sign::non_negative);
  }
  return species;
}

Vec2 region_corner(const Loader& loader, const Field& field, const DomainSettings& domain) {
  const Vec2 corner = loader.vector<2>(field, Sign::any, "m");
  const Vec3 top = domain.max_corner();
  if (!inside(corner[0], domain.origin[0], top[0]) || !inside(corner[1], domain.origin[1], top[1]))
    loader.expected(field,
                    "a point [x, y] inside the domain's horizontal extent " + horizontal_extent(domain));
  return corner;
}

Stand read_stand(const Loader& loader, const Field& item, const Scenario& scenario) {
  const MapFields map(loader, item, {"species", "region", "layout", "spacing", "scale", "seed"});
  Stand stand;
  const Field species = map.require("species", "a species name");
  stand.layout.species = species_index(loader, species, scenario.forest.species);
  stand.species = scenario.forest.species[stand.layout.species].name;

  const MapFields region(loader, map.require("region", "a map {min: [x, y], max: [x, y]} (m)"),
                         {"min", "max"});
  const Vec2 min =
      region_corner(loader, region.require("min", "a list of 2 numbers [x, y] (m)"), scenario.domain);
  const Field max_field = region.require("max", "a list of 2 numbers [x, y] (m)");
  const Vec2 max = region_corner(loader, max_field, scenario.domain);
  if (!(max[0] > min[0]) || !(max[1] > min[1]))
    loader.expected(max_field,
                    fmt::format("a point north-east of min [{}, {}] (x and y both larger)", min[0], min[1]));
  stand.layout.min = {min[0], min[1]};
  stand.layout.max = {max[0], max[1]};

  if (const auto layout = map.get("layout"))
    stand.layout.layout = loader.word(*layout, {"poisson", "grid"}) == 0 ? trees::StandLayout::poisson
                                                                         : trees::StandLayout::grid;
  const Field spacing = map.require("spacing", "a number > 0 (m)");
  stand.layout.spacing = loader.number(spacing, Sign::positive, "m");
  stand.layout.scale_min = stand.layout.scale_max = 1.0;
  if (const auto scale_field = map.get("scale")) {
    const MapFields scale(loader, *scale_field, {"min", "max"});
    if (const auto low = scale.get("min")) stand.layout.scale_min = loader.number(*low, Sign::positive);
    if (const auto high = scale.get("max")) {
      stand.layout.scale_max = loader.number(*high, Sign::positive);
      if (stand.layout.scale_max < stand.layout.scale_min)
        loader.expected(*high, fmt::format("a number >= scale.min ({})", stand.layout.scale_min));
    } else if (stand.layout.scale_max < stand.layout.scale_min) {
      loader.expected(*scale.get("min"), "a number <= scale.max (1, the default)");
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
  const MapFields map(loader, item, {"species", "position", "yaw", "scale"});
  PlacedTreeSettings tree;
  tree.species_index =
      species_index(loader, map.require("species", "a species name"), scenario.forest.species);
  tree.species = scenario.forest.species[tree.species_index].name;

  const Field position = map.require("position", "a list [x, y] or [x, y, z] (m)");
  if (!position.node.IsSequence() || (position.node.size() != 2 && position.node.size() != 3))
    loader.expected(position, "a list [x, y] or [x, y, z] (m)");
  for (std::size_t i = 0; i < position.node.size(); ++i) {
    tree.position[i] = loader.number(
        loader.child(position, position.node[i], fmt::format("{}[{}]", position.key, i)), Sign::any, "m");
  }
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
  if (const auto yaw = map.get("yaw")) tree.yaw = loader.number(*yaw, Sign::any, "degrees");
  if (const auto scale = map.get("scale")) tree.scale = loader.number(*scale, Sign::positive);
  return tree;
}

void read_forest(const Loader& loader, const Field& field, Scenario& scenario) {
  const MapFields map(loader, field, {"two_way_coupling", "integrator", "species", "stands", "trees"});
  ForestSettings& forest = scenario.forest;
  if (const auto coupling = map.get("two_way_coupling")) forest.two_way_coupling = loader.boolean(*coupling);
  if (const auto integrator = map.get("integrator")) {
    forest.integrator = loader.word(*integrator, {"exact", "semi_implicit"}) == 0
                            ? trees::ModalIntegrator::exact
                            : trees::ModalIntegrator::semi_implicit;
  }
  if (const auto species = map.get("species"))
    for (const Field& item : loader.items(*species, "a list of species"))
      forest.species.push_back(read_species(loader, item, forest.species, scenario.seed));
  if (const auto stands = map.get("stands"))
    for (const Field& item : loader.items(*stands, "a list of stands"))
      forest.stands.push_back(read_stand(loader, item, scenario));
  if (const auto trees = map.get("trees"))
    for (const Field& item : loader.items(*trees, "a list of trees"))
      forest.trees.push_back(read_tree(loader, item, scenario));
}

void read_solver(const Loader& loader, const Field& field, SolverSettings& solver) {
  const MapFields map(
      loader, field,
      {"pressure", "tolerance", "max_iterations", "jacobi_iterations", "advection", "vorticity_confinement"});
  if (const auto pressure = map.get("pressure")) {
    const fluid::PressureSolverType solvers[] = {fluid::PressureSolverType::multigrid,
                                                 fluid::PressureSolverType::cg,
                                                 fluid::PressureSolverType::jacobi};
    solver.pressure = solvers[loader.word(*pressure, {"multigrid", "cg", "jacobi"})];
  }
  if (const auto tolerance = map.get("tolerance"))
    solver.tolerance = loader.number(*tolerance, Sign::positive);
  if (const auto iterations = map.get("max_iterations"))
    solver.max_iterations = loader.integer(*iterations, 1, std::numeric_limits<int>::max());
  if (const auto iterations = map.get("jacobi_iterations"))
    solver.jacobi_iterations = loader.integer(*iterations, 1, std::numeric_limits<int>::max());
  if (const auto advection = map.get("advection"))
    solver.advection = loader.word(*advection, {"semi_lagrangian", "maccormack"}) == 0
                           ? fluid::AdvectionScheme::semi_lagrangian
                           : fluid::AdvectionScheme::maccormack;
  if (const auto epsilon = map.get("vorticity_confinement"))
    solver.vorticity_confinement = loader.number(*epsilon, Sign::non_negative);
}

bool probe_name(const std::string& name) {
  return !name.empty() && std::all_of(name.begin(), name.end(), [](unsigned char c) {
    return (c >= 'A' && c <= 'Z') || (c >= 'a' && c <= 'z') || (c >= '0' && c <= '9') || c == '_';
  });
}

void read_output(const Loader& loader, const Field& field, Scenario& scenario) {
  OutputSettings& output = scenario.output;
  const MapFields map(loader, field, {"directory", "interval", "vtk", "vdb", "probes"});
  std::filesystem::path directory = std::filesystem::path("out") / scenario.name;
  if (const auto given = map.get("directory")) directory = loader.text(*given, "a directory path");
  // Against the working directory, not the scenario folder: a run writes where it is started.
  output.directory = std::filesystem::absolute(directory).lexically_normal();
  if (const auto interval = map.get("interval"))
    output.interval = loader.number(*interval, Sign::positive, "s");
  if (const auto vtk_field = map.get("vtk")) {
    const MapFields vtk(loader, *vtk_field, {"wind", "trees", "fields"});
    if (const auto wind = vtk.get("wind")) output.vtk_wind = loader.boolean(*wind);
    if (const auto trees = vtk.get("trees")) output.vtk_trees = loader.boolean(*trees);
    if (const auto fields = vtk.get("fields"))
      output.vtk_fields =
          loader.word_set(*fields, {"velocity", "pressure", "speed", "vorticity", "solid", "canopy_density"});
  }
  if (const auto vdb_field = map.get("vdb")) {
    const MapFields vdb(loader, *vdb_field, {"enabled", "grids"});
    if (const auto enabled = vdb.get("enabled")) output.vdb_enabled = loader.boolean(*enabled);
    if (const auto grids = vdb.get("grids")) output.vdb_grids = loader.word_set(*grids, {"vel", "speed"});
  }
  if (const auto probes = map.get("probes")) {
    for (const Field& item : loader.items(*probes, "a list of probes")) {
      const MapFields probe_map(loader, item, {"name", "position"});
      Probe probe;
      const Field name = probe_map.require("name", "a probe name");
      probe.name = loader.text(name, "a probe name");
      if (!probe_name(probe.name)) loader.expected(name, "a probe name of letters, digits and _");
      for (const Probe& other : output.probes)
        if (other.name == probe.name) loader.expected(name, "a probe name not used before");
      const Field position = probe_map.require("position", "a list of 3 numbers [x, y, z] (m)");
      probe.position = loader.vector<3>(position, Sign::any, "m");
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
  if (!root.node.IsMap()) loader.expected(root, "a map of scenario keys (scenario, time, domain, wind, ...)");
  const MapFields top(loader, root,
                      {"scenario", "seed", "time", "domain", "boundaries", "wind", "events", "obstacles",
                       "terrain", "forest", "solver", "output"});

  const Field scenario_name = top.require("scenario", "a scenario name");
  scenario.name = loader.text(scenario_name, "a scenario name");
  if (scenario.name.find_first_of("/\\") != std::string::npos || scenario.name == "." ||
      scenario.name == ".." ||
      std::any_of(scenario.name.begin(), scenario.name.end(), [](unsigned char c) { return c < 0x20; })) {
    // The name becomes a folder name (out/<scenario>).
    loader.expected(scenario_name, "a scenario name usable as a folder name (no / or \\, not . or ..)");
  }
  if (const auto seed = top.get("seed")) scenario.seed = loader.seed(*seed);
  read_time(loader, top.require("time", "a map {end, dt, cfl}"), scenario.time);
  read_domain(loader, top.require("domain", "a map {origin, size, cell_size}"), scenario.domain);
  if (const auto boundaries = top.get("boundaries")) read_boundaries(loader, *boundaries, scenario);
  read_wind(loader, top.require("wind", "a map {speed, direction, reference_height, profile}"), scenario);
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
