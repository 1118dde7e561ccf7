// A stage's share of a checkpoint saved over other blocks (docs/design.md "Long runs", docs/parallel.md): the
// parts every rank saved, as a stage reads them to take this rank's share. The redistribution
// (host/app/CheckpointRedistribution) hands each stage its parts, and the stage says what it takes: the
// wind grid the arrays its parts declare (WindPart::saved_arrays), the trees each tree's slices, the leaves
// each leaf's slot.
//
//   std::vector<fw::host::SavedShare> parts = ...;   // the wind stage of each rank of the saved run
//   fw::host::StageState mine = wind.share_of(parts);  // this rank's block of every saved array, halo too
//   wind.restore_state(mine);
#pragma once

#include <fmt/format.h>

#include <algorithm>
#include <cstdint>
#include <cstring>
#include <stdexcept>
#include <string>
#include <vector>

#include "fluid/GridSpec.hpp"
#include "host/runtime/ComputeContext.hpp"
#include "host/stages/BlockGrid.hpp"
#include "host/stages/StageState.hpp"

namespace fw::host {

/// One rank's part of a checkpoint, as one stage sees it: that stage's saved state, the rank's block of the
/// wind grid (with its halo) and the trees it held (Forest::id), in its order.
struct SavedShare {
  const StageState* state = nullptr;
  BlockArray block;
  std::vector<int> tree_ids;
};

/// A saved array of the wind grid and where its values lie: the cells (component -1) or the faces of
/// velocity component 0, 1 or 2.
struct GridArray {
  const char* name = "";
  int component = -1;
};

/// `count` values of T from the start of a saved array's bytes; throws std::invalid_argument naming the
/// array when it holds fewer.
template <typename T>
std::vector<T> saved_values(const std::vector<std::uint8_t>& bytes, std::size_t count,
                            const std::string& name) {
  if (bytes.size() < count * sizeof(T))
    throw std::invalid_argument(
        fmt::format("checkpoint: the saved \"{}\" holds {} bytes, {} expected: it is another run's", name,
                    bytes.size(), count * sizeof(T)));
  std::vector<T> values(count);
  if (count > 0) std::memcpy(values.data(), bytes.data(), count * sizeof(T));
  return values;
}

/// Values as the device allocates them: at least ComputeContext::kMinimumBufferBytes.
template <typename T>
std::vector<std::uint8_t> saved_bytes(const std::vector<T>& values) {
  std::vector<std::uint8_t> bytes(std::max(values.size() * sizeof(T), ComputeContext::kMinimumBufferBytes),
                                  0);
  if (!values.empty()) std::memcpy(bytes.data(), values.data(), values.size() * sizeof(T));
  return bytes;
}

/// The cell columns a block owns, without its halo: x from lo[0] to hi[0] - 1, y from lo[1] to hi[1] - 1.
struct OwnColumns {
  std::array<int, 2> lo{0, 0}, hi{0, 0};
  bool holds(int i, int j) const { return i >= lo[0] && i < hi[0] && j >= lo[1] && j < hi[1]; }
};
OwnColumns own_columns(const BlockArray& cells);

}  // namespace fw::host
