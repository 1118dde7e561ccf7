// io/ScenarioStateKeys: the keys a checkpoint's state depends on, compared as YAML data; a resume may change
// only time.end and output, and an error names the key and its line.
#include "io/ScenarioStateKeys.hpp"

#include <catch2/catch.hpp>

#include <string>

#include "base/SourceError.hpp"

namespace {

const std::string kScenario =
    "scenario: a\nseed: 3\ntime: {end: 10.0, dt: auto}\n"
    "domain: {size: [64, 32, 16], cell_size: 2.0}\n"
    "wind: {speed: 5.0, direction: 270}\n"
    "output: {directory: out, interval: 1.0}\n";

std::string refusal(const std::string& changed) {
  try {
    fw::io::require_same_state(fw::io::state_keys(kScenario), fw::io::state_keys(changed), "b.yaml");
  } catch (const fw::base::SourceError& e) {
    return e.what();
  }
  return "accepted";
}

}  // namespace

TEST_CASE(
    "ScenarioStateKeys: time.end, time.spin_up, output, the decomposition and the name may change, and "
    "layout "
    "and comments do not count",
    "[io]") {
  CHECK(refusal(kScenario) == "accepted");
  CHECK(refusal("# extended\nscenario: b\nseed: 3\ntime:\n  end: 60.0\n  dt: auto\n  spin_up: 5.0\n"
                "domain: {cell_size: 2.0, size: [64, 32, 16], decomposition: [2, 1]}\n"
                "wind:\n  speed: 5.0\n  direction: 270\n"
                "output: {directory: elsewhere, interval: 0.5, vdb: {enabled: true}}\n") == "accepted");
}

TEST_CASE("ScenarioStateKeys: a changed, added or removed key is refused with its file, line and name",
          "[io]") {
  const std::string expected = "the value the checkpoint was written with";
  std::string changed = kScenario;
  changed.replace(changed.find("[64, 32, 16]"), 12, "[64, 32, 24]");
  CHECK(refusal(changed).starts_with("b.yaml:4: domain.size: " + expected));
  changed = kScenario;
  changed.replace(changed.find("seed: 3"), 7, "seed: 4");
  CHECK(refusal(changed).starts_with("b.yaml:2: seed: " + expected));
  changed = kScenario;
  changed.replace(changed.find("dt: auto"), 8, "dt: 0.1");
  CHECK(refusal(changed).starts_with("b.yaml:3: time.dt: " + expected));
  CHECK(refusal(kScenario + "solver: {advection: upwind5}\n").starts_with("b.yaml:7: solver.advection: "));
  changed = kScenario;
  changed.erase(changed.find("seed: 3\n"), 8);
  CHECK(refusal(changed).starts_with("b.yaml: seed: " + expected));
}

TEST_CASE("ScenarioStateKeys: storm damage and the species' strength keep their values on a resume", "[io]") {
  // Which trees have failed is state: the keys that decide it are the forest's, which a resume may not
  // change.
  const std::string forest =
      "forest:\n"
      "  damage: {enabled: true}\n"
      "  species:\n"
      "    - {name: pine, skeleton: {generate: {preset: conifer}}, strength: {preset: scots_pine}}\n";
  const auto refused = [&](const std::string& changed) {
    try {
      fw::io::require_same_state(fw::io::state_keys(kScenario + forest),
                                 fw::io::state_keys(kScenario + changed), "b.yaml");
    } catch (const fw::base::SourceError& e) {
      return std::string(e.what());
    }
    return std::string("accepted");
  };
  CHECK(refused(forest) == "accepted");
  std::string changed = forest;
  changed.replace(changed.find("{enabled: true}"), 15, "{enabled: true, consequences: false}");
  CHECK(refused(changed).starts_with("b.yaml:8: forest.damage: the value the checkpoint was written with"));
  changed = forest;
  changed.replace(changed.find("{preset: scots_pine}"), 20, "{preset: scots_pine, soil: B}");
  CHECK(refused(changed).starts_with("b.yaml:9: forest.species: the value the checkpoint was written with"));
}
