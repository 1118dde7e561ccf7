// Fuzz target: the scenario loader and the planner, as deep as `forestwind check` goes without a device.
// Feeds: the bytes as a scenario file (YAML, the schema, muparser expressions; scratch/scenario.yaml, next
// to a copy of scenarios/hills.pgm and a three-node tree.tree that seeds may name), then, when it loads, the
// plan `check` builds (host::PlanFor::check: species bases computed without a cache, leaves counted, the
// turbulence box priced from its spec, forest, coupling, outputs), the plan report and the planned time
// steps. Clean refusals: io::ScenarioError, base::SourceError and any other std::invalid_argument (what
// `check` exits 2 on) whose message names a file of the scratch folder ("FILE:LINE: KEY: ..."). A modal
// problem that cannot be solved is the species' fault, refused so too (issue 44). Bugs: anything else: a
// crash, a sanitizer report, another exception (length_error, bad_alloc, a runtime_error, a trees::ModalError
// that escapes), an unnamed file, a hang, a huge allocation.
#include <cstdint>
#include <filesystem>
#include <ostream>
#include <streambuf>

#include "host/app/SimulationPlan.hpp"
#include "io/Scenario.hpp"
#include "tests/fuzz/FuzzSupport.hpp"

namespace {

// Discards what the plan report prints.
class NullBuffer : public std::streambuf {
 protected:
  int overflow(int c) override { return c; }
};

// The files the example scenarios and the CLI tests name, beside the fuzzed scenario.
void place_named_files() {
  static const bool placed = [] {
    const auto& folder = fw::fuzz::scratch_folder();
    std::filesystem::copy_file(std::filesystem::path(FORESTWIND_SOURCE_DIR) / "scenarios/hills.pgm",
                               folder / "hills.pgm", std::filesystem::copy_options::overwrite_existing);
    static constexpr char kTree[] = "0 -1 0 0 0 0.1\n1 0 0 0 1 0.08\n2 1 0 0 2 0.05\n";
    fw::fuzz::write_input("tree.tree", reinterpret_cast<const std::uint8_t*>(kTree), sizeof kTree - 1);
    return true;
  }();
  (void)placed;
}

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  place_named_files();
  const auto path = fw::fuzz::write_input("scenario.yaml", data, size);
  try {
    const fw::io::Scenario scenario = fw::io::load_scenario(path);
    const fw::host::SimulationPlan plan =
        fw::host::plan_simulation(scenario, nullptr, nullptr, 1, fw::host::PlanFor::check);
    NullBuffer discard;
    std::ostream report(&discard);
    fw::host::print_plan(plan, report);
    report << fw::host::planned_dt(plan) << fw::host::planned_spin_up_steps(plan);
  } catch (const std::invalid_argument& e) {
    fw::fuzz::expect_names_file(e, fw::fuzz::scratch_folder());
  }
  return 0;
}
