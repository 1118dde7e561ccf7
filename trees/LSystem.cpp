#include "trees/LSystem.hpp"

#include <fmt/format.h>

#include <Eigen/Geometry>

#include <algorithm>
#include <cmath>
#include <numbers>
#include <random>
#include <stdexcept>

#include "base/TextNumber.hpp"

namespace fw::trees {

namespace {

using ModuleTemplate = LSystem::ModuleTemplate;
using ParameterTemplate = LSystem::ParameterTemplate;

[[noreturn]] void fail(std::string_view text, std::string_view what) {
  throw std::invalid_argument(fmt::format("LSystem: \"{}\": {}", text, what));
}

double parse_number(std::string_view text, std::string_view number) {
  const std::optional<double> value = base::parse_finite(number);
  if (!value) fail(text, fmt::format("expected a number, got \"{}\"", number));
  return *value;
}

// EXPR of a successor module: VALUE | p | p*VALUE | VALUE*p, optionally followed by ~S.
ParameterTemplate parse_parameter(std::string_view text, std::string_view expr, bool allow_predecessor,
                                  bool allow_jitter) {
  ParameterTemplate parameter;
  std::string_view main = expr;
  if (const auto tilde = expr.find('~'); tilde != std::string_view::npos) {
    if (!allow_jitter) fail(text, "a word takes literal parameters only, no ~");
    main = expr.substr(0, tilde);
    parameter.jitter = parse_number(text, expr.substr(tilde + 1));
    if (!(parameter.jitter >= 0.0 && parameter.jitter < 1.0))
      fail(text, fmt::format("expected a jitter ~S with 0 <= S < 1, got {}", parameter.jitter));
  }
  const bool starts_p = main.starts_with("p");
  const bool ends_p = main.ends_with("p");
  if (starts_p || ends_p) {
    if (!allow_predecessor) fail(text, "there is no predecessor parameter p here");
    parameter.kind = ParameterTemplate::Kind::scaled_predecessor;
    if (main == "p") {
      parameter.value = 1.0;
    } else if (starts_p && main.size() > 2 && main[1] == '*') {
      parameter.value = parse_number(text, main.substr(2));
    } else if (ends_p && main.size() > 2 && main[main.size() - 2] == '*') {
      parameter.value = parse_number(text, main.substr(0, main.size() - 2));
    } else {
      fail(text, fmt::format("expected p, p*VALUE or VALUE*p, got \"{}\"", main));
    }
  } else {
    parameter.kind = ParameterTemplate::Kind::literal;
    parameter.value = parse_number(text, main);
  }
  return parameter;
}

std::vector<ModuleTemplate> parse_modules(std::string_view text, bool allow_predecessor, bool allow_jitter) {
  std::string compact;  // white space is insignificant
  for (char c : text)
    if (!std::isspace(static_cast<unsigned char>(c))) compact += c;
  std::vector<ModuleTemplate> modules;
  int depth = 0;
  for (std::size_t i = 0; i < compact.size(); ++i) {
    const char symbol = compact[i];
    if (symbol == '(' || symbol == ')') fail(text, fmt::format("unexpected '{}' at character {}", symbol, i));
    ModuleTemplate module{symbol, {}};
    if (symbol == '[') ++depth;
    if (symbol == ']' && --depth < 0) fail(text, "']' without a matching '['");
    if (i + 1 < compact.size() && compact[i + 1] == '(') {
      if (symbol == '[' || symbol == ']') fail(text, "brackets take no parameter");
      const auto close = compact.find(')', i + 2);
      if (close == std::string::npos) fail(text, "'(' without a matching ')'");
      module.parameter = parse_parameter(text, std::string_view(compact).substr(i + 2, close - i - 2),
                                         allow_predecessor, allow_jitter);
      i = close;
    }
    modules.push_back(module);
  }
  if (depth != 0) fail(text, "'[' without a matching ']'");
  return modules;
}

// A random number source shared by a whole derivation, drawn in string order.
class UniformStream {
 public:
  explicit UniformStream(std::uint64_t seed) : engine_(seed) {}
  double next() { return unit_interval(engine_()); }

 private:
  std::mt19937_64 engine_;  // its output sequence is fixed by the standard, unlike the distributions
};

void append_successor(std::span<const ModuleTemplate> successor, double predecessor_parameter,
                      UniformStream& random, std::vector<Module>& out) {
  for (const ModuleTemplate& t : successor) {
    Module module{t.symbol, std::numeric_limits<double>::quiet_NaN()};
    const ParameterTemplate& p = t.parameter;
    if (p.kind != ParameterTemplate::Kind::none) {
      double value = p.kind == ParameterTemplate::Kind::literal ? p.value : p.value * predecessor_parameter;
      if (p.jitter > 0.0) value *= 1.0 + p.jitter * (2.0 * random.next() - 1.0);
      module.parameter = value;
    }
    out.push_back(module);
  }
}

// --- turtle ---------------------------------------------------------------------------------------------

struct TurtleState {
  Eigen::Vector3d position = Eigen::Vector3d::Zero();
  Eigen::Vector3d heading = Eigen::Vector3d::UnitZ();
  Eigen::Vector3d left = -Eigen::Vector3d::UnitY();
  Eigen::Vector3d up = Eigen::Vector3d::UnitX();  // = heading x left
  double tropism = 0.0;
  int order = 0;
  int segment = -1;
  bool stopped = false;  // the branch hit the ground: nothing more grows in this bracket
};

// Rotates the pair (a, b) by angle in their plane, turning a toward b.
void rotate_pair(Eigen::Vector3d& a, Eigen::Vector3d& b, double angle_rad) {
  const double c = std::cos(angle_rad), s = std::sin(angle_rad);
  const Eigen::Vector3d a_new = c * a + s * b;
  b = c * b - s * a;
  a = a_new;
}

// Gram-Schmidt, so that thousands of rotations do not let the frame drift from orthonormal.
void reorthonormalize(TurtleState& t) {
  t.heading.normalize();
  t.left = (t.left - t.left.dot(t.heading) * t.heading).normalized();
  t.up = t.heading.cross(t.left);
}

void bend_toward(TurtleState& t, const Eigen::Vector3d& direction) {
  if (t.tropism == 0.0) return;
  const Eigen::Vector3d axis = t.heading.cross(direction);
  const double sin_phi = axis.norm();
  if (sin_phi < 1e-12) return;  // already along (or exactly against) the tropism direction
  const double phi = std::atan2(sin_phi, t.heading.dot(direction));  // angle from H to T
  const double alpha = std::clamp(t.tropism * sin_phi, phi - std::numbers::pi, phi);
  const Eigen::AngleAxisd rotation(alpha, axis / sin_phi);
  t.heading = rotation * t.heading;
  t.left = rotation * t.left;
  reorthonormalize(t);
}

double angle_or_default(const Module& m, const TurtleSettings& settings) {
  const double degrees = m.has_parameter() ? m.parameter : settings.angle_deg;
  if (!std::isfinite(degrees))
    throw std::invalid_argument(fmt::format("LSystem: turtle: '{}' with a non-finite angle", m.symbol));
  return degrees * (std::numbers::pi / 180.0);
}

}  // namespace

std::string to_string(std::span<const Module> word) {
  std::string text;
  for (const Module& m : word) {
    text += m.symbol;
    if (m.has_parameter()) text += fmt::format("({:g})", m.parameter);
  }
  return text;
}

std::vector<Module> parse_word(std::string_view text) {
  std::vector<Module> word;
  for (const ModuleTemplate& t : parse_modules(text, /*allow_predecessor=*/false, /*allow_jitter=*/false)) {
    word.push_back({t.symbol, t.parameter.kind == ParameterTemplate::Kind::none
                                  ? std::numeric_limits<double>::quiet_NaN()
                                  : t.parameter.value});
  }
  return word;
}

LSystem::LSystem(std::string_view axiom) : rules_(256) {
  axiom_ = parse_modules(axiom, /*allow_predecessor=*/false, /*allow_jitter=*/true);
}

void LSystem::add_rule(char symbol, std::string_view successor, double weight) {
  if (symbol == '[' || symbol == ']' || symbol == '(' || symbol == ')')
    throw std::invalid_argument(fmt::format("LSystem: '{}' cannot be rewritten", symbol));
  if (!(std::isfinite(weight) && weight > 0.0))
    throw std::invalid_argument(
        fmt::format("LSystem: rule for '{}': expected a weight > 0, got {}", symbol, weight));
  rules_[static_cast<unsigned char>(symbol)].push_back(
      {weight, parse_modules(successor, /*allow_predecessor=*/true, /*allow_jitter=*/true)});
}

std::vector<Module> LSystem::derive(int iterations, std::uint64_t seed) const {
  if (iterations < 0)
    throw std::invalid_argument(fmt::format("LSystem: expected iterations >= 0, got {}", iterations));
  UniformStream random(seed);
  std::vector<Module> word;
  append_successor(axiom_, 1.0, random, word);
  std::vector<Module> next;
  for (int iteration = 0; iteration < iterations; ++iteration) {
    next.clear();
    for (const Module& m : word) {
      const auto& alternatives = rules_[static_cast<unsigned char>(m.symbol)];
      if (alternatives.empty()) {
        next.push_back(m);
        continue;
      }
      std::size_t chosen = 0;
      if (alternatives.size() > 1) {
        double total = 0.0;
        for (const Alternative& a : alternatives) total += a.weight;
        double remaining = random.next() * total;
        // Walk the cumulative weights; the last alternative also catches rounding at the top end.
        while (chosen + 1 < alternatives.size() && remaining >= alternatives[chosen].weight)
          remaining -= alternatives[chosen++].weight;
      }
      append_successor(alternatives[chosen].successor, m.has_parameter() ? m.parameter : 1.0, random, next);
      if (next.size() > kMaxWordLength)
        throw std::length_error(fmt::format("LSystem: the word after {} iterations would exceed {} modules",
                                            iteration + 1, kMaxWordLength));
    }
    word.swap(next);
  }
  return word;
}

std::vector<BranchSegment> interpret(std::span<const Module> word, const TurtleSettings& settings) {
  const double tropism_norm = settings.tropism_direction.norm();
  if (!(tropism_norm > 0.0) || !std::isfinite(tropism_norm))
    throw std::invalid_argument("LSystem: turtle: the tropism direction must be a finite non-zero vector");
  const Eigen::Vector3d tropism_direction = settings.tropism_direction / tropism_norm;

  std::vector<BranchSegment> segments;
  std::vector<TurtleState> stack;
  TurtleState t;
  t.tropism = settings.tropism;
  for (const Module& m : word) {
    switch (m.symbol) {
      case 'F': {
        const double length = m.has_parameter() ? m.parameter : settings.step_length;
        if (!std::isfinite(length))
          throw std::invalid_argument("LSystem: turtle: 'F' with a non-finite length");
        if (t.stopped || length == 0.0) break;
        bend_toward(t, tropism_direction);
        const Eigen::Vector3d end = t.position + length * t.heading;
        if (end.z() < settings.ground_z) {
          t.stopped = true;
          break;
        }
        const int id = int(segments.size());
        segments.push_back({id, t.segment, t.order, t.position, end});
        t.segment = id;
        t.position = end;
        break;
      }
      case '+':
        rotate_pair(t.heading, t.left, angle_or_default(m, settings));
        reorthonormalize(t);
        break;
      case '-':
        rotate_pair(t.heading, t.left, -angle_or_default(m, settings));
        reorthonormalize(t);
        break;
      case '&':
        rotate_pair(t.heading, t.up, -angle_or_default(m, settings));  // H toward -U
        reorthonormalize(t);
        break;
      case '^':
        rotate_pair(t.heading, t.up, angle_or_default(m, settings));
        reorthonormalize(t);
        break;
      case '\\':
        rotate_pair(t.left, t.up, angle_or_default(m, settings));
        reorthonormalize(t);
        break;
      case '/':
        rotate_pair(t.left, t.up, -angle_or_default(m, settings));
        reorthonormalize(t);
        break;
      case '|':
        rotate_pair(t.heading, t.left, std::numbers::pi);
        reorthonormalize(t);
        break;
      case '$': {
        const Eigen::Vector3d horizontal = Eigen::Vector3d::UnitZ().cross(t.heading);
        if (horizontal.norm() < 1e-12) break;  // vertical heading: every roll is level
        t.left = horizontal.normalized();
        t.up = t.heading.cross(t.left);
        break;
      }
      case 'T': {
        const double e = m.has_parameter() ? m.parameter : settings.tropism;
        if (!std::isfinite(e)) throw std::invalid_argument("LSystem: turtle: 'T' with a non-finite value");
        t.tropism = e;
        break;
      }
      case '[':
        stack.push_back(t);
        ++t.order;
        break;
      case ']':
        if (stack.empty()) throw std::invalid_argument("LSystem: turtle: ']' without a matching '['");
        t = stack.back();
        stack.pop_back();
        break;
      default:
        break;  // apices, leaves and other markers draw nothing
    }
  }
  if (!stack.empty()) throw std::invalid_argument("LSystem: turtle: '[' without a matching ']'");
  return segments;
}

}  // namespace fw::trees
