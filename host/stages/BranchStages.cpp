#include "host/stages/BranchStages.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <numbers>
#include <stdexcept>

#include "host/stages/SavedStateNames.hpp"
#include "trees/BranchElements.hpp"
#include "trees/RigidBranches.hpp"

namespace fw::host {
namespace {

FwBranchSpecies device_model(const trees::SpeciesBasis& basis, const trees::SpeciesDynamics& dynamics) {
  FwBranchSpecies model{};
  model.model = dynamics.model == trees::TreeDynamics::rigid_bodies ? FW_DYNAMICS_RIGID_BODIES
                : dynamics.model == trees::TreeDynamics::springs    ? FW_DYNAMICS_SPRINGS
                                                                    : FW_DYNAMICS_MODAL;
  model.normal_drag = basis.settings().wind.branch_normal_drag ? 1 : 0;
  if (dynamics.model == trees::TreeDynamics::rigid_bodies)
    model.damping =
        float(trees::rigid_damping(dynamics.rigid_bodies.damping_ratio, basis.modes().omega()(0)));
  model.max_angle = float(dynamics.springs.max_angle_deg * std::numbers::pi / 180.0);
  model.sway_amplitude = float(dynamics.springs.sway_amplitude);
  model.sway_omega = float(2.0 * std::numbers::pi * dynamics.springs.sway_frequency_hz);
  return model;
}

// The element trees of `forest`, their entry offsets per instance (-1 for modal ones) and the entry count.
struct ElementTrees {
  std::vector<FwBranchTree> trees;
  std::vector<int> entry_offsets;
  int entries = 0, largest = 0;
};

ElementTrees element_trees(const trees::Forest& forest, const std::vector<trees::SpeciesDynamics>& dynamics) {
  ElementTrees out;
  for (int k = 0; k < forest.instance_count(); ++k) {
    const int n = BranchStages::entries_of(forest, dynamics, k);
    if (n == 0) {
      out.entry_offsets.push_back(-1);
      continue;
    }
    out.trees.push_back(FwBranchTree{k, out.entries, forest.id(k)});
    out.entry_offsets.push_back(out.entries);
    out.entries += n;
    out.largest = std::max(out.largest, n);
  }
  return out;
}

// The springs' blocks (kernels/tree_branches.cl spring_angles): (tree, first entry) pairs, FW_LANES
// consecutive entries of one spring tree each, its last block shorter.
std::vector<fw_int> spring_blocks(const trees::Forest& forest, const std::vector<FwBranchTree>& trees,
                                  const std::vector<trees::SpeciesDynamics>& dynamics) {
  std::vector<fw_int> blocks;
  if (dynamics.empty()) return blocks;  // every species modal
  for (std::size_t t = 0; t < trees.size(); ++t) {
    const int species = forest.instances()[std::size_t(trees[t].instance)].species;
    if (dynamics[std::size_t(species)].model != trees::TreeDynamics::springs) continue;
    const int n = forest.species()[std::size_t(species)].skeleton().size();
    for (int first = 0; first < n; first += FW_LANES) blocks.insert(blocks.end(), {fw_int(t), fw_int(first)});
  }
  return blocks;
}

std::size_t floats(std::size_t count) {
  return ComputeContext::allocation_bytes(count * sizeof(float));
}

}  // namespace

bool BranchStages::needed(const std::vector<trees::SpeciesDynamics>& dynamics) {
  return std::any_of(dynamics.begin(), dynamics.end(),
                     [](const trees::SpeciesDynamics& d) { return d.model != trees::TreeDynamics::modal; });
}

int BranchStages::entries_of(const trees::Forest& forest, const std::vector<trees::SpeciesDynamics>& dynamics,
                             int instance) {
  const int species = forest.instances().at(std::size_t(instance)).species;
  const bool modal =
      dynamics.empty() || dynamics.at(std::size_t(species)).model == trees::TreeDynamics::modal;
  return modal ? 0 : forest.species_of(instance).skeleton().size();
}

std::size_t BranchStages::estimate_device_bytes(const trees::Forest& forest,
                                                const std::vector<trees::SpeciesDynamics>& dynamics,
                                                std::size_t items) {
  const ElementTrees et = element_trees(forest, dynamics);
  std::size_t table = 0;
  for (const trees::SpeciesBasis& basis : forest.species()) table += std::size_t(basis.skeleton().size());
  const std::size_t entries = std::size_t(et.entries), count = et.trees.size();
  return ComputeContext::allocation_bytes(forest.species().size() * sizeof(FwBranchSpecies)) +
         ComputeContext::allocation_bytes(table * sizeof(FwBranch)) +
         2 * ComputeContext::allocation_bytes(count * sizeof(FwBranchTree)) +
         ComputeContext::allocation_bytes(spring_blocks(forest, et.trees, dynamics).size() * sizeof(fw_int)) +
         2 * floats(3 * entries) + floats(FW_JOINT_FLOATS * entries) +
         floats(items * FW_RIGID_SCRATCH_FLOATS * std::size_t(et.largest)) +
         floats(std::min(items, count) * FW_POSE_FLOATS * std::size_t(et.largest));
}

BranchStages::BranchStages(ComputeContext& cc, const fluid::GridSpec& spec, const trees::Forest& forest,
                           const std::vector<trees::SpeciesDynamics>& dynamics, const WindBlocks* blocks,
                           cl::Buffer instances, cl::Buffer species)
    : cc_(cc), instances_(std::move(instances)), species_(std::move(species)) {
  if (!dynamics.empty() && dynamics.size() != forest.species().size())
    throw std::invalid_argument(
        fmt::format("BranchStages: {} dynamics for {} species", dynamics.size(), forest.species().size()));
  for (const trees::SpeciesDynamics& d : dynamics) d.validate();

  std::vector<FwBranchSpecies> models;
  std::vector<FwBranch> table;
  for (std::size_t sp = 0; sp < forest.species().size(); ++sp) {
    const trees::SpeciesBasis& basis = forest.species()[sp];
    const trees::SpeciesDynamics d = dynamics.empty() ? trees::SpeciesDynamics{} : dynamics[sp];
    models.push_back(device_model(basis, d));
    if (d.model == trees::TreeDynamics::modal) {
      // Modal species keep their place in the layout (FwSpecies::skeleton_offset) but no table.
      table.resize(table.size() + std::size_t(basis.skeleton().size()), FwBranch{});
      continue;
    }
    const std::vector<FwBranch> packed =
        trees::BranchElements::of(basis.skeleton(), basis.settings().material, basis.settings().wind).pack();
    table.insert(table.end(), packed.begin(), packed.end());
  }

  const ElementTrees et = element_trees(forest, dynamics);
  trees_ = et.trees;
  entry_offsets_ = et.entry_offsets;
  entry_count_ = et.entries;
  largest_tree_ = et.largest;
  std::vector<FwBranchTree> rigid, springs;
  for (const FwBranchTree& tree : trees_) {
    const int model = models[std::size_t(forest.instances()[std::size_t(tree.instance)].species)].model;
    (model == FW_DYNAMICS_RIGID_BODIES ? rigid : springs).push_back(tree);
  }
  rigid_count_ = int(rigid.size());
  spring_count_ = int(springs.size());
  const std::vector<fw_int> springs_blocks = spring_blocks(forest, trees_, dynamics);
  spring_block_count_ = int(springs_blocks.size() / 2);

  constexpr cl_mem_flags ro = CL_MEM_READ_ONLY;
  models_ = cc_.upload(models, ro);
  branches_ = cc_.upload(table, ro);
  trees_buffer_ = cc_.upload(trees_, ro);
  rigid_trees_ = cc_.upload(rigid, ro);
  spring_blocks_ = cc_.upload(springs_blocks, ro);
  sample_world_ = cc_.zero_floats(3 * std::size_t(entry_count_));
  joints_ = cc_.zero_floats(FW_JOINT_FLOATS * std::size_t(entry_count_));
  // A scratch slot for each item that gets a tree: at most one a tree, however far flat_items rounds the
  // range up to whole work-groups (the items past the trees never touch their slot).
  pose_items_ = cc_.flat_items(trees_.size());
  pose_scratch_ =
      cc_.zero_floats(std::min(pose_items_, trees_.size()) * FW_POSE_FLOATS * std::size_t(largest_tree_));
  scratch_items_ = rigid.empty() ? 0 : cc_.flat_items(rigid.size());
  scratch_ = cc_.zero_floats(std::min(scratch_items_, rigid.size()) * FW_RIGID_SCRATCH_FLOATS *
                             std::size_t(largest_tree_));

  const cl::Program program = cc_.build("tree_branches.cl");
  if (!trees_.empty())
    Kernel(program, "branch_sample_positions")
        .set_args(tree_count(), trees_buffer_, instances_, species_, branches_, sample_world_)
        .enqueue(cc_, cl::NDRange(cc_.flat_items(trees_.size())));
  samples_.emplace(cc_, spec, blocks, sample_world_, entry_count_);
  spring_angles_ = Kernel(program, "spring_angles");
  rigid_step_ = Kernel(program, "rigid_branches_step");
  rigid_equilibrium_ = Kernel(program, "rigid_branches_equilibrium");
  deform_ = Kernel(program, "branch_deform");
}

void BranchStages::enqueue_sample(DeviceVelocity& velocity) {
  samples_->enqueue_sample(velocity);
}

void BranchStages::enqueue_step(float dt) {
  const int rigid = rigid_count_, springs = spring_count_;
  if (springs > 0) enqueue_spring_angles();
  if (rigid > 0)
    rigid_step_
        .set_args(rigid, rigid_trees_, instances_, species_, models_, branches_, drag_law_.to_device(),
                  samples_->wind(), dt, joints_, scratch_, fw_int(FW_RIGID_SCRATCH_FLOATS * largest_tree_))
        .enqueue(cc_, cl::NDRange(scratch_items_));
  time_ += double(dt);
}

void BranchStages::enqueue_equilibrium() {
  const int rigid = rigid_count_, springs = spring_count_;
  if (springs > 0) enqueue_spring_angles();
  if (rigid > 0)
    rigid_equilibrium_
        .set_args(rigid, rigid_trees_, instances_, species_, models_, branches_, drag_law_.to_device(),
                  samples_->wind(), joints_, scratch_, fw_int(FW_RIGID_SCRATCH_FLOATS * largest_tree_))
        .enqueue(cc_, cl::NDRange(scratch_items_));
}

void BranchStages::enqueue_spring_angles() {
  spring_angles_
      .set_args(fw_int(spring_block_count_), spring_blocks_, trees_buffer_, instances_, species_, models_,
                branches_, drag_law_.to_device(), samples_->wind(), float(time_), joints_)
      .enqueue(cc_, cl::NDRange(cc_.flat_items(std::size_t(spring_block_count_))));
}

void BranchStages::enqueue_deform(cl::Buffer& displacements) {
  if (trees_.empty()) return;
  deform_
      .set_args(tree_count(), trees_buffer_, instances_, species_, branches_, joints_, pose_scratch_,
                fw_int(FW_POSE_FLOATS * largest_tree_), displacements)
      .enqueue(cc_, cl::NDRange(pose_items_));
}

void BranchStages::reset_state() {
  time_ = 0.0;
  if (entry_count_ > 0)
    cc_.queue().enqueueFillBuffer(joints_, 0.0f, 0,
                                  FW_JOINT_FLOATS * std::size_t(entry_count_) * sizeof(float));
}

std::vector<float> BranchStages::download_joints() {
  std::vector<float> values(FW_JOINT_FLOATS * std::size_t(entry_count_));
  if (!values.empty())
    cc_.queue().enqueueReadBuffer(joints_, CL_TRUE, 0, values.size() * sizeof(float), values.data());
  return values;
}

std::vector<Eigen::Vector3d> BranchStages::download_angles(int instance, int entries) {
  const int offset = entry_offset(instance);
  if (offset < 0)
    throw std::invalid_argument(fmt::format("BranchStages: instance {} is a modal tree", instance));
  std::vector<float> values(FW_JOINT_FLOATS * std::size_t(entries));
  cc_.queue().enqueueReadBuffer(joints_, CL_TRUE, FW_JOINT_FLOATS * std::size_t(offset) * sizeof(float),
                                values.size() * sizeof(float), values.data());
  std::vector<Eigen::Vector3d> angles(static_cast<std::size_t>(entries));
  for (std::size_t j = 0; j < angles.size(); ++j)
    angles[j] = Eigen::Vector3d(values[FW_JOINT_FLOATS * j], values[FW_JOINT_FLOATS * j + 1],
                                values[FW_JOINT_FLOATS * j + 2]);
  return angles;
}

void BranchStages::save_state(StageState& state) {
  state.save(cc_, saved::kJointState, joints_);
  state.numbers[saved::kBranchClock] = {time_};
}

void BranchStages::restore_state(const StageState& state) {
  static constexpr const char* kStage = "trees";
  state.restore(cc_, kStage, saved::kJointState, joints_);
  time_ = state.number(kStage, saved::kBranchClock, 1).at(0);
}

}  // namespace fw::host
