// A stochastic, parametric, bracketed L-system and the 3D turtle that turns its string into branch segments.
//
//   fw::trees::LSystem plant("F(1)A(0.8)");                                 // axiom
//   plant.add_rule('A', "F(p)[&(40~0.2)A(p*0.7)]/(137.5)A(p*0.9)", 3.0);   // A -> ... with weight 3
//   plant.add_rule('A', "F(p)", 1.0);                                      // or stop growing, weight 1
//   std::vector<fw::trees::Module> word = plant.derive(5, /*seed=*/42);
//   fw::trees::TurtleSettings turtle;                                      // heading +z, 25 degree turns
//   std::vector<fw::trees::BranchSegment> segments = fw::trees::interpret(word, turtle);
//
// Rewriting. A word is a sequence of modules: a one-character symbol with an optional real parameter p. Each
// iteration replaces every module that has rules, in parallel, by one of its rule's successors, chosen with
// probability weight / (sum of that symbol's weights); modules without rules are copied. All randomness comes
// from one std::mt19937_64 seeded with `seed`, drawn in string order, and mapped to [0, 1) as
// (bits >> 11) * 2^-53, so a derivation is the same on every platform.
//
// Successor text: symbols, each optionally followed by "(EXPR)"; white space is ignored. EXPR is
//   VALUE            a literal, e.g. F(1.5)
//   p                the predecessor's parameter (the module being rewritten)
//   p*VALUE, VALUE*p the predecessor's parameter scaled
// optionally followed by "~S" with 0 <= S < 1: the value is multiplied by (1 + S * (2u - 1)), u uniform in
// [0, 1), drawn when the successor is produced (e.g. "&(40~0.2)" is a pitch of 32..48 degrees). A predecessor
// without a parameter gives p = 1. The axiom uses the same syntax without p.
//
// Turtle (units: lengths in the caller's units, angles in degrees). The turtle has a position and a
// right-handed orthonormal frame: heading H, left L, up U = H x L; it starts at the origin with H = +z,
// L = -y, U = +x. A module's parameter replaces the default (TurtleSettings::step_length for F,
// TurtleSettings::angle_deg for turns).
//   F(l)  bend H toward the tropism direction T (below), then move l along H and draw a segment
//   +(a)  yaw left:   rotate the frame by +a about U (H turns toward L);   -(a) yaw right (rotate by -a)
//   &(a)  pitch down: rotate by +a about L (H turns toward -U);           ^(a) pitch up
//   \(a)  roll left:  rotate by +a about H (L turns toward U);            /(a) roll right
//   |     turn around: rotate by 180 degrees about U
//   $     roll about H until L is horizontal (L = (z x H)/|z x H|, so U points upward); no-op when H is
//   vertical T(e)  set the tropism susceptibility e (radians per F) [ ]   push / pop the whole turtle state
//   (position, frame, susceptibility, branch order, current segment) any other symbol (apices such as A)
//   draws nothing.
// Tropism (Prusinkiewicz & Lindenmayer, "The Algorithmic Beauty of Plants", 2.3): before each F the frame is
// rotated about H x T by alpha = e |H x T|, but never past T, so that gravity (T = -z, e > 0) makes branches
// droop and a branch that already points along T stays straight.
// A segment whose end would lie below TurtleSettings::ground_z is not drawn, and its branch (the rest of the
// enclosing bracket) stops growing: branches do not grow into the soil.
//
// Branch order: the bracket depth of the segment (a segment outside all brackets has order 0).
#pragma once

#include <Eigen/Core>

#include <cstdint>
#include <limits>
#include <span>
#include <string>
#include <string_view>
#include <vector>

namespace fw::trees {

/// One letter of an L-system word: a symbol and an optional parameter (NaN: none given).
struct Module {
  char symbol = 'F';
  double parameter = std::numeric_limits<double>::quiet_NaN();

  bool has_parameter() const { return parameter == parameter; }  // NaN != NaN
  friend bool operator==(const Module& a, const Module& b) {
    return a.symbol == b.symbol &&
           (a.has_parameter() ? b.has_parameter() && a.parameter == b.parameter : !b.has_parameter());
  }
};

/// Writes a word back in successor syntax, e.g. "F(1)[+(90)F]A"; parameters with up to 6 significant digits.
std::string to_string(std::span<const Module> word);

/// Reads a word in successor syntax with literal parameters only (no p, no ~); throws std::invalid_argument.
std::vector<Module> parse_word(std::string_view text);

/// A stochastic parametric bracketed L-system. Throws std::invalid_argument("LSystem: ...") on malformed
/// successor text, unbalanced brackets, non-positive or non-finite weights.
class LSystem {
 public:
  /// Longest word derive() builds before it throws std::length_error (guards against runaway grammars).
  static constexpr std::size_t kMaxWordLength = 20'000'000;

  explicit LSystem(std::string_view axiom);

  /// Adds one stochastic alternative for `symbol`; a symbol's alternatives are chosen in proportion to their
  /// weights. '[' and ']' cannot be rewritten.
  void add_rule(char symbol, std::string_view successor, double weight = 1.0);

  /// The word after `iterations` (>= 0) parallel rewriting steps, with all random choices drawn from a
  /// std::mt19937_64 seeded with `seed`. Throws std::invalid_argument for iterations < 0 and
  /// std::length_error when the word would exceed kMaxWordLength modules.
  std::vector<Module> derive(int iterations, std::uint64_t seed) const;

  // The compiled form of one successor module's parameter expression; public only so that the .cpp helpers
  // can name it.
  struct ParameterTemplate {
    enum class Kind { none, literal, scaled_predecessor } kind = Kind::none;
    double value = 0.0;   // the literal, or the factor on p
    double jitter = 0.0;  // S of "~S"
  };
  struct ModuleTemplate {
    char symbol = 'F';
    ParameterTemplate parameter;
  };

 private:
  struct Alternative {
    double weight = 1.0;
    std::vector<ModuleTemplate> successor;
  };
  std::vector<ModuleTemplate> axiom_;
  std::vector<std::vector<Alternative>> rules_;  // indexed by (unsigned char)symbol
};

/// The turtle's defaults and environment; see the header comment for the symbols.
struct TurtleSettings {
  double step_length = 1.0;                                             ///< F without a parameter
  double angle_deg = 25.0;                                              ///< + - & ^ \ / without a parameter
  Eigen::Vector3d tropism_direction = Eigen::Vector3d(0.0, 0.0, -1.0);  ///< T, normalised by interpret()
  double tropism = 0.0;  ///< initial susceptibility e, radians per F; T(e) modules change it per branch
  double ground_z = -std::numeric_limits<double>::infinity();  ///< segments may not end below this z
};

/// One drawn F: a straight piece of branch.
struct BranchSegment {
  int id = 0;       ///< index in the returned list (segments are listed in drawing order)
  int parent = -1;  ///< the segment whose end is this one's start; -1 when it starts at the origin
  int order = 0;    ///< branch order: bracket depth at which it was drawn
  Eigen::Vector3d start = Eigen::Vector3d::Zero();
  Eigen::Vector3d end = Eigen::Vector3d::Zero();

  double length() const { return (end - start).norm(); }
};

/// Interprets a word with a 3D turtle. F with a zero length draws nothing. Throws std::invalid_argument for
/// unbalanced brackets, a non-finite parameter of a turtle symbol, or a zero tropism direction.
std::vector<BranchSegment> interpret(std::span<const Module> word, const TurtleSettings& settings = {});

/// The uniform [0, 1) number the L-system draws from 64 random bits: (bits >> 11) * 2^-53.
inline double unit_interval(std::uint64_t bits) {
  return double(bits >> 11) * 0x1.0p-53;
}

}  // namespace fw::trees
