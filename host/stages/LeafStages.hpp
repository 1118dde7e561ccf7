// The leaves of a forest on the device (docs/design.md, "Data flow" 4; docs/leaves.md): flutter of attached
// leaves, shedding, flight in the resolved wind, landing and exits, every step; and on output frames every
// leaf's blade, the attached ones at their deformed anchors.
//
//   host::LeafStages leaves(cc, spec, forest, species_leaves);   // every instance's leaves, attached
//   leaves.enqueue_step(wind.stages().step(), mask, velocity);    // after the wind step, before the next
//   trees.enqueue_deform();                                       // output frame: the trees' displacements
//   leaves.enqueue_frame(trees.displacements());                  // attached leaves follow them
//   host::LeafSnapshot snap = leaves.download();                  // positions, normals, states
//   trees::LeafCounts counts = leaves.counts();                   // reads 3 counters back
//
// Kernels: kernels/leaves.cl. A step samples the wind once per site (a cell that holds the rest centre of
// a leaf), steps the flying leaves one at a time, then the attached ones FW_LANES at a time. The CPU oracle
// is trees/LeafReference. Flat leaf j: instances in order, each instance's species leaves in order.
#pragma once

#include <cstdint>
#include <limits>
#include <vector>

#include "fluid/GridSpec.hpp"
#include "host/runtime/ComputeContext.hpp"
#include "host/stages/FluidStages.hpp"
#include "kernels/shared_types.h"
#include "trees/Forest.hpp"
#include "trees/LeafState.hpp"
#include "trees/SpeciesLeaves.hpp"

namespace fw::host {

/// Every leaf's state copied back: 3 floats a leaf for position (m, world) and normal, a byte for the state
/// (trees::LeafState), the instance per leaf and the blade side (m).
struct LeafSnapshot {
  std::vector<float> position, normal;
  std::vector<std::uint8_t> state;
  std::vector<std::int32_t> tree_id;
  std::vector<float> side;
};

class LeafStages {
 public:
  /// Packs the leaves of every instance of `forest` (species_leaves: one per forest species, possibly empty)
  /// and uploads them, all attached at rest. Throws std::invalid_argument("LeafStages: ...") for an invalid
  /// grid, a species count that differs from the forest's, or more leaves than 32-bit indexing holds.
  LeafStages(ComputeContext& cc, const fluid::GridSpec& spec, const trees::Forest& forest,
             const std::vector<trees::SpeciesLeaves>& species_leaves);

  /// Most leaves of a forest: leaves are indexed with 32-bit integers, and each lane block may run FW_LANES
  /// past the last.
  static constexpr long long kMaxLeaves = std::numeric_limits<std::int32_t>::max() - FW_LANES;

  /// Bytes of device memory the constructor allocates, at most: per leaf its state, angle and rate, site
  /// and instance, five float4 (position, velocity, normal, the frame's position and normal) and at most one
  /// site of its own (a cell and its wind); per species leaf its rest table and element nodes; per instance
  /// its first leaf and block. Every per-leaf array is padded by FW_LANES.
  static std::size_t estimate_device_bytes(const trees::Forest& forest,
                                           const std::vector<trees::SpeciesLeaves>& species_leaves);

  int leaf_count() const { return leaf_count_; }

  /// One step of every leaf over step.dt, ending at step.time + step.dt, in the wind `vel` (the step's end
  /// velocity); mask: the pressure mask (FW_MASK_FLUID marks fluid cells).
  void enqueue_step(const FwStep& step, cl::Buffer& mask, DeviceVelocity& vel);
  /// Output frames: the attached leaves moved with the trees' displacements (3 floats per flat node, world
  /// frame: ForestStages::displacements() after enqueue_deform); download() then returns these positions.
  void enqueue_frame(cl::Buffer& displacements);
  /// Blocks. The blades at the last step's end: attached leaves at their deformed anchors when enqueue_frame
  /// ran since that step, else at their rest anchors.
  LeafSnapshot download();
  /// Blocks: shed, landed and exited from the device counters; flying and attached follow.
  trees::LeafCounts counts();

 private:
  /// The frame kernel: every leaf's blade at the last step's end into frame_position_ and frame_normal_.
  void enqueue_blades(cl::Buffer& displacements, bool displaced);

  ComputeContext& cc_;
  FwGrid grid_{};
  int leaf_count_ = 0, instance_count_ = 0;
  int block_count_ = 0;  // blocks of FW_LANES leaves of one instance (kernels/leaves.cl)
  int rest_stride_ = 0, site_count_ = 0, site_stride_ = 0;
  float time_ = 0.0f;  // the last step's end, s
  bool frame_ready_ = false;
  std::vector<std::int32_t> leaf_instance_host_;
  std::vector<float> side_host_;
  cl::Buffer leaf_instance_, first_leaf_, first_block_, instances_, leaf_species_, rest_, rest_nodes_;
  cl::Buffer leaf_site_, site_cells_, site_wind_;
  cl::Buffer state_, theta_, theta_rate_, position_, velocity_, normal_, frame_position_, frame_normal_;
  cl::Buffer counters_, no_displacements_;
  Kernel site_wind_kernel_, flying_, attached_, frame_;
};

}  // namespace fw::host
