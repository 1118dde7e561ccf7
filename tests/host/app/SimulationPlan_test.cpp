// The plan on the host, no device: every species' leaves, generated on the skeleton of its basis, their
// totals and device memory, and the same leaves from the same scenario; each stand's leaf and frontal area
// index against a stand worked out by hand, the warning for a stand no forest is like, and a stand's own
// leaf area index; each species' tree model.
#include "host/app/SimulationPlan.hpp"
#include "host/stages/LeafStages.hpp"

#include <fmt/format.h>
#include <catch2/catch.hpp>

#include <cmath>
#include <cstddef>
#include <sstream>
#include <string>

#include "io/Scenario.hpp"
#include "tests/support/TempDir.hpp"
#include "trees/Foliage.hpp"
#include "trees/Skeleton.hpp"
#include "trees/StandDensity.hpp"
#include "trees/TreeFile.hpp"

using Catch::Matchers::Contains;
using Catch::Matchers::StartsWith;
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

// The stand worked out by hand: kTreeFile's crown hull is the rhombus of its branch tips (+-1.2, 0) and
// (0, +-1.0), 2.4 m^2. A grid 4.5 m apart, centred in the 12 x 12 m region [2, 14]^2, puts 3 x 3 trees at
// 3.5, 8 and 12.5 on each axis, every crown (and so every element) inside the region, whose columns of 2 m
// cells (centres 3 .. 13) cover it exactly. One more oak stands alone at (24, 8), outside the stand's
// columns.
constexpr double kCrownArea = 2.4;     // m^2
constexpr double kRegionArea = 144.0;  // m^2, 12 x 12
constexpr int kStandTrees = 9;

// Species oak (crown leaf area index `crown_lai`, `leaves` a flow map or empty), one stand of it over
// [2, 14]^2 with the rest of its entry `stand` (layout, spacing, maybe leaf_area_index), and the lone oak.
std::string stand_scenario(double crown_lai, const std::string& stand, const std::string& leaves = "") {
  return "scenario: plan_stand\nseed: 4\n"
         "time: {end: 1.0}\n"
         "domain: {size: [32, 16, 8], cell_size: 2.0}\n"
         "wind: {speed: 5.0, direction: 270}\n"
         "forest:\n"
         "  species:\n"
         "    - name: oak\n"
         "      skeleton: {file: tree.tree}\n"
         "      modes: {count: 4, wind_samples: 2}\n" +
         fmt::format("      canopy: {{leaf_area_index: {}}}\n", crown_lai) +
         (leaves.empty() ? std::string() : "      leaves: " + leaves + "\n") +
         "  stands:\n"  // the stand's entry is on line 13 (14 with leaves)
         "    - {species: oak, region: {min: [2, 2], max: [14, 14]}, " +
         stand +
         "}\n"
         "  trees:\n"
         "    - {species: oak, position: [24, 8]}\n";
}

fw::host::SimulationPlan stand_plan(const TempDir& dir, const std::string& name, const std::string& text) {
  dir.write("tree.tree", kTreeFile);
  return fw::host::plan_simulation(fw::io::load_scenario(dir.write(name + ".yaml", text)), nullptr, nullptr);
}

// Sum over kTreeFile's elements of D L, D = r_a + r_b (the wood's frontal area, trees/CanopyDrag.hpp), m^2.
double woody_area(const TempDir& dir) {
  const fw::trees::Skeleton tree = fw::trees::read_tree_file(dir.write("tree.tree", kTreeFile));
  double area = 0.0;
  for (const auto& [parent, child] : tree.elements()) {
    const auto& a = tree.node(parent);
    const auto& b = tree.node(child);
    area += (a.radius + b.radius) * (b.position - a.position).norm();
  }
  return area;
}

}  // namespace

TEST_CASE("SimulationPlan: a stand's leaf and frontal area index are those of the stand worked out by hand",
          "[simulation][plan]") {
  TempDir dir("fw_plan");
  constexpr double kCrownLai = 10.0;
  const auto plan = stand_plan(dir, "hand", stand_scenario(kCrownLai, "layout: grid, spacing: 4.5"));
  REQUIRE(plan.stands.size() == 1);
  const fw::host::StandPlan& stand = plan.stands[0];
  const fw::trees::StandDensity& density = stand.density;
  REQUIRE(density.trees == kStandTrees);
  CHECK(stand.first_instance == 0);
  CHECK(stand.forest_species == 0);  // the species' own basis: the stand gives no leaf area index
  CHECK(density.ground_area == kRegionArea);
  CHECK(density.columns == 36);  // 6 x 6 columns of 2 m
  CHECK(density.column_ground_area == kRegionArea);
  // The crown hull as the foliage computes it (exact, up to the rounding of the hull's shoelace sum).
  CHECK(fw::trees::Foliage::of(plan.forest.species()[0].skeleton(), 1.0).crown_projected_area ==
        Approx(kCrownArea).epsilon(1e-12));

  // LAI = N x (crown LAI x crown area) / region area = 9 x 24 / 144. The leaf areas come from the world
  // skeletons (turned and moved), whose hulls equal the species' to rounding: 1e-12 relative.
  const double lai = kStandTrees * kCrownLai * kCrownArea / kRegionArea;
  CHECK(density.leaf_area_index() == Approx(lai).epsilon(1e-12));
  CHECK(density.forest_like());
  // FAI = N x (wood + leaves) / the columns' ground, every element inside the columns. The field sums in
  // double over pieces clipped at the cells, so only rounding separates the two: 1e-10 relative.
  const double fai = kStandTrees * (woody_area(dir) + kCrownLai * kCrownArea) / kRegionArea;
  CHECK(density.frontal_area_index() == Approx(fai).epsilon(1e-10));
  CHECK(plan.warnings.empty());

  // check prints both figures, and no line for the lone tree.
  std::ostringstream out;
  fw::host::print_plan(plan, out);
  INFO(out.str());
  CHECK_THAT(out.str(), Contains(fmt::format("stand 0: 9 oak trees on 12 x 12 m, leaf area index {:.2f} (the "
                                             "species' 10 a crown), frontal area index {:.2f} over 36 grid "
                                             "columns\n",
                                             lai, fai)));
  CHECK(out.str().find("stand 1") == std::string::npos);
}

TEST_CASE(
    "SimulationPlan: a stand denser or sparser than any forest warns and names its keys, a forest's does not",
    "[simulation][plan]") {
  TempDir dir("fw_plan");
  // 9 x 9 trees 1.5 m apart carry 81 x 24 m^2 of leaves on 144 m^2: LAI 13.5, above 12.
  const std::string dense_file = dir.path() + "/dense.yaml";
  const auto dense = stand_plan(dir, "dense", stand_scenario(10.0, "layout: grid, spacing: 1.5"));
  REQUIRE(dense.stands[0].density.trees == 81);
  CHECK(dense.stands[0].density.leaf_area_index() == Approx(13.5).epsilon(1e-12));
  REQUIRE(dense.warnings.size() == 1);
  const std::string& warning = dense.warnings[0];
  INFO(warning);
  CHECK_THAT(warning,
             StartsWith(dense_file + ":13: forest.stands[0]: the oak stand's leaf area index is 13.5 "));
  CHECK_THAT(warning, Contains("above the 0.3 to 12 of forests"));
  CHECK_THAT(warning, Contains("forest.stands[0].spacing 1.5 m"));
  CHECK_THAT(warning, Contains("forest.species[0].canopy.leaf_area_index 10 (per crown)"));
  CHECK_THAT(warning, Contains("forest.stands[0].leaf_area_index"));

  // Crowns at leaf area index 1 on the hand-worked grid: LAI 0.15, below 0.3.
  const auto sparse = stand_plan(dir, "sparse", stand_scenario(1.0, "layout: grid, spacing: 4.5"));
  CHECK(sparse.stands[0].density.leaf_area_index() == Approx(0.15).epsilon(1e-12));
  REQUIRE(sparse.warnings.size() == 1);
  CHECK_THAT(sparse.warnings[0], Contains("below the 0.3 to 12 of forests"));

  // A stand given a leaf area index outside the range names that key.
  const auto given =
      stand_plan(dir, "given", stand_scenario(3.0, "layout: grid, spacing: 4.5, leaf_area_index: 15"));
  REQUIRE(given.warnings.size() == 1);
  CHECK_THAT(given.warnings[0], Contains("forest.stands[0].leaf_area_index 15 sets it: lower it"));

  // LAI 1.5 (the hand-worked stand) and a poisson stand of the same crowns: no warning.
  CHECK(stand_plan(dir, "forest", stand_scenario(10.0, "layout: grid, spacing: 4.5")).warnings.empty());
  const auto poisson = stand_plan(dir, "poisson", stand_scenario(10.0, "spacing: 3.0"));
  INFO("poisson LAI " << poisson.stands[0].density.leaf_area_index());
  CHECK(poisson.stands[0].density.forest_like());
  CHECK(poisson.warnings.empty());
}

TEST_CASE(
    "SimulationPlan: a stand's own leaf area index scales its trees' foliage, leaves and canopy density to "
    "it",
    "[simulation][plan]") {
  TempDir dir("fw_plan");
  constexpr double kSpeciesLai = 3.0, kStandLai = 4.0;
  const std::string leaves = "{area: 0.01, fraction: 0.1}";
  const auto plan = stand_plan(
      dir, "own", stand_scenario(kSpeciesLai, "layout: grid, spacing: 4.5, leaf_area_index: 4", leaves));
  const fw::host::StandPlan& stand = plan.stands[0];
  REQUIRE(stand.leaf_area_index == kStandLai);

  // The stand's trees get a basis of their own, after the species'; the lone oak keeps the species'.
  REQUIRE(plan.forest.species().size() == 2);
  CHECK(stand.forest_species == 1);
  for (int k = 0; k < kStandTrees; ++k) CHECK(plan.forest.instances()[std::size_t(k)].species == 1);
  CHECK(plan.forest.instances()[kStandTrees].species == 0);
  REQUIRE(plan.species.size() == 2);
  CHECK(plan.species[1].name == "oak (stand 0)");
  CHECK(plan.species[0].trees == 1);
  CHECK(plan.species[1].trees == kStandTrees);
  // Each crown carries LAI x region / (N x crown area): 4 x 144 / (9 x 2.4) = 26.67 per crown hull area.
  const double crown_lai = kStandLai * kRegionArea / (kStandTrees * kCrownArea);
  CHECK(stand.crown_leaf_area_index == Approx(crown_lai).epsilon(1e-12));
  CHECK(plan.forest.species()[1].settings().wind.leaf_area_index == stand.crown_leaf_area_index);
  CHECK(plan.forest.species()[0].settings().wind.leaf_area_index == kSpeciesLai);
  // The same modes (foliage weighs nothing), another wind basis: more foliage, more load.
  CHECK(plan.forest.species()[1].modes().frequencies_hz() ==
        plan.forest.species()[0].modes().frequencies_hz());
  CHECK(plan.forest.species()[1].wind().projection_matrix().norm() >
        plan.forest.species()[0].wind().projection_matrix().norm());

  // The stand's LAI is the figure given (to the rounding of the crown hulls: 1e-12), and its FAI is the
  // wood's plus that figure, every element inside the columns (rounding of the cell sums: 1e-10).
  CHECK(stand.density.leaf_area_index() == Approx(kStandLai).epsilon(1e-12));
  const double fai = kStandTrees * woody_area(dir) / kRegionArea + kStandLai;
  CHECK(stand.density.frontal_area_index() == Approx(fai).epsilon(1e-10));
  CHECK(plan.warnings.empty());

  // Leaves follow the foliage: round(fraction x leaf area / area) on each, the stand's with its own.
  REQUIRE(plan.coupling.leaves.size() == 2);
  CHECK(plan.coupling.leaves[0].count() == std::lround(0.1 * kSpeciesLai * kCrownArea / 0.01));
  CHECK(plan.coupling.leaves[1].count() == std::lround(0.1 * crown_lai * kCrownArea / 0.01));
  CHECK(plan.leaf_count == plan.coupling.leaves[0].count() + kStandTrees * plan.coupling.leaves[1].count());

  std::ostringstream out;
  fw::host::print_plan(plan, out);
  INFO(out.str());
  CHECK_THAT(out.str(),
             Contains("stand 0: 9 oak trees on 12 x 12 m, leaf area index 4.00 (given; 26.7 a crown)"));
  CHECK_THAT(out.str(), Contains("species oak (stand 0): "));
}

TEST_CASE(
    "SimulationPlan: a stand's own leaf area index on crowns that cannot carry leaves names the key's line",
    "[simulation][plan]") {
  TempDir dir("fw_plan");
  // A vertical stick: its crown hull has no area, so no foliage can give the stand a leaf area index.
  dir.write("stick.tree", "0 -1 0 0 0 0.1\n1 0 0 0 1 0.08\n2 1 0 0 2 0.05\n");
  std::string text = stand_scenario(3.0, "spacing: 4.0,\n       leaf_area_index: 2");
  text.replace(text.find("tree.tree"), 9, "stick.tree");
  const std::string path = dir.write("stick.yaml", text);
  try {
    fw::host::plan_simulation(fw::io::load_scenario(path), nullptr, nullptr);
    FAIL("the plan accepted a stand leaf area index on a crown without area");
  } catch (const fw::io::ScenarioError& error) {
    INFO(error.what());
    CHECK(error.line() == 14);
    CHECK(error.key() == "forest.stands[0].leaf_area_index");
    CHECK_THAT(std::string(error.what()), StartsWith(path + ":14: forest.stands[0].leaf_area_index: "));
    CHECK_THAT(std::string(error.what()), Contains("no horizontal extent"));
  }
}

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

TEST_CASE("SimulationPlan: every forest species gets its model, a stand's own basis its species'",
          "[simulation][plan]") {
  TempDir dir("fw_plan");
  using fw::trees::TreeDynamics;
  // The modal scenario: no `dynamics`, so every species modal.
  const auto modal = plan_of(dir, "modal", "");
  REQUIRE(modal.coupling.dynamics.size() == 2);
  CHECK(modal.coupling.dynamics[0].model == TreeDynamics::modal);
  CHECK(modal.coupling.dynamics[1].model == TreeDynamics::modal);
  CHECK(modal.species[0].dynamics == "modal");

  // The stand's oak as springs (without `modes`, the springs' modes are the default ones): the stand's own
  // basis, after the species', carries the species' model and settings.
  std::string text = stand_scenario(3.0, "layout: grid, spacing: 4.5, leaf_area_index: 4");
  const std::string modes = "      modes: {count: 4, wind_samples: 2}\n";
  REQUIRE(text.find(modes) != std::string::npos);
  text.replace(text.find(modes), modes.size(),
               "      dynamics: springs\n      springs: {max_angle_deg: 15}\n");
  const auto plan = stand_plan(dir, "springs", text);
  REQUIRE(plan.forest.species().size() == 2);
  REQUIRE(plan.coupling.dynamics.size() == plan.forest.species().size());
  REQUIRE(plan.coupling.leaves.size() == plan.forest.species().size());
  for (const fw::trees::SpeciesDynamics& dynamics : plan.coupling.dynamics) {
    CHECK(dynamics.model == TreeDynamics::springs);
    CHECK(dynamics.springs.max_angle_deg == 15.0);
  }
  // check's summary names the model of each.
  std::ostringstream out;
  fw::host::print_plan(plan, out);
  INFO(out.str());
  CHECK_THAT(out.str(), Contains("species oak: springs, "));
  CHECK_THAT(out.str(), Contains("species oak (stand 0): springs, "));
}

TEST_CASE(
    "SimulationPlan: a rigid or springs species on a small skeleton keeps the modes it has, a modal one "
    "is refused",
    "[simulation][plan]") {
  TempDir dir("fw_plan");
  // A vertical stick of 3 nodes: 12 DOFs, fewer than the default 20 modes.
  dir.write("stick.tree", "0 -1 0 0 0 0.1\n1 0 0 0 1 0.08\n2 1 0 0 2 0.05\n");
  const auto text = [](const std::string& dynamics) {
    return "scenario: plan_stick\ntime: {end: 1.0}\n"
           "domain: {size: [16, 16, 8], cell_size: 2.0}\n"
           "wind: {speed: 5.0, direction: 270}\n"
           "forest:\n"
           "  species:\n"
           "    - name: stick\n"  // line 7
           "      skeleton: {file: stick.tree}\n"
           "      dynamics: " +
           dynamics +
           "\n"
           "  trees:\n"
           "    - {species: stick, position: [8, 8]}\n";
  };
  constexpr int kStickModes = 11;  // 12 DOFs less one
  for (const char* model : {"rigid_bodies", "springs"}) {
    INFO(model);
    const auto plan = stand_plan(dir, model, text(model));
    REQUIRE(plan.species.size() == 1);
    CHECK(plan.species[0].modes == kStickModes);
    CHECK(plan.species[0].dynamics == model);
  }
  // A modal species keeps the count the file gives, or its default, and is refused past the DOFs.
  const std::string path = dir.write("modal.yaml", text("modal"));
  try {
    fw::host::plan_simulation(fw::io::load_scenario(path), nullptr, nullptr);
    FAIL("the plan accepted 20 modes on 12 DOFs");
  } catch (const fw::io::ScenarioError& error) {
    INFO(error.what());
    CHECK(error.line() == 7);
    CHECK(error.key() == "forest.species[0].modes.count");
  }
}

TEST_CASE("SimulationPlan: check names the subgrid model and the constant the solver gets") {
  TempDir dir("fw_plan_subgrid");
  const auto solver_line = [&](const std::string& solver) {
    const std::string text =
        "scenario: plan_subgrid\nseed: 4\ntime: {end: 1.0}\n"
        "domain: {size: [16, 16, 8], cell_size: 2.0}\n"
        "wind: {speed: 5.0, direction: 270}\n"
        "solver: " +
        solver + "\n";
    std::ostringstream out;
    fw::host::print_plan(stand_plan(dir, "subgrid", text), out);
    return out.str();
  };
  // upwind5 names no constant and gets the measured one; the other schemes get none unless asked.
  CHECK_THAT(solver_line("{advection: upwind5}"),
             Contains("advection: upwind5, subgrid: smagorinsky, C_s 0.16, pressure:"));
  CHECK_THAT(solver_line("{advection: maccormack}"),
             Contains("advection: maccormack, subgrid: none (smagorinsky, C_s 0), pressure:"));
  CHECK_THAT(solver_line("{advection: maccormack, smagorinsky_constant: 0.12}"),
             Contains("subgrid: smagorinsky, C_s 0.12,"));
  CHECK_THAT(solver_line("{advection: upwind5, subgrid: tke}"), Contains("subgrid: tke, pressure:"));
}

TEST_CASE("SimulationPlan: the grid's blocks over the ranks, given or chosen, and a split that cannot work",
          "[plan]") {
  TempDir dir("fw_plan_blocks");
  const auto plan_with = [&](const std::string& name, const std::string& decomposition, int ranks) {
    std::string text = scenario_text("");
    const std::string domain = "domain: {size: [16, 16, 8], cell_size: 2.0}";
    text.replace(text.find(domain), domain.size(),
                 "domain: {size: [16, 16, 8], cell_size: 2.0" + decomposition + "}");
    dir.write("tree.tree", kTreeFile);
    return fw::host::plan_simulation(fw::io::load_scenario(dir.write(name + ".yaml", text)), nullptr, nullptr,
                                     ranks);
  };
  // 8 x 8 cells: 2 ranks take 1 x 2 blocks of 4 cells (2 x 1 exchanges as much; whole rows first).
  CHECK(plan_with("chosen", "", 2).decomposition.describe() == "1 x 2 blocks of 8 x 4 x 4 cells");
  CHECK(plan_with("given", ", decomposition: [1, 2]", 2).decomposition.blocks() == std::array<int, 2>{1, 2});
  // One process ignores the file's blocks, so that the same scenario runs alone.
  CHECK(plan_with("alone", ", decomposition: [1, 2]", 1).decomposition.ranks() == 1);
  // 8 cells with a halo of 3 take at most 2 blocks along an axis.
  CHECK_THROWS_WITH(plan_with("too_many", ", decomposition: [4, 1]", 4),
                    Catch::Contains("too_many.yaml:4: domain.decomposition: 4 blocks along x need at least 3 "
                                    "cells each"));
}

TEST_CASE(
    "SimulationPlan: check's plan reports what a run's does, the turbulence box priced and the leaves "
    "counted without building either",
    "[simulation][plan]") {
  TempDir dir("fw_plan_check");
  dir.write("tree.tree", kTreeFile);
  const std::string text =
      "scenario: plan_check\nseed: 4\n"
      "time: {end: 1.0}\n"
      "domain: {size: [16, 16, 8], cell_size: 2.0}\n"
      "wind: {speed: 5.0, direction: 270, turbulence: {intensity: 0.1, length_scale: 4}}\n"
      "forest:\n"
      "  species:\n"
      "    - name: oak\n"
      "      skeleton: {file: tree.tree}\n"
      "      modes: {count: 4, wind_samples: 2}\n"
      "      canopy: {leaf_area_index: 3.0}\n"
      "      leaves: {area: 0.002}\n"
      "  trees:\n"
      "    - {species: oak, position: [8, 8]}\n";
  const fw::io::Scenario scenario = fw::io::load_scenario(dir.write("check.yaml", text));
  const fw::host::SimulationPlan run = fw::host::plan_simulation(scenario, nullptr, nullptr);
  const fw::host::SimulationPlan check =
      fw::host::plan_simulation(scenario, nullptr, nullptr, 1, fw::host::PlanFor::check);
  // The run's plan holds the box and the leaves; check's their spec and count.
  REQUIRE(run.wind.turbulence != nullptr);
  CHECK(check.wind.turbulence == nullptr);
  REQUIRE(check.turbulence_box.has_value());
  CHECK(check.turbulence_box->cells == run.wind.turbulence->cells());
  REQUIRE(run.coupling.leaves.size() == 1);
  REQUIRE(run.coupling.leaves[0].count() > 0);
  CHECK(run.coupling.leaves[0].leaves().size() == std::size_t(run.coupling.leaves[0].count()));
  CHECK(check.coupling.leaves[0].leaves().empty());
  CHECK(check.coupling.leaves[0].count() == run.coupling.leaves[0].count());
  CHECK(check.leaf_count == run.leaf_count);
  // The same memory, part by part (the box's from its spec: as many floats as the built box holds), and the
  // same report, line by line.
  CHECK(check.memory.total() == run.memory.total());
  REQUIRE(check.memory.parts().size() == run.memory.parts().size());
  for (std::size_t k = 0; k < run.memory.parts().size(); ++k) {
    INFO(run.memory.parts()[k].name);
    CHECK(check.memory.parts()[k].bytes == run.memory.parts()[k].bytes);
  }
  std::ostringstream run_report, check_report;
  fw::host::print_plan(run, run_report);
  fw::host::print_plan(check, check_report);
  CHECK(check_report.str() == run_report.str());
  CHECK_THAT(check_report.str(), Contains("inflow turbulence"));
}
