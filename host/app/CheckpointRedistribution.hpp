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
// The wind's arrays (velocity, pressure solution, eddy viscosity, subgrid energy) are put together over the
// whole domain from each part's own cells (a halo is a copy of its neighbour's) and cut to this rank's block
// with its halo, as the run cuts the solids (block_of). A tree's modal state and travelled distance go to the
// rank that holds its root. A leaf's flutter angle and rate stay with its tree. Where a leaf is (its slot:
// state, position, velocity, normal, flight and drag) goes to its tree's rank while it is attached, has left
// the domain or lies in that rank's own columns; a flying or landed leaf elsewhere goes to the rank whose own
// columns hold it, after that rank's own leaves in (tree, leaf) order, as leaves that arrive in a step are,
// and its tree's slot is marked moved. The leaf counters' totals go to rank 0, whose counts are summed
// anyway. Each rank reads every part: for a resume, this rank holds the whole state once.
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
