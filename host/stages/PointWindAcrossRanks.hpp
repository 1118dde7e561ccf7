// The wind at points anywhere in the domain over MPI ranks (docs/parallel.md): each point is sampled by the
// rank whose block holds it, and its wind goes back to the rank that needs it (the trees' samples in a
// neighbour's block, every probe for rank 0).
//
//   fw::host::PointWindAcrossRanks remote(cc, local_spec, blocks, needed);   // needed: 3 floats a point, m
//   std::vector<float> wind = remote.exchange(grid.velocity());         // 3 floats a point, m/s
//
// Collective: every rank constructs one and calls exchange() at the same steps, each with its own points
// (none is fine). The holder samples with kernels/probe_sample.cl from its block's cells and halo. The
// point's cell lies in the holder's cells, so the sample's corners lie within a cell of them (two, where the
// host's double and the device's float disagree on the cell), inside the halo of at least FW_PAD cells; and a
// block samples in the domain's indices (sample_mac_component), so the wind is the bits one process samples.
// Alone (no blocks, or one rank) the rank holds every point and exchange() samples them itself.
#pragma once

#include <memory>
#include <vector>

#include "fluid/GridSpec.hpp"
#include "host/runtime/ComputeContext.hpp"
#include "host/stages/BlockGrid.hpp"
#include "host/stages/FluidStages.hpp"
#include "host/stages/PointWindReadback.hpp"

namespace fw::host {

class PointWindAcrossRanks {
 public:
  /// The rank whose block holds the cell column of `point` (world, m; clamped into the domain). spec: a
  /// rank's grid (its block_domain the domain's cells) or the whole grid.
  static int holder(const fluid::GridSpec& spec, const fluid::Decomposition& decomposition,
                    const float point[3]);

  /// spec: this rank's grid (block_spec, or the whole grid alone); blocks: null alone; needed: 3 floats a
  /// point, world frame, m, as the device rounds them. Collective. Throws std::invalid_argument (from
  /// PointWindReadback) for a position that is not finite.
  PointWindAcrossRanks(ComputeContext& cc, const fluid::GridSpec& spec, const WindBlocks* blocks,
                       const std::vector<float>& needed);

  int point_count() const { return int(order_.size()); }
  /// The points other ranks asked this one for (and its own that it holds).
  int request_count() const { return requests_ ? requests_->point_count() : 0; }
  /// The wind at every needed point, 3 floats a point, m/s, in the constructor's order. Collective; blocks.
  std::vector<float> exchange(DeviceVelocity& velocity);

 private:
  const Communicator* world_;
  std::vector<int> holder_of_;       // per needed point: the rank that samples it
  std::vector<int> order_;           // per needed point: its place in its holder's list
  std::vector<int> request_counts_;  // per rank: the points it asked this one for
  std::unique_ptr<PointWindReadback> requests_;
};

}  // namespace fw::host
