// The species' part of the plan, no device: what deep code refuses of a species (a modal problem that cannot
// be solved, a skeleton taller than any tree) is refused as the scenario's, naming the key at fault
// (issue 44: such a species exited 1 with ModalBasis' message and no file, line or key).
#include <catch2/catch.hpp>

#include <string>

#include "host/app/SimulationPlan.hpp"
#include "io/Scenario.hpp"
#include "tests/support/TempDir.hpp"

using Catch::Matchers::Contains;
using Catch::Matchers::StartsWith;
using fw::test::TempDir;

namespace {

// One species from `tree.tree` (the text given), one tree of it.
fw::host::SimulationPlan plan_with_tree(const TempDir& dir, const std::string& tree) {
  dir.write("tree.tree", tree);
  const std::string text =
      "scenario: species_plan\n"
      "time: {end: 1.0}\n"
      "domain: {size: [32, 16, 16], cell_size: 2.0}\n"
      "wind: {speed: 5.0, direction: 270}\n"
      "forest:\n"
      "  species:\n"
      "    - name: stick\n"                  // 7
      "      skeleton: {file: tree.tree}\n"  // 8
      "      modes: {count: 4}\n"
      "  trees:\n"
      "    - {species: stick, position: [16, 8]}\n";
  return fw::host::plan_simulation(fw::io::load_scenario(dir.write("species.yaml", text)), nullptr, nullptr,
                                   1, fw::host::PlanFor::check);
}

}  // namespace

TEST_CASE("SpeciesPlan: a species whose modes cannot be solved is refused, naming its entry",
          "[simulation][plan]") {
  TempDir dir("fw_species_plan");
  // A 10 nm element at the root, as thick as the rest: its stiffness, 10^9 times the next element's, leaves
  // the modal problem without a positive definite stiffness in double precision.
  CHECK_THROWS_WITH(plan_with_tree(dir, "0 -1 0 0 0 0.1\n1 0 0 0 1e-8 0.1\n2 1 0 0 10 0.05\n"),
                    StartsWith(dir.path() + "/species.yaml:7: forest.species[0]: a species whose vibration "
                                            "modes can be solved expected") &&
                        Contains("ModalBasis: "));
  // The same tree without that element is solved.
  CHECK(plan_with_tree(dir, "0 -1 0 0 0 0.1\n1 0 0 0 5 0.08\n2 1 0 0 10 0.05\n").species.size() == 1);
}

TEST_CASE("SpeciesPlan: a skeleton taller than any tree is refused at the key that gives it",
          "[simulation][plan]") {
  TempDir dir("fw_species_plan");
  CHECK_THROWS_WITH(plan_with_tree(dir, "0 -1 0 0 0 2\n1 0 0 0 100 1.5\n2 1 0 0 200 1\n"),
                    StartsWith(dir.path() + "/species.yaml:8: forest.species[0].skeleton.file: a skeleton at "
                                            "most 150 m tall expected") &&
                        Contains("got one 200 m tall"));
  CHECK(plan_with_tree(dir, "0 -1 0 0 0 2\n1 0 0 0 70 1.5\n2 1 0 0 140 1\n").species.size() == 1);
}
