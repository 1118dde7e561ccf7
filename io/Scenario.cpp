// The Scenario's own functions past its wind's (io/WindScenario.cpp): the probes' interval, the checks of a
// species on its skeleton. Reading a file into it is io/scenario/ (load_scenario: io/scenario/Load.cpp).
#include "io/Scenario.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <cstddef>

#include "io/ScenarioSchema.hpp"

namespace fw::io {

std::optional<double> Scenario::resolved_probe_interval() const {
  if (output.probe_interval) return output.probe_interval;
  if (wind.turbulence) return std::nullopt;  // every solver step, for spectra
  return output.interval;
}

namespace {

// A skeleton of n nodes, root clamped, has 6 (n - 1) DOFs; the modal analysis keeps fewer modes than that.
constexpr long kDofsPerNode = 6;

long skeleton_dofs(int skeleton_nodes) {
  return kDofsPerNode * (skeleton_nodes - 1);
}

}  // namespace

void check_species_skeleton(const Scenario& scenario, int species_index, int skeleton_nodes) {
  const Species& species = scenario.forest.species.at(std::size_t(species_index));
  if (species.dynamics.model != trees::TreeDynamics::modal) return;  // its count is not the file's
  const long dofs = skeleton_dofs(skeleton_nodes);
  if (species.modes.count >= dofs) {
    throw ScenarioError(
        scenario.file.string(), species.modes.count_line,
        schema::item_path(schema::key(schema::kSpeciesKeys, "forest.species[].modes.count").path,
                          std::size_t(species_index)),
        fmt::format("at most {} modes for this skeleton of {} nodes ({} DOFs) expected, got '{}'",
                    std::max(0L, dofs - 1), skeleton_nodes, dofs, species.modes.count));
  }
}

int species_mode_count(const Scenario& scenario, int species_index, int skeleton_nodes) {
  const Species& species = scenario.forest.species.at(std::size_t(species_index));
  if (species.dynamics.model == trees::TreeDynamics::modal) return species.modes.count;
  return int(std::clamp(skeleton_dofs(skeleton_nodes) - 1, 1L, long(species.modes.count)));
}

}  // namespace fw::io
