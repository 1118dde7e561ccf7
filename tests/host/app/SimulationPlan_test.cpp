// The plan on the host, no device: every species' leaves, generated on the skeleton of its basis, their
// totals and device memory, and the same leaves from the same scenario.
#include "host/app/SimulationPlan.hpp"
#include "host/stages/LeafStages.hpp"

#include <catch2/catch.hpp>

#include <cmath>
#include <cstddef>
#include <sstream>
#include <string>

#include "io/Scenario.hpp"
#include "tests/support/TempDir.hpp"
#include "trees/Foliage.hpp"

using Catch::Matchers::Contains;
using fw::test::TempDir;

namespace {

// A small tree, 4 m tall: a trunk of 4 elements and four branches of 2, one towards each side, so that its
// crown has a horizontal extent (leaves need one).
const char* kTreeFile =
    "# test tree: trunk 0-4, branches from nodes 2 and 3\n"
    "0 -1 0 0 0 0.12\n1 0 0 0 1.0 0.10\n2 1 0 0 2.0 0.08\n3 2 0 0 3.0 0.06\n4 3 0 0 4.0 0.04\n"
    "5 2 0.6 0 2.4 0.03\n6 5 1.2 0 2.7 0.02\n7 2 -0.6 0 2.4 0.03\n8 7 -1.2 0 2.7 0.02\n"
    "9 3 0 0.5 3.3 0.03\n10 9 0 1.0 3.5 0.02\n11 3 0 -0.5 3.3 0.03\n12 11 0 -1.0 3.5 0.02\n";

// Species oak with `leaves` (a flow map, or empty for none) and LAI 3; species bare without leaves; two oaks
// and one bare tree.
std::string scenario_text(const std::string& leaves) {
  return "scenario: plan_leaves\nseed: 4\n"
         "time: {end: 1.0}\n"
         "domain: {size: [16, 16, 8], cell_size: 2.0}\n"
         "wind: {speed: 5.0, direction: 270}\n"
         "forest:\n"
         "  species:\n"
         "    - name: oak\n"
         "      skeleton: {file: tree.tree}\n"
         "      modes: {count: 4, wind_samples: 2}\n"
         "      canopy: {leaf_area_index: 3.0}\n" +
         (leaves.empty() ? std::string() : "      leaves: " + leaves + "\n") +
         "    - name: bare\n"
         "      skeleton: {file: tree.tree}\n"
         "      modes: {count: 4, wind_samples: 2}\n"
         "  trees:\n"
         "    - {species: oak, position: [4, 8]}\n"
         "    - {species: bare, position: [8, 8]}\n"
         "    - {species: oak, position: [12, 8], yaw: 90, scale: 1.2}\n";
}

fw::host::SimulationPlan plan_of(const TempDir& dir, const std::string& name, const std::string& leaves,
                                 std::ostream* log = nullptr) {
  dir.write("tree.tree", kTreeFile);
  const fw::io::Scenario scenario = fw::io::load_scenario(dir.write(name + ".yaml", scenario_text(leaves)));
  return fw::host::plan_simulation(scenario, nullptr, log);
}

}  // namespace

TEST_CASE("SimulationPlan: a species with leaves gets round(fraction x leaf area / area) of them",
          "[simulation][plan]") {
  TempDir dir("fw_plan");
  std::ostringstream log;
  const auto plan = plan_of(dir, "leaves", "{area: 0.01, fraction: 0.5, seed: 9}", &log);
  REQUIRE(plan.coupling.leaves.size() == 2);  // one per forest species, in forest order
  REQUIRE(plan.forest.species().size() == 2);

  // On the skeleton of the species' basis, with the canopy's leaf area index.
  const auto& skeleton = plan.forest.species()[0].skeleton();
  const auto foliage = fw::trees::Foliage::of(skeleton, 3.0);
  REQUIRE(foliage.leaf_area > 0.0);
  const long expected = std::lround(0.5 * foliage.leaf_area / 0.01);
  INFO("leaf area " << foliage.leaf_area << " m^2");
  REQUIRE(expected > 10);
  const fw::trees::SpeciesLeaves& oak = plan.coupling.leaves[0];
  CHECK(oak.count() == expected);
  CHECK(oak.settings().seed == 9);
  CHECK(oak.settings().area == 0.01);
  for (const auto& leaf : oak.leaves()) {
    REQUIRE(leaf.element >= 0);
    REQUIRE(std::size_t(leaf.element) < skeleton.elements().size());
    CHECK(foliage.leaf_bearing[std::size_t(leaf.element)]);
  }
  // The species without `leaves` has none, a default-constructed set.
  CHECK(plan.coupling.leaves[1].count() == 0);
  // Two oaks carry the species' leaves each; the bare tree none.
  CHECK(plan.leaf_count == 2 * expected);

  // The log names the leaves of the species that has them.
  CHECK_THAT(log.str(), Contains(", " + std::to_string(expected) + " leaves ("));
  CHECK(log.str().find("leaves") == log.str().rfind("leaves"));  // once: bare has none

  // Device memory: the leaves are a part of their own (their stage's estimate, checked against what the
  // stage allocates in tests/kernels/leaves_test.cpp), and the only difference from the same forest bare.
  const auto bare = plan_of(dir, "no_leaves", "");
  CHECK(bare.leaf_count == 0);
  CHECK(bare.coupling.leaves.size() == 2);
  CHECK(bare.coupling.leaves[0].count() == 0);
  const auto part = [](const fw::host::SimulationPlan& p, const std::string& name) {
    for (const auto& entry : p.memory.parts())
      if (entry.name == name) return entry.bytes;
    return std::size_t(0);
  };
  CHECK(part(bare, "leaves") == 0);
  CHECK(part(plan, "leaves") ==
        fw::host::LeafStages::estimate_device_bytes(plan.forest, plan.coupling.leaves));
  CHECK(plan.memory.total() - bare.memory.total() == part(plan, "leaves"));
}

TEST_CASE("SimulationPlan: the same scenario twice gives identical leaves, another seed other leaves",
          "[simulation][plan]") {
  TempDir dir("fw_plan");
  const auto first = plan_of(dir, "first", "{model: stochastic, area: 0.02}");
  const auto second = plan_of(dir, "second", "{model: stochastic, area: 0.02}");
  const fw::trees::SpeciesLeaves& a = first.coupling.leaves[0];
  const fw::trees::SpeciesLeaves& b = second.coupling.leaves[0];
  REQUIRE(a.count() > 0);
  REQUIRE(a.count() == b.count());
  // The default seed: global seed 4 + 2^32 + species index 0.
  CHECK(a.settings().seed == 4 + fw::io::kLeafSeedOffset);
  for (int k = 0; k < a.count(); ++k) {
    INFO("leaf " << k);
    const auto& x = a.leaf(k);
    const auto& y = b.leaf(k);
    CHECK(x.element == y.element);
    CHECK(x.along == y.along);
    CHECK(x.anchor == y.anchor);
    CHECK(x.petiole == y.petiole);
    CHECK(x.hinge == y.hinge);
    CHECK(x.normal == y.normal);
    CHECK(x.strength == y.strength);
    CHECK(x.phase == y.phase);
    CHECK(x.frequency == y.frequency);
    CHECK(x.tumble_axis == y.tumble_axis);
  }
  const auto reseeded = plan_of(dir, "reseeded", "{model: stochastic, area: 0.02, seed: 17}");
  REQUIRE(reseeded.coupling.leaves[0].count() == a.count());  // the same foliage, so the same count
  bool differ = false;
  for (int k = 0; k < a.count(); ++k)
    differ = differ || !(reseeded.coupling.leaves[0].leaf(k).anchor == a.leaf(k).anchor);
  CHECK(differ);
}
