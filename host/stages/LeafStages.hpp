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
// Kernels: kernels/leaves.cl. A step samples the wind once per site (the centre of a cell that holds the rest
// centre of a leaf: PointWindOnDevice), steps the flying leaves one at a time, then the attached ones
// FW_LANES at a time. The CPU oracle is trees/LeafReference. Slot j < own_count(): leaf j of the own
// instances in order, each instance's species leaves in order; the slots after them hold the leaves other
// ranks sent.
//
// Over MPI ranks (WindBlocks, docs/parallel.md) a rank steps the leaves of its own trees (a Forest::subset)
// and every flying or landed leaf in its block's own columns: after each step, a leaf outside them moves on
// to the rank whose block holds it (its state travels through the host, MPI_Alltoallv), so enqueue_step is
// collective. A moving leaf keeps what a flying leaf needs (flight, flight_drag in kernels/leaves.cl), its
// tree's id and its index among that tree's leaves, and so it flies on to the bits one process gives it.
#pragma once

#include <array>
#include <cstdint>
#include <functional>
#include <limits>
#include <optional>
#include <unordered_map>
#include <vector>

#include "fluid/GridSpec.hpp"
#include "host/runtime/ComputeContext.hpp"
#include "host/stages/BlockGrid.hpp"
#include "host/stages/FluidStages.hpp"
#include "host/stages/PointWindOnDevice.hpp"
#include "host/stages/SavedShare.hpp"
#include "host/stages/StageState.hpp"
#include "kernels/shared_types.h"
#include "trees/Forest.hpp"
#include "trees/LeafState.hpp"
#include "trees/SpeciesLeaves.hpp"

namespace fw::host {

/// This rank's leaves copied back: 3 floats a leaf for position (m, world) and normal, a byte for the state
/// (trees::LeafState), per leaf its tree's id (Forest::id), its index among that tree's leaves, and the blade
/// side (m).
struct LeafSnapshot {
  std::vector<float> position, normal;
  std::vector<std::uint8_t> state;
  std::vector<std::int32_t> tree_id, leaf;
  std::vector<float> side;
};

class LeafStages {
 public:
  /// Packs the leaves of every instance of `forest` (species_leaves: one per forest species, possibly empty)
  /// and uploads them, all attached at rest. Throws std::invalid_argument("LeafStages: ...") for an invalid
  /// grid, a species count that differs from the forest's, or more leaves than 32-bit indexing holds. Over
  /// ranks: spec is this rank's block_spec, forest its own trees, and every rank constructs one (collective).
  LeafStages(ComputeContext& cc, const fluid::GridSpec& spec, const trees::Forest& forest,
             const std::vector<trees::SpeciesLeaves>& species_leaves, const WindBlocks* blocks = nullptr);

  /// Most leaves of a forest: leaves are indexed with 32-bit integers, and each lane block may run FW_LANES
  /// past the last.
  static constexpr long long kMaxLeaves = std::numeric_limits<std::int32_t>::max() - FW_LANES;

  /// Bytes of device memory the constructor allocates, at most: per leaf its state, angle and rate, site,
  /// slot in the leaving list and flight drag, six float4 (position, velocity, normal, flight, the frame's
  /// position and normal) and at most one site of its own (its centre and its wind); per species leaf its
  /// rest table and element nodes; per instance its first leaf and block. Every per-leaf array is padded by
  /// FW_LANES. Over ranks the leaves other ranks send come on top.
  static std::size_t estimate_device_bytes(const trees::Forest& forest,
                                           const std::vector<trees::SpeciesLeaves>& species_leaves);

  /// The leaves of this rank's own trees (all leaves in one process).
  int own_count() const { return own_count_; }
  /// The slots taken by leaves that other ranks sent here (some may have moved on since, their slots free for
  /// the next to arrive).
  int arrived_count() const { return slot_count_ - own_count_; }
  /// How many leaves other ranks have sent here since the run began (or resumed).
  long long arrivals() const { return arrivals_; }

  /// One step of every leaf over step.dt, ending at step.time + step.dt, in the wind `vel` (the step's end
  /// velocity); mask: the pressure mask (FW_MASK_FLUID marks fluid cells). Over ranks collective: it then
  /// moves the leaves that left the block on, and throws std::runtime_error when a leaf's step reached past
  /// the block's halo.
  void enqueue_step(const FwStep& step, cl::Buffer& mask, DeviceVelocity& vel);
  /// Output frames: the attached leaves moved with the trees' displacements (3 floats per flat node, world
  /// frame: ForestStages::displacements() after enqueue_deform); download() then returns these positions.
  void enqueue_frame(cl::Buffer& displacements);
  /// Blocks. The blades of this rank's leaves at the last step's end: attached leaves at their deformed
  /// anchors when enqueue_frame ran since that step, else at their rest anchors.
  LeafSnapshot download();
  /// What the next step reads (StageState, for checkpoints): every slot's leaf (state, position, velocity,
  /// normal, flight, drag) and which tree and leaf it holds, the own leaves' flutter angles and rates, the
  /// counters and the last step's end. Blocking.
  StageState save_state();
  /// Sets what save_state() saved on the same rank of the same forest; std::invalid_argument otherwise.
  void restore_state(const StageState& state);
  /// This rank's state from a checkpoint saved over other blocks (`parts`: every saved rank's leaves stage
  /// and the trees it held; host/stages/LeafShare.cpp). A leaf's flutter stays with its tree, `own` (this
  /// rank's trees, of `tree_count` in the forest). Where it is (its slot) goes to its tree's rank while
  /// attached or gone from the domain, or while it lies in that rank's own columns of `block` (this rank's
  /// block of `spec`); a flying or landed leaf elsewhere goes to the rank whose own columns hold it, after
  /// that rank's own leaves in (tree, leaf) order, as leaves that arrive in a step are, and its tree's slot
  /// is marked moved. `leaves_of(id)`: tree id's leaves. `takes_counters`: this rank takes the counters'
  /// totals (one rank does: the counts are summed over ranks). Throws std::invalid_argument naming a leaf no
  /// part holds.
  static StageState share_of(const std::vector<SavedShare>& parts, const fluid::GridSpec& spec,
                             const BlockArray& block, const trees::Forest& own, int tree_count,
                             const std::function<std::size_t(int)>& leaves_of, bool takes_counters);
  /// Blocks: shed, landed and exited from the device counters, summed over ranks (collective); flying and
  /// attached follow.
  trees::LeafCounts counts();

 private:
  /// A leaf on its way to another rank: its tree's id, its index among that tree's leaves, its side (m), and
  /// its slot's values as kernels/leaves.cl leaves_pack writes them.
  struct MovingLeaf {
    std::int32_t tree = 0, leaf = 0;
    float side = 0.0f;
    float packed[FW_LEAF_PACKED_FLOATS] = {};
  };

  /// The frame kernel: every own leaf's blade at the last step's end into frame_position_ and frame_normal_.
  void enqueue_blades(cl::Buffer& displacements, bool displaced);
  /// Over ranks, after a step: the leaves outside the block's own columns go to the ranks holding them. Those
  /// sent here take their own slots (a leaf of this rank's trees coming back), else the slots that leaves
  /// sent here before have left (lowest first), else new ones.
  void move_leaves();
  /// Room for `slots` slots in every per-slot array, their values kept.
  void reserve_slots(int slots);
  /// Every per-slot array reallocated for `capacity` slots, the values of the first slots kept.
  void allocate_slots(int capacity);
  /// The device buffers a step carries to the next, by their names in a saved state.
  std::vector<std::pair<const char*, cl::Buffer*>> state_buffers();
  void read_counters(std::int32_t (&c)[FW_LEAF_COUNTERS]);

  ComputeContext& cc_;
  const WindBlocks* blocks_ = nullptr;  // null alone
  const Communicator* world_;           // the ranks whose counts add up (alone: this process)
  fluid::GridSpec spec_;
  FwGrid grid_{};
  int own_count_ = 0, instance_count_ = 0;
  int slot_count_ = 0, slot_capacity_ = 0;  // own leaves and the leaves sent here
  // Slots past the own leaves whose leaf moved on (FW_LEAF_MOVED): a leaf crossing cuts back and forth would
  // otherwise take a new slot every time, and a storm's leaf memory grow without bound.
  std::vector<int> free_slots_;
  long long arrivals_ = 0;
  // Each own tree's first own slot, by its id: a leaf of an own tree that comes back takes its own slot.
  std::unordered_map<std::int32_t, int> own_first_slot_;
  long long leaf_total_ = 0;  // every rank's own leaves
  int block_count_ = 0;       // blocks of FW_LANES leaves of one instance (kernels/leaves.cl)
  int rest_stride_ = 0;
  float time_ = 0.0f;  // the last step's end, s
  bool frame_ready_ = false;
  std::array<int, 2> own_lo_{0, 0}, own_hi_{0, 0};  // the block's own cells along x, y (domain indices)
  // Per slot: its tree's id, its index among that tree's leaves, its side (m).
  std::vector<std::int32_t> slot_tree_, slot_leaf_;
  std::vector<float> slot_side_;
  cl::Buffer first_leaf_, first_block_, instances_, leaf_species_, rest_, rest_nodes_, leaf_site_;
  cl::Buffer site_positions_;
  std::optional<PointWindOnDevice> sites_;
  cl::Buffer theta_, theta_rate_, frame_position_, frame_normal_;                     // own leaves
  cl::Buffer state_, position_, velocity_, normal_, flight_, flight_drag_, leaving_;  // every slot
  cl::Buffer counters_, no_displacements_;
  Kernel flying_, attached_, frame_, leaving_kernel_, pack_, unpack_;
};

}  // namespace fw::host
