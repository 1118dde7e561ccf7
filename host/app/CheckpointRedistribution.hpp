// A checkpoint written over other MPI ranks or blocks, redistributed over this run's (docs/design.md "Long
// runs", docs/parallel.md): a run checkpointed in one process goes on over 4 ranks, or one of 2 x 2 ranks in
// one process, and the run is bit for bit the one that never stopped wherever the run over ranks is bit for
// bit the run in one process.
//
//   fw::host::CheckpointParts read = fw::host::read_checkpoint(folder, world, plan.decomposition.describe());
//   fw::host::RunSnapshot mine =
//       read.own ? read.parts.front() : fw::host::redistribute_checkpoint(read.parts, coupled, plan);
//   coupled.restore_state(mine.stages);
//
// The redistribution hands each stage every part's saved state, with the part's block and trees
// (SavedShare), and the stage takes this rank's share: the wind grid the arrays its parts declare
// (WindGrid::share_of), put together over the domain from each part's own cells and cut to this rank's block
// with its halo; the trees each tree's slices (ForestStages::share_of), for the trees whose roots this rank
// holds; the leaves each leaf's slot and flutter (LeafStages::share_of). Each rank reads every part: for a
// resume, this rank holds the whole state once.
#pragma once

#include <vector>

#include "host/app/CoupledStep.hpp"
#include "host/app/RunCheckpoint.hpp"
#include "host/app/SimulationPlan.hpp"

namespace fw::host {

/// This rank's snapshot of `parts` (every part of one checkpoint, read_checkpoint) for `coupled`, the step of
/// `plan` built over this run's ranks (its blocks and own trees say what this rank holds). Throws
/// std::invalid_argument naming what does not fit (a part of another grid or forest).
RunSnapshot redistribute_checkpoint(const std::vector<RunSnapshot>& parts, CoupledStep& coupled,
                                    const SimulationPlan& plan);

}  // namespace fw::host
