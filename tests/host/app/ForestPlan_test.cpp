// The forest's part of the plan, no device: a tree scaled taller than any tree, or smaller than the smallest,
// is refused at its scale's key (issue 44: a stand's scale of 4e9 made `check` rasterise a tree of 4e10 m).
#include <catch2/catch.hpp>

#include <string>

#include "host/app/SimulationPlan.hpp"
#include "io/Scenario.hpp"
#include "tests/support/TempDir.hpp"

using Catch::Matchers::Contains;
using Catch::Matchers::StartsWith;
using fw::test::TempDir;

namespace {

// A 10 m stick, with the forest's lines that follow the species (`forest`).
fw::host::SimulationPlan plan_with(const TempDir& dir, const std::string& forest) {
  dir.write("tree.tree", "0 -1 0 0 0 0.2\n1 0 0 0 5 0.15\n2 1 0 0 10 0.1\n");
  const std::string text =
      "scenario: forest_plan\n"
      "time: {end: 1.0}\n"
      "domain: {size: [64, 64, 16], cell_size: 2.0}\n"
      "wind: {speed: 5.0, direction: 270}\n"
      "forest:\n"
      "  species:\n"
      "    - name: stick\n"
      "      skeleton: {file: tree.tree}\n"
      "      modes: {count: 4}\n" +  // 9
      forest;
  return fw::host::plan_simulation(fw::io::load_scenario(dir.write("forest.yaml", text)), nullptr, nullptr, 1,
                                   fw::host::PlanFor::check);
}

}  // namespace

TEST_CASE("ForestPlan: a scale that makes a tree taller than any tree names the scale's key",
          "[simulation][plan]") {
  TempDir dir("fw_forest_plan");
  // 10 m x 16 = 160 m > 150 m; 10 m x 15 = 150 m is the tallest allowed.
  CHECK_THROWS_WITH(
      plan_with(dir, "  trees:\n    - {species: stick, position: [32, 32], scale: 16}\n"),
      StartsWith(dir.path() + "/forest.yaml:11: forest.trees[0].scale: a scale that makes a tree "
                              "of this species (10 m tall) 0.01 to 150 m tall expected") &&
          Contains("got '16' (160 m)"));
  CHECK(plan_with(dir, "  trees:\n    - {species: stick, position: [32, 32], scale: 15}\n")
            .forest.instance_count() == 1);
  // 10 m x 1e-4 = 1 mm, below the dwarf willow's 1 cm.
  CHECK_THROWS_WITH(plan_with(dir, "  trees:\n    - {species: stick, position: [32, 32], scale: 1e-4}\n"),
                    Contains("forest.trees[0].scale") && Contains("got '0.0001' (0.001 m)"));
  // A stand's scale.max on its own line.
  CHECK_THROWS_WITH(plan_with(dir,
                              "  stands:\n    - species: stick\n      region: {min: [8, 8], max: [56, 56]}\n"
                              "      spacing: 8\n      scale:\n        min: 1\n        max: 20\n"),
                    StartsWith(dir.path() + "/forest.yaml:16: forest.stands[0].scale.max: a scale"));
}
