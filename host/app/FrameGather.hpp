// Over MPI ranks, the parts of a frame that a file of the whole domain holds (the VDB frames): rank 0
// gathers every rank's own faces of the velocity and every rank's leaves (docs/parallel.md, "Output over
// ranks").
//
//   frame.gathered = fw::host::gather_frame(frame, plan.wind.spec, blocks, wind.block(), /*leaves=*/true);
//   // rank 0: frame.gathered->velocity is the whole domain's, as one process downloads it
#pragma once

#include <optional>

#include "fluid/GridSpec.hpp"
#include "host/stages/BlockGrid.hpp"
#include "io/writers/FrameWriter.hpp"

namespace fw::host {

/// frame: this rank's velocity (its block with the halo, laid out as `cells`: WindGrid::block()) and its
/// leaves; whole: the domain's grid. Collective. On rank 0: the domain's faces, each from the rank whose
/// block holds the cell above it (the domain's last face along x or y from the last block), and every
/// rank's leaves in one process's order (by tree, then by leaf) when `leaves` (every rank alike); nullopt on
/// the other ranks.
std::optional<io::OutputFrame::Gathered> gather_frame(const io::OutputFrame& frame,
                                                      const fluid::GridSpec& whole, const WindBlocks& blocks,
                                                      const BlockArray& cells, bool leaves);

}  // namespace fw::host
