// The scenario keys that a run's state depends on, each with a hash of its value, so that a checkpoint can
// refuse a scenario whose state it does not hold (docs/design.md "Long runs").
//
//   std::vector<fw::io::StateKey> saved = fw::io::state_keys(text_when_checkpointed);
//   fw::io::require_same_state(saved, fw::io::state_keys(text_now), "storm.yaml");   // SourceError if not
//
// A resumed run may change time.end (to extend the run), output (any of it) and the scenario's name; every
// other key must keep its value, because it changes what the saved fields mean or how the run goes on from
// them: the grid, the boundaries, the wind, the events, the solids, the forest, the solver, the seed and
// the time step. A top-level map is checked key by key ("domain.size", "forest.species", "time.dt"), so an
// error names the key that changed. A value is compared as YAML data, not text: comments, spacing and flow
// or block style do not matter, but writing out a default that was left implicit does. Files the scenario
// names (skeletons, heightmaps) are compared through what they make: the run's state arrays must fit.
#pragma once

#include <cstdint>
#include <string>
#include <vector>

namespace fw::io {

struct StateKey {
  std::string key;         ///< dotted: "seed", "domain.size"
  int line = 0;            ///< 1-based line of the key in the text it was read from
  std::uint64_t hash = 0;  ///< FNV-1a of the value's canonical form
};

/// The state keys of a scenario's YAML text (which must parse: load_scenario has checked it), in file order.
std::vector<StateKey> state_keys(const std::string& scenario_text);

/// Throws base::SourceError("FILE:LINE: KEY: ...") for the first key whose value is not `saved`'s, or that
/// one of them has and the other lacks; file: the current scenario's path, for the message.
void require_same_state(const std::vector<StateKey>& saved, const std::vector<StateKey>& current,
                        const std::string& file);

}  // namespace fw::io
