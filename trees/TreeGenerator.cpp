#include "trees/TreeGenerator.hpp"

#include "trees/LSystem.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <cmath>
#include <span>
#include <stdexcept>
#include <string_view>

namespace fw::trees {

namespace {

struct Rule {
  char symbol;
  std::string_view successor;
  double weight;
};

enum class RadiusModel { pipe, palm };

struct Preset {
  std::string_view name;
  double default_height;  // m
  int default_iterations;
  std::string_view axiom;
  std::vector<Rule> rules;
  Eigen::Vector3d tropism_direction;
  double tropism;  // initial susceptibility, radians per F (T(e) modules override it per branch)
  RadiusModel radius_model;
  double tip_radius_fraction;  // pipe model: tip radius / height
};

// Default element length as a fraction of the height.
constexpr double kElementFraction = 1.0 / 40.0;

// Palm radii (see the header comment), as fractions of the height / of the trunk radius.
constexpr double kPalmTrunkRadiusFraction = 0.012;
constexpr double kPalmBaseFlare = 0.15;
constexpr double kPalmFrondBaseFraction = 0.15;
constexpr double kPalmFrondTipRatio = 0.3;

// Grammars. Parameters of apices (A, B, C, S, W, R) are the length of the internode they will grow, in
// arbitrary units (the tree is scaled to its height afterwards). /(137.5) is the golden-angle phyllotaxis.
const std::vector<Preset>& presets() {
  static const std::vector<Preset> all = {
      {"broadleaf",
       15.0,
       8,
       // A clear bole, then the first fork into scaffold limbs.
       "F(3.5~0.1)/(45~0.9)B(2)",
       {
           // B: the first fork, 2-4 limbs and no leader (decurrent).
           {'B', "F(p*0.4)[&(30~0.25)A(p)]/(180~0.1)&(30~0.25)A(p)", 1.0},
           {'B', "F(p*0.4)[&(32~0.25)A(p)]/(120~0.1)[&(32~0.25)A(p)]/(120~0.1)&(32~0.25)A(p)", 2.0},
           {'B',
            "F(p*0.4)[&(35~0.25)A(p)]/(90~0.1)[&(35~0.25)A(p)]/(90~0.1)[&(35~0.25)A(p)]/"
            "(90~0.1)&(35~0.25)A(p)",
            1.0},
           // A: a scaffold limb internode, then a fork into two near-equal limbs (one continues at the
           // same order) ...
           {'A', "F(p~0.15)/(90~0.3)[&(28~0.3)A(p*0.78)]^(22~0.3)A(p*0.82)", 0.45},
           // ... or a thinner side branch L and a continuation ...
           {'A', "F(p~0.15)[&(45~0.3)L(p*0.62)]/(137.5~0.1)^(5~0.9)A(p*0.85)", 0.35},
           // ... or a three-way fork.
           {'A', "F(p~0.15)[&(35~0.3)A(p*0.7)]/(120~0.1)[&(35~0.3)A(p*0.7)]/(120~0.1)&(20~0.3)A(p*0.75)",
            0.20},
           // L: a side branch forks like a limb, but its recursion may also end (Oliapuram's random stop).
           {'L', "F(p~0.15)[&(40~0.3)L(p*0.7)]/(137.5~0.1)L(p*0.85)", 0.45},
           {'L', "F(p~0.15)/(90~0.3)[&(30~0.3)L(p*0.75)]^(25~0.3)L(p*0.75)", 0.35},
           {'L', "F(p~0.15)", 0.20},
       },
       Eigen::Vector3d::UnitZ(),
       0.05,  // weak upward (photo)tropism keeps the spreading limbs from drooping below horizontal
       RadiusModel::pipe,
       0.0007},
      {"conifer",
       20.0,
       14,
       "F(2)A",
       {
           // A: a leader internode and a whorl of 5 (or 4) branches near 82 degrees from vertical; the
           // leader itself is never pitched, so it stays straight.
           {'A',
            "F(1~0.08)[&(82~0.06)T(0.025)B(0.3)]/(72~0.1)[&(82~0.06)T(0.025)B(0.3)]/(72~0.1)"
            "[&(82~0.06)T(0.025)B(0.3)]/(72~0.1)[&(82~0.06)T(0.025)B(0.3)]/(72~0.1)"
            "[&(82~0.06)T(0.025)B(0.3)]/(31~0.5)A",
            2.0},
           {'A',
            "F(1~0.08)[&(80~0.06)T(0.025)B(0.3)]/(90~0.1)[&(80~0.06)T(0.025)B(0.3)]/(90~0.1)"
            "[&(80~0.06)T(0.025)B(0.3)]/(90~0.1)[&(80~0.06)T(0.025)B(0.3)]/(41~0.5)A",
            1.0},
           // B: a branch grows one internode per iteration, sometimes with a side shoot.
           {'B', "F(p~0.1)B(p)", 0.5},
           {'B', "F(p~0.1)[+(55~0.2)C(p*0.8)]B(p)", 0.25},
           {'B', "F(p~0.1)[-(55~0.2)C(p*0.8)]B(p)", 0.25},
           {'C', "F(p~0.1)C(p*0.9)", 0.8},
           {'C', "F(p~0.1)", 0.2},
       },
       -Eigen::Vector3d::UnitZ(),
       0.0,
       RadiusModel::pipe,
       0.0005},
      {"palm",
       12.0,
       12,
       // S: the trunk, bending a little (always about the same axis) at each internode; C: the crown, which
       // stays at the tip because S rewrites to its left.
       "SC",
       {
           {'S', "F(1~0.05)&(1.2~0.5)S", 1.0},
           {'C',
            "[&(25~0.2)T(0.15)R(0.45)]/(137.5)[&(28~0.2)T(0.15)R(0.45)]/(137.5)[&(29~0.2)T(0.15)R(0.45)]/"
            "(137.5)"
            "[&(36~0.2)T(0.15)R(0.45)]/(137.5)[&(40~0.2)T(0.15)R(0.45)]/(137.5)[&(45~0.2)T(0.15)R(0.45)]/"
            "(137.5)"
            "[&(50~0.2)T(0.15)R(0.45)]/(137.5)[&(54~0.2)T(0.15)R(0.45)]/(137.5)[&(58~0.2)T(0.15)R(0.45)]/"
            "(137.5)"
            "[&(62~0.2)T(0.15)R(0.45)]/(137.5)[&(66~0.2)T(0.15)R(0.45)]/(137.5)[&(69~0.2)T(0.15)R(0.45)]/"
            "(137.5)"
            "[&(72~0.2)T(0.15)R(0.45)]/(137.5)[&(75~0.2)T(0.15)R(0.45)]/(137.5)[&(78~0.2)T(0.15)R(0.45)]/"
            "(137.5)"
            "[&(80~0.2)T(0.15)R(0.45)]",
            1.0},
           // R: a frond grows one internode per iteration and arches under the T(e) tropism.
           {'R', "F(p~0.05)R(p)", 1.0},
       },
       -Eigen::Vector3d::UnitZ(),
       0.0,
       RadiusModel::palm,
       0.0},
      {"weeping",
       10.0,
       7,
       // A short bole, then the first fork into 3-4 scaffold limbs.
       "F(2.5~0.05)/(30~0.9)B(1.6)",
       {
           {'B', "F(p*0.3)[&(35~0.2)S(p)]/(120~0.1)[&(35~0.2)S(p)]/(120~0.1)&(35~0.2)S(p)", 1.0},
           {'B',
            "F(p*0.3)[&(35~0.2)S(p)]/(90~0.1)[&(35~0.2)S(p)]/(90~0.1)[&(35~0.2)S(p)]/(90~0.1)&(35~0.2)S(p)",
            1.0},
           // S: a scaffold limb that arches out under a weak droop and sheds pendulous whips W to its
           // sides. $ levels the turtle so that & pitches the whip toward the ground whatever the limb's
           // roll.
           {'S',
            "F(p*0.5~0.1)F(p*0.5~0.1)[+(60~0.3)$&(50~0.3)T(0.5)W(p*0.6)][-(60~0.3)$&(50~0.3)T(0.5)W(p*0.6)]"
            "/(137.5~0.1)[&(30~0.25)S(p*0.8)]S(p*0.85)",
            0.5},
           {'S', "F(p*0.5~0.1)F(p*0.5~0.1)[+(60~0.3)$&(50~0.3)T(0.5)W(p*0.6)]/(137.5~0.1)S(p*0.85)", 0.5},
           // W: a whip grows one internode per iteration and sometimes forks.
           {'W', "F(p~0.1)W(p)", 0.7},
           {'W', "F(p~0.1)[/(90~0.5)&(25~0.3)W(p*0.8)]W(p)", 0.3},
       },
       -Eigen::Vector3d::UnitZ(),
       0.12,
       RadiusModel::pipe,
       0.0007},
  };
  return all;
}

[[noreturn]] void fail(const std::string& what) {
  throw std::invalid_argument("TreeGenerator: " + what);
}

const Preset& find_preset(const std::string& name) {
  for (const Preset& preset : presets())
    if (preset.name == name) return preset;
  fail(fmt::format("unknown preset \"{}\"; expected one of: {}", name, fmt::join(preset_names(), ", ")));
}

// Number of equal elements a segment of `length` is split into so that none is longer than max_length.
long long element_count(double length, double max_length) {
  long long count = std::max(1LL, (long long)std::ceil(length / max_length));
  if (length / double(count) > max_length) ++count;  // rounding in the division above
  return count;
}

// Radii from the tips toward the root: r_tip at leaves, r^2 = sum of the children's r^2 elsewhere.
// Requires every node's parent to have a smaller index.
void set_pipe_model_radii(std::vector<SkeletonNode>& nodes, double tip_radius) {
  std::vector<double> area(nodes.size(), 0.0);  // sum of the children's r^2; 0 marks a tip
  for (std::size_t i = nodes.size(); i-- > 0;) {
    const double r2 = area[i] > 0.0 ? area[i] : tip_radius * tip_radius;
    nodes[i].radius = std::sqrt(r2);
    if (nodes[i].parent >= 0) area[std::size_t(nodes[i].parent)] += r2;
  }
}

// Palm radii (header comment): a nearly constant trunk (order 0) and fronds tapering to their tips.
void set_palm_radii(std::vector<SkeletonNode>& nodes, const std::vector<int>& order, double height) {
  const std::size_t n = nodes.size();
  // Arc length from the start of the node's branch (the root for the trunk) and the length still ahead.
  std::vector<double> along(n, 0.0), ahead(n, 0.0);
  auto length_to_parent = [&](std::size_t i) {
    return (nodes[i].position - nodes[std::size_t(nodes[i].parent)].position).norm();
  };
  for (std::size_t i = 1; i < n; ++i) {
    const auto parent = std::size_t(nodes[i].parent);
    along[i] = (order[parent] == order[i] ? along[parent] : 0.0) + length_to_parent(i);
  }
  for (std::size_t i = n; i-- > 1;) {
    const auto parent = std::size_t(nodes[i].parent);
    if (order[parent] == order[i]) ahead[parent] = std::max(ahead[parent], ahead[i] + length_to_parent(i));
  }
  const double trunk_radius = kPalmTrunkRadiusFraction * height;
  const double trunk_length = ahead[0];
  const double frond_base = kPalmFrondBaseFraction * trunk_radius;
  for (std::size_t i = 0; i < n; ++i) {
    const double fraction = along[i] / (along[i] + ahead[i]);  // 0 at the branch base, 1 at its tip
    if (order[i] == 0) {
      nodes[i].radius = trunk_radius * (1.0 + kPalmBaseFlare * (1.0 - along[i] / trunk_length));
    } else {
      nodes[i].radius = frond_base * (1.0 - (1.0 - kPalmFrondTipRatio) * fraction);
    }
  }
}

}  // namespace

std::vector<std::string> preset_names() {
  std::vector<std::string> names;
  for (const Preset& preset : presets()) names.emplace_back(preset.name);
  return names;
}

Skeleton generate_tree(const GeneratorSettings& settings) {
  const Preset& preset = find_preset(settings.preset);
  if (!std::isfinite(settings.height) || settings.height < 0.0)
    fail(fmt::format("expected a height > 0 m (or 0 for the preset's default), got {}", settings.height));
  if (!std::isfinite(settings.max_element_length) || settings.max_element_length < 0.0)
    fail(fmt::format("expected a max_element_length > 0 m (or 0 for the preset's default), got {}",
                     settings.max_element_length));
  if (settings.iterations < 0)
    fail(fmt::format("expected iterations > 0 (or 0 for the preset's default), got {}", settings.iterations));
  const double height = settings.height > 0.0 ? settings.height : preset.default_height;
  const double max_element_length =
      settings.max_element_length > 0.0 ? settings.max_element_length : kElementFraction * height;
  const int iterations = settings.iterations > 0 ? settings.iterations : preset.default_iterations;

  LSystem grammar(preset.axiom);
  for (const Rule& rule : preset.rules) grammar.add_rule(rule.symbol, rule.successor, rule.weight);
  std::vector<Module> word;
  try {
    word = grammar.derive(iterations, settings.seed);
  } catch (const std::length_error&) {
    fail(fmt::format("{} iterations of the {} grammar give too large a tree (more than {} modules)",
                     iterations, preset.name, LSystem::kMaxWordLength));
  }
  TurtleSettings turtle;
  turtle.tropism_direction = preset.tropism_direction;
  turtle.tropism = preset.tropism;
  turtle.ground_z = 0.0;
  const std::vector<BranchSegment> segments = interpret(word, turtle);

  double raw_height = 0.0;
  for (const BranchSegment& s : segments) raw_height = std::max(raw_height, s.end.z());
  if (segments.empty() || !(raw_height > 0.0)) fail(fmt::format("the {} grammar drew no tree", preset.name));
  const double scale = height / raw_height;

  long long node_count = 1;
  for (const BranchSegment& s : segments) {
    node_count += element_count(scale * s.length(), max_element_length);
    if (node_count > kMaxGeneratedNodes)
      fail(fmt::format("max_element_length {} m would give more than {} nodes", max_element_length,
                       kMaxGeneratedNodes));
  }

  std::vector<SkeletonNode> nodes;
  std::vector<int> order;  // branch order of the segment each node ends
  nodes.reserve(std::size_t(node_count));
  order.reserve(std::size_t(node_count));
  nodes.push_back({-1, Eigen::Vector3d::Zero(), 1.0});
  order.push_back(0);
  std::vector<int> segment_end(segments.size(), 0);  // node index at each segment's end
  for (const BranchSegment& s : segments) {
    const Eigen::Vector3d start = scale * s.start, end = scale * s.end;
    const long long count = element_count((end - start).norm(), max_element_length);
    int previous = s.parent < 0 ? 0 : segment_end[std::size_t(s.parent)];
    for (long long k = 1; k <= count; ++k) {
      // The last node is the segment end itself, so children attach exactly where it ends.
      const Eigen::Vector3d position = k == count ? end : start + (double(k) / double(count)) * (end - start);
      nodes.push_back({previous, position, 1.0});
      order.push_back(s.order);
      previous = int(nodes.size()) - 1;
    }
    segment_end[std::size_t(s.id)] = previous;
  }

  if (preset.radius_model == RadiusModel::pipe) {
    set_pipe_model_radii(nodes, preset.tip_radius_fraction * height);
  } else {
    set_palm_radii(nodes, order, height);
  }
  return Skeleton::from_nodes(std::move(nodes));
}

Skeleton generate_tree_with_nodes(GeneratorSettings settings, int target_nodes, double* element_length) {
  if (target_nodes < 2) {
    throw std::invalid_argument(
        fmt::format("TreeGenerator: target node count must be >= 2, got {}", target_nodes));
  }
  // The node count falls as the element length grows; bisect on log(length).
  const double height = settings.height > 0.0 ? settings.height : generate_tree(settings).height();
  double lo = std::log(1e-3), hi = std::log(height);
  Skeleton best;
  double best_length = 0.0;
  for (int step = 0; step < 40; ++step) {
    const double mid = 0.5 * (lo + hi);
    settings.max_element_length = std::exp(mid);
    Skeleton tree = generate_tree(settings);
    const int nodes = tree.size();
    if (best.size() == 0 || std::abs(nodes - target_nodes) < std::abs(best.size() - target_nodes)) {
      best = std::move(tree);
      best_length = settings.max_element_length;
    }
    if (std::abs(best.size() - target_nodes) <= target_nodes / 200) break;  // within 0.5%
    (nodes > target_nodes ? lo : hi) = mid;
  }
  if (element_length) *element_length = best_length;
  return best;
}

}  // namespace fw::trees
