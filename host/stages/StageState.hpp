// What a stage carries from one step to the next, copied back for a checkpoint (docs/design.md "Long runs"):
// named device buffers byte for byte, and named numbers (times, offsets, integrals, counts) as doubles. A
// stage restores from what it saved and nothing else, so a resumed step sees the bits it would have seen.
//
//   fw::host::StageState state = wind.save_state();      // blocking reads
//   ...                                                  // into a checkpoint and back
//   (host/app/RunCheckpoint) wind.restore_state(state);                           // std::invalid_argument
//   naming what does not fit
//
// Names are the stage's own ("u", "phi", "time"); the run layer prefixes them with the stage's name.
#pragma once

#include <cstdint>
#include <map>
#include <string>
#include <vector>

#include "host/runtime/ComputeContext.hpp"

namespace fw::host {

struct StageState {
  std::map<std::string, std::vector<std::uint8_t>> buffers;  ///< whole device buffers, their bytes
  std::map<std::string, std::vector<double>> numbers;        ///< host values, exact in a double

  /// Copies the whole of `buffer` back under `name` (blocking).
  void save(ComputeContext& cc, const std::string& name, cl::Buffer& buffer);
  /// Writes the bytes saved under `name` back into `buffer` (blocking). Throws std::invalid_argument naming
  /// `stage` and `name` when they are missing or the buffer's size differs.
  void restore(ComputeContext& cc, const std::string& stage, const std::string& name,
               cl::Buffer& buffer) const;
  /// The numbers saved under `name`; throws std::invalid_argument naming `stage` and `name` unless there
  /// are `count` of them.
  const std::vector<double>& number(const std::string& stage, const std::string& name,
                                    std::size_t count) const;
  /// The bytes saved under `name`; throws std::invalid_argument naming `stage` and `name` when missing.
  const std::vector<std::uint8_t>& bytes(const std::string& stage, const std::string& name) const;
};

}  // namespace fw::host
