// The element tree models on the device (trees/TreeDynamics.hpp: rigid_bodies, springs): the trees whose
// species one of them moves, beside the modal trees of the same forest (host/stages/ForestStages owns this
// stage and calls it from its own steps). Every such tree samples the wind at its elements' centres, steps
// its joints (rigid bodies) or bends them quasi-statically (springs), and on output frames writes its
// nodes' displacements into the forest's, where the outputs and the leaves find them as they find a modal
// tree's.
//
//   fw::host::BranchStages branches(cc, spec, forest, dynamics, blocks, instances, species);
//   branches.enqueue_sample(wind.velocity());   // collective over ranks
//   branches.enqueue_step(dt);                  // the joints over dt; the springs at the step's start
//   branches.enqueue_deform(displacements);     // output frames: nodes of the element trees only
//
// Kernels: kernels/tree_branches.cl (one tree per iteration). CPU oracles: trees/RigidBranches,
// trees/SpringBranches, trees/BranchPose.
#pragma once

#include <optional>
#include <vector>

#include "fluid/DragLaw.hpp"
#include "fluid/GridSpec.hpp"
#include "host/runtime/ComputeContext.hpp"
#include "host/stages/PointWindOnDevice.hpp"
#include "host/stages/StageState.hpp"
#include "kernels/shared_types.h"
#include "trees/Forest.hpp"
#include "trees/TreeDynamics.hpp"

namespace fw::host {

class BranchStages {
 public:
  /// Whether any of `dynamics` (one per species of a forest; empty: all modal) is an element model: then
  /// every rank builds this stage, since its sampling is collective.
  static bool needed(const std::vector<trees::SpeciesDynamics>& dynamics);
  /// The entries (joints) of instance k of `forest` under `dynamics`: its skeleton's node count when an
  /// element model moves it, 0 for a modal tree. What the joint state, its checkpoints and their
  /// redistribution hold per tree.
  static int entries_of(const trees::Forest& forest, const std::vector<trees::SpeciesDynamics>& dynamics,
                        int instance);
  /// Bytes of device memory the constructor allocates for `forest` under `dynamics`, with `items` work-items
  /// per kernel (ComputeContext::flat_items of the element trees).
  static std::size_t estimate_device_bytes(const trees::Forest& forest,
                                           const std::vector<trees::SpeciesDynamics>& dynamics,
                                           std::size_t items);

  /// The element trees of `forest` (this rank's, over ranks) under `dynamics` (one per species, validated
  /// here: std::invalid_argument). instances and species: the forest's packed tables, already on the device
  /// (ForestStages), read by every kernel here. Collective over ranks.
  BranchStages(ComputeContext& cc, const fluid::GridSpec& spec, const trees::Forest& forest,
               const std::vector<trees::SpeciesDynamics>& dynamics, const WindBlocks* blocks,
               cl::Buffer instances, cl::Buffer species);

  int tree_count() const { return int(trees_.size()); }
  /// Entries (elements and roots) of all element trees: the flat length of the joint state and winds.
  int entry_count() const { return entry_count_; }
  /// The first entry of instance k, or -1 when a modal species moves it.
  int entry_offset(int instance) const { return entry_offsets_.at(std::size_t(instance)); }

  void set_drag_law(const fluid::DragLaw& law) { drag_law_ = law; }

  /// The wind at every element centre. Collective over ranks.
  void enqueue_sample(DeviceVelocity& velocity);
  /// Rigid bodies: one implicit step of dt (s); springs: their bend at the step's start. Then the clock
  /// (what the springs' sine reads) advances by dt.
  void enqueue_step(float dt);
  /// Every rigid tree at rest in the last sampled wind, and every spring tree bent by it (the start).
  void enqueue_equilibrium();
  /// The element trees' node displacements (3 floats a node, m, world frame) into `displacements`, the
  /// forest's flat array; the modal trees' nodes are left alone.
  void enqueue_deform(cl::Buffer& displacements);
  /// Joints at rest and the clock at 0.
  void reset_state();

  /// Every entry's joint angle and rate (FW_JOINT_FLOATS floats an entry). Blocking.
  std::vector<float> download_joints();
  /// Instance k's joint angles (rad, one per table entry: `entries`, its skeleton's node count), read from
  /// the device. Throws std::invalid_argument for a modal tree. Blocking.
  std::vector<Eigen::Vector3d> download_angles(int instance, int entries);

  /// The joints and the clock, for checkpoints (StageState).
  void save_state(StageState& state);
  void restore_state(const StageState& state);

  /// What the damage stage's kernel reads (host/stages/DamageStages, kernels/tree_loads.cl
  /// branch_tree_loads): the element trees, their table on the device (FwBranchTree each), the species'
  /// models (FwBranchSpecies) and element tables (FwBranch, in the FwSpecies.skeleton_offset layout), and the
  /// joint state, which it zeroes for a failed tree held at rest.
  const std::vector<FwBranchTree>& trees() const { return trees_; }
  cl::Buffer& trees_buffer() { return trees_buffer_; }
  cl::Buffer& models() { return models_; }
  cl::Buffer& table() { return branches_; }
  cl::Buffer& joints() { return joints_; }

 private:
  void enqueue_spring_angles();

  ComputeContext& cc_;
  fluid::DragLaw drag_law_;
  std::vector<FwBranchTree> trees_;
  std::vector<int> entry_offsets_;          // per instance, -1 for a modal tree
  int rigid_count_ = 0, spring_count_ = 0;  // the trees of each model
  int entry_count_ = 0, largest_tree_ = 0, spring_block_count_ = 0;
  double time_ = 0.0;
  cl::Buffer instances_, species_, models_, branches_, trees_buffer_, rigid_trees_;
  cl::Buffer sample_world_, joints_, scratch_, pose_scratch_;
  cl::Buffer spring_blocks_;  // (tree, first entry) of each block of the springs' kernel
  std::optional<PointWindOnDevice> samples_;
  std::size_t scratch_items_ = 0, pose_items_ = 0;
  Kernel spring_angles_, rigid_step_, rigid_equilibrium_, deform_;
};

}  // namespace fw::host
