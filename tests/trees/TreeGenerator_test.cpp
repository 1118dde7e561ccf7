#include "trees/TreeGenerator.hpp"

#include <catch2/catch.hpp>

#include <algorithm>
#include <cmath>
#include <limits>
#include <stdexcept>
#include <string>
#include <vector>

using fw::trees::generate_tree;
using fw::trees::GeneratorSettings;
using fw::trees::preset_names;
using fw::trees::Skeleton;

namespace {

GeneratorSettings settings_for(const std::string& preset, std::uint64_t seed = 1) {
  GeneratorSettings settings;
  settings.preset = preset;
  settings.seed = seed;
  return settings;
}

double element_length(const Skeleton& tree, std::pair<int, int> element) {
  return (tree.node(element.first).position - tree.node(element.second).position).norm();
}

bool is_tip(const Skeleton& tree, int node) {
  return tree.children(node).empty();
}

// The node where the branch ending at `tip` grew from: the nearest ancestor with two or more children.
int branching_node_of(const Skeleton& tree, int tip) {
  int node = tree.node(tip).parent;
  while (node != tree.root() && tree.children(node).size() < 2) node = tree.node(node).parent;
  return node;
}

double horizontal_distance(const Eigen::Vector3d& p) {
  return std::hypot(p.x(), p.y());
}

// Fraction of tips that lie below the branching node their branch grew from.
double fraction_of_hanging_tips(const Skeleton& tree) {
  int tips = 0, hanging = 0;
  for (int i = 0; i < tree.size(); ++i) {
    if (!is_tip(tree, i)) continue;
    ++tips;
    hanging += tree.node(i).position.z() < tree.node(branching_node_of(tree, i)).position.z();
  }
  return double(hanging) / double(tips);
}

std::string error_of(const GeneratorSettings& settings) {
  try {
    generate_tree(settings);
  } catch (const std::invalid_argument& e) {
    return e.what();
  }
  return "no exception";
}

}  // namespace

TEST_CASE("TreeGenerator: the presets are broadleaf, conifer, palm and weeping", "[generator]") {
  CHECK(preset_names() == std::vector<std::string>{"broadleaf", "conifer", "palm", "weeping"});
}

TEST_CASE("TreeGenerator: every preset gives a valid skeleton of the requested height", "[generator]") {
  for (const std::string& preset : preset_names()) {
    for (std::uint64_t seed = 1; seed <= 5; ++seed) {
      INFO(preset << " seed " << seed);
      GeneratorSettings settings = settings_for(preset, seed);
      settings.height = 12.5;
      const Skeleton tree = generate_tree(settings);        // from_nodes validated it
      CHECK(tree.height() == Approx(12.5).epsilon(1e-12));  // scaled exactly, up to rounding
      CHECK(tree.root() == 0);
      CHECK(tree.node(0).position == Eigen::Vector3d::Zero());
      CHECK(tree.bounding_box().min().z() >= 0.0);
      for (const auto& node : tree.nodes()) CHECK(node.radius > 0.0);
      // The trunk starts along +z.
      const auto root_children = tree.children(0);
      REQUIRE(root_children.size() == 1);
      const Eigen::Vector3d first = tree.node(root_children[0]).position.normalized();
      CHECK(first.z() > 0.99);
    }
  }
}

TEST_CASE("TreeGenerator: a zero height gives the preset's default height", "[generator]") {
  CHECK(generate_tree(settings_for("broadleaf")).height() == Approx(15.0).epsilon(1e-12));
  CHECK(generate_tree(settings_for("conifer")).height() == Approx(20.0).epsilon(1e-12));
  CHECK(generate_tree(settings_for("palm")).height() == Approx(12.0).epsilon(1e-12));
  CHECK(generate_tree(settings_for("weeping")).height() == Approx(10.0).epsilon(1e-12));
}

TEST_CASE("TreeGenerator: radii follow the pipe model at every branching node", "[generator]") {
  for (const std::string preset : {"broadleaf", "conifer", "weeping"}) {
    for (std::uint64_t seed = 1; seed <= 3; ++seed) {
      INFO(preset << " seed " << seed);
      const Skeleton tree = generate_tree(settings_for(preset, seed));
      double tip_radius = -1.0;
      for (int i = 0; i < tree.size(); ++i) {
        const auto children = tree.children(i);
        if (children.empty()) {
          if (tip_radius < 0.0) tip_radius = tree.node(i).radius;
          CHECK(tree.node(i).radius == tip_radius);  // every tip has the preset's tip radius
          continue;
        }
        double area = 0.0;
        for (int c : children) area += tree.node(c).radius * tree.node(c).radius;
        const double r = tree.node(i).radius;
        CHECK(r * r == Approx(area).epsilon(1e-9));  // relative, rounding of sqrt only
      }
      CHECK(tree.node(0).radius > 5.0 * tip_radius);  // the trunk carries the whole crown
    }
  }
}

TEST_CASE("TreeGenerator: palm has a nearly constant trunk and thin tapering fronds", "[generator]") {
  for (std::uint64_t seed = 1; seed <= 3; ++seed) {
    INFO("seed " << seed);
    const Skeleton palm = generate_tree(settings_for("palm", seed));
    // Unbranched trunk: exactly one node, the crown, has more than one child.
    std::vector<int> forks;
    for (int i = 0; i < palm.size(); ++i)
      if (palm.children(i).size() > 1) forks.push_back(i);
    REQUIRE(forks.size() == 1);
    const int crown = forks[0];
    CHECK(palm.children(crown).size() == 16);  // 16 fronds
    CHECK(palm.node(crown).position.z() > 0.7 * palm.height());
    // Trunk radii (root to crown) within the 15 % base flare, widest at the base.
    double trunk_min = std::numeric_limits<double>::infinity(), trunk_max = 0.0;
    std::vector<bool> on_trunk(std::size_t(palm.size()), false);
    for (int i = crown; i >= 0; i = palm.node(i).parent) {
      on_trunk[std::size_t(i)] = true;
      trunk_min = std::min(trunk_min, palm.node(i).radius);
      trunk_max = std::max(trunk_max, palm.node(i).radius);
    }
    CHECK(trunk_max / trunk_min <= 1.15 + 1e-12);
    CHECK(palm.node(0).radius == trunk_max);
    // Slightly curved: the crown leans off the axis, but by less than a fifth of the height.
    const double lean = horizontal_distance(palm.node(crown).position);
    CHECK(lean > 0.0);
    CHECK(lean < 0.2 * palm.height());
    // Fronds are much thinner than the trunk and taper toward their tips; they arch: tips below the top.
    for (int i = 0; i < palm.size(); ++i) {
      if (on_trunk[std::size_t(i)]) continue;
      CHECK(palm.node(i).radius <= 0.15 * trunk_min + 1e-12);
      CHECK(palm.node(i).radius < palm.node(palm.node(i).parent).radius);
    }
    int drooping_tips = 0;
    for (int i = 0; i < palm.size(); ++i)
      drooping_tips += is_tip(palm, i) && palm.node(i).position.z() < palm.node(crown).position.z();
    CHECK(drooping_tips >= 8);  // the older half of the crown arches below the crown
  }
}

TEST_CASE("TreeGenerator: no element is longer than max_element_length", "[generator]") {
  for (const std::string& preset : preset_names()) {
    INFO(preset);
    const Skeleton by_default = generate_tree(settings_for(preset));
    for (const auto& e : by_default.elements())
      CHECK(element_length(by_default, e) <= by_default.height() / 40.0 * (1.0 + 1e-12));
    GeneratorSettings fine = settings_for(preset);
    fine.max_element_length = 0.1;
    const Skeleton tree = generate_tree(fine);
    double shortest = std::numeric_limits<double>::infinity();
    for (const auto& e : tree.elements()) {
      CHECK(element_length(tree, e) <= 0.1 * (1.0 + 1e-12));  // relative rounding slack
      shortest = std::min(shortest, element_length(tree, e));
    }
    CHECK(shortest > 1e-4);  // no near-coincident nodes
    CHECK(tree.size() > by_default.size());
    CHECK(tree.height() == Approx(by_default.height()).epsilon(1e-12));  // same tree, finer elements
  }
}

TEST_CASE("TreeGenerator: the same seed gives an identical skeleton", "[generator]") {
  for (const std::string& preset : preset_names()) {
    INFO(preset);
    const Skeleton a = generate_tree(settings_for(preset, 77));
    const Skeleton b = generate_tree(settings_for(preset, 77));
    REQUIRE(a.size() == b.size());
    for (int i = 0; i < a.size(); ++i) {
      CHECK(a.node(i).parent == b.node(i).parent);
      CHECK(a.node(i).position == b.node(i).position);  // bit-identical
      CHECK(a.node(i).radius == b.node(i).radius);
    }
  }
}

TEST_CASE("TreeGenerator: a different seed gives a different tree", "[generator]") {
  for (const std::string& preset : preset_names()) {
    INFO(preset);
    const Skeleton a = generate_tree(settings_for(preset, 1));
    const Skeleton b = generate_tree(settings_for(preset, 2));
    bool differs = a.size() != b.size();
    for (int i = 0; !differs && i < a.size(); ++i) differs = a.node(i).position != b.node(i).position;
    CHECK(differs);
  }
}

TEST_CASE("TreeGenerator: conifer has one straight vertical leader and a conical crown", "[generator]") {
  for (std::uint64_t seed = 1; seed <= 5; ++seed) {
    INFO("seed " << seed);
    const Skeleton tree = generate_tree(settings_for("conifer", seed));
    const double height = tree.height();
    int top = 0;
    for (int i = 0; i < tree.size(); ++i)
      if (tree.node(i).position.z() > tree.node(top).position.z()) top = i;
    // Every node on the highest node's path to the root stays on the z axis (1e-9 H: rounding only).
    int path_length = 0;
    for (int i = top; i >= 0; i = tree.node(i).parent, ++path_length)
      CHECK(horizontal_distance(tree.node(i).position) < 1e-9 * height);
    CHECK(path_length >= 40);  // default elements are H/40 long
    // Branches near horizontal and shorter toward the top: the crown's reach shrinks with height.
    double reach_low = 0.0, reach_high = 0.0;
    for (const auto& node : tree.nodes()) {
      const double z = node.position.z() / height;
      if (z > 0.15 && z < 0.4) reach_low = std::max(reach_low, horizontal_distance(node.position));
      if (z > 0.65 && z < 0.9) reach_high = std::max(reach_high, horizontal_distance(node.position));
    }
    CHECK(reach_high < 0.7 * reach_low);
    CHECK(reach_low > 0.15 * height);
  }
}

TEST_CASE("TreeGenerator: broadleaf is decurrent with a spreading crown", "[generator]") {
  for (std::uint64_t seed = 1; seed <= 5; ++seed) {
    INFO("seed " << seed);
    const Skeleton tree = generate_tree(settings_for("broadleaf", seed));
    // A clear bole that forks into 2-4 scaffold limbs, none of which continues the trunk's direction.
    int fork = 0;
    while (tree.children(fork).size() == 1) fork = tree.children(fork)[0];
    CHECK(tree.children(fork).size() >= 2);
    CHECK(tree.children(fork).size() <= 4);
    CHECK(tree.node(fork).position.z() > 0.15 * tree.height());
    CHECK(tree.node(fork).position.z() < 0.5 * tree.height());
    for (int limb : tree.children(fork)) {
      const Eigen::Vector3d direction = (tree.node(limb).position - tree.node(fork).position).normalized();
      CHECK(direction.z() < std::cos(15.0 * M_PI / 180.0));  // at least 15 degrees off vertical
    }
    const auto box = tree.bounding_box();
    const double width = std::max(box.sizes().x(), box.sizes().y());
    CHECK(width > 0.5 * tree.height());
    CHECK(fraction_of_hanging_tips(tree) < 0.5);  // a broadleaf's twigs mostly point up and out
  }
}

TEST_CASE("TreeGenerator: weeping branch tips hang below their branching points", "[generator]") {
  for (std::uint64_t seed = 1; seed <= 10; ++seed) {
    INFO("seed " << seed);
    const Skeleton tree = generate_tree(settings_for("weeping", seed));
    // Over 40 seeds the fraction is 0.87 or more; the rest are the rising scaffold limbs' ends.
    CHECK(fraction_of_hanging_tips(tree) > 0.75);
  }
}

TEST_CASE("TreeGenerator: default node counts lie between 300 and 5000", "[generator]") {
  for (const std::string& preset : preset_names()) {
    for (std::uint64_t seed = 1; seed <= 20; ++seed) {
      INFO(preset << " seed " << seed);
      const int n = generate_tree(settings_for(preset, seed)).size();
      CHECK(n >= 300);
      CHECK(n <= 5000);
    }
  }
}

TEST_CASE("TreeGenerator: shorter elements or more iterations reach 30k nodes", "[generator]") {
  for (const std::string& preset : preset_names()) {
    INFO(preset);
    GeneratorSettings settings = settings_for(preset);
    settings.height = 10.0;
    settings.max_element_length = settings.height / 8000.0;
    // No wall-clock bound: machines differ, and tests assert none.
    const Skeleton tree = generate_tree(settings);
    CHECK(tree.size() >= 30000);
  }
  GeneratorSettings more = settings_for("broadleaf");
  more.iterations = 16;  // about 1.35x nodes per iteration beyond the default 8
  CHECK(generate_tree(more).size() >= 30000);
  more.iterations = 4;
  CHECK(generate_tree(more).size() < generate_tree(settings_for("broadleaf")).size());
}

TEST_CASE("TreeGenerator: an unknown preset throws and lists the valid names", "[generator]") {
  const std::string message = error_of(settings_for("baobab"));
  CHECK_THAT(message, Catch::StartsWith("TreeGenerator: "));
  CHECK_THAT(message, Catch::Contains("baobab"));
  for (const std::string& name : preset_names()) CHECK_THAT(message, Catch::Contains(name));
}

TEST_CASE("TreeGenerator: invalid heights, element lengths and iterations throw", "[generator]") {
  const double bad_values[] = {-1.0, std::numeric_limits<double>::quiet_NaN(),
                               std::numeric_limits<double>::infinity()};
  for (double bad : bad_values) {
    GeneratorSettings height = settings_for("conifer");
    height.height = bad;
    CHECK_THAT(error_of(height), Catch::StartsWith("TreeGenerator: expected a height"));
    GeneratorSettings element = settings_for("conifer");
    element.max_element_length = bad;
    CHECK_THAT(error_of(element), Catch::StartsWith("TreeGenerator: expected a max_element_length"));
  }
  GeneratorSettings iterations = settings_for("palm");
  iterations.iterations = -2;
  CHECK_THAT(error_of(iterations), Catch::StartsWith("TreeGenerator: expected iterations"));
  GeneratorSettings tiny = settings_for("broadleaf");
  tiny.max_element_length = 1e-7;  // billions of nodes: refused before anything is allocated
  CHECK_THAT(error_of(tiny), Catch::Contains("nodes"));
}
