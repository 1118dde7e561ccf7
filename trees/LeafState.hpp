// What a leaf is doing, and how many leaves are doing it (docs/leaves.md, "States and counts"): shared by the
// device stage, the CPU oracle and the writers.
#pragma once

#include <cstdint>

namespace fw::trees {

/// The same values as FW_LEAF_* in kernels/shared_types.h.
enum class LeafState : std::uint8_t { attached = 0, flying = 1, landed = 2, exited = 3 };

struct LeafCounts {
  long shed = 0;  ///< ever detached (flying + landed + exited)
  long flying = 0;
  long landed = 0;
  long exited = 0;
  long attached = 0;
};

}  // namespace fw::trees
