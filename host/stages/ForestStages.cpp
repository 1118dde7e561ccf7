#include "host/stages/ForestStages.hpp"

#include "host/stages/SavedStateNames.hpp"

#include "host/runtime/Communicator.hpp"

#include <fmt/format.h>

#include <cmath>
#include <map>
#include <stdexcept>
#include <string>

namespace fw::host {
namespace {

// The forest's buffers as the constructor allocates them: every packed table, then the state (forces, the
// strong-wind amplitudes q~ and q~^2, q and qdot: 5 floats a mode), the samples' positions and wind (3 each a
// sample) and the displacements (3 a node).
std::size_t forest_buffer_bytes(const trees::ForestPacking& p) {
  std::size_t bytes = 0;
  const auto add = [&bytes](const auto& table) {
    bytes += ComputeContext::allocation_bytes(table.size() * sizeof(table[0]));
  };
  add(p.species), add(p.instances), add(p.node_shapes), add(p.projections), add(p.sample_points);
  add(p.omega), add(p.damping_ratios), add(p.mode_instance), add(p.node_instance), add(p.strong_v);
  add(p.strong_w), add(p.strong_b), add(p.walk), add(p.rest_elements);
  const auto floats = [](std::size_t count) {
    return ComputeContext::allocation_bytes(count * sizeof(float));
  };
  const std::size_t modes = std::size_t(p.total_modes);
  bytes += floats(modes) + 2 * floats(2 * modes);
  bytes += 2 * floats(3 * std::size_t(p.total_samples)) + floats(3 * std::size_t(p.total_nodes));
  return bytes;
}

}  // namespace

std::size_t ForestStages::estimate_device_bytes(const trees::Forest& forest,
                                                const std::vector<trees::SpeciesDynamics>& dynamics) {
  std::size_t bytes = forest_buffer_bytes(forest.pack());
  // The element trees' work-items: at most one a tree (ComputeContext::flat_items).
  if (BranchStages::needed(dynamics))
    bytes += BranchStages::estimate_device_bytes(forest, dynamics, std::size_t(forest.instance_count()));
  return bytes;
}

std::size_t ForestStages::estimate_unresolved_bytes(const trees::UnresolvedTurbulenceSettings& settings,
                                                    const trees::Forest& forest) {
  if (forest.instance_count() == 0) return 0;
  const std::size_t table = trees::UnresolvedTurbulence::kDeviceFloatsPerPoint *
                            std::size_t(settings.series_length) * sizeof(float);
  return ComputeContext::allocation_bytes(table) +
         ComputeContext::allocation_bytes(std::size_t(forest.total_samples()) * sizeof(fw_int)) +
         ComputeContext::allocation_bytes(kTravelFloats * std::size_t(forest.instance_count()) *
                                          sizeof(float));
}

ForestStages::ForestStages(ComputeContext& cc, const fluid::GridSpec& spec, const trees::Forest& forest,
                           const WindBlocks* blocks, const std::vector<trees::SpeciesDynamics>& dynamics)
    : cc_(cc) {
  try {
    spec.validate();
  } catch (const std::invalid_argument& e) {
    throw std::invalid_argument(std::string("ForestStages: ") + e.what());
  }
  grid_ = spec.to_device();
  trees::ForestPacking p = forest.pack();
  // An element model's species has no modes on the device: its trees' modal forces, state and
  // displacements stay zero, at the cost of a loop of no iterations per tree.
  for (std::size_t sp = 0; sp < p.species.size() && !dynamics.empty(); ++sp)
    if (dynamics.at(sp).model != trees::TreeDynamics::modal) p.species[sp].mode_count = 0;
  instance_count_ = int(p.instances.size());
  total_modes_ = p.total_modes;
  total_nodes_ = p.total_nodes;
  total_samples_ = p.total_samples;

  constexpr cl_mem_flags ro = CL_MEM_READ_ONLY;
  species_ = cc_.upload(p.species, ro);
  instances_ = cc_.upload(p.instances, ro);
  node_shapes_ = cc_.upload(p.node_shapes, ro);
  projections_ = cc_.upload(p.projections, ro);
  sample_points_ = cc_.upload(p.sample_points, ro);
  omega_ = cc_.upload(p.omega, ro);
  zeta_ = cc_.upload(p.damping_ratios, ro);
  mode_instance_ = cc_.upload(p.mode_instance, ro);
  node_instance_ = cc_.upload(p.node_instance, ro);
  strong_v_ = cc_.upload(p.strong_v, ro);
  strong_w_ = cc_.upload(p.strong_w, ro);
  strong_b_ = cc_.upload(p.strong_b, ro);
  walk_ = cc_.upload(p.walk, ro);
  rest_elements_ = cc_.upload(p.rest_elements, ro);

  forces_ = cc_.zero_floats(std::size_t(total_modes_));
  strong_amplitudes_buffer_ = cc_.zero_floats(2 * std::size_t(total_modes_));
  state_ = cc_.zero_floats(2 * std::size_t(total_modes_));
  displacements_ = cc_.zero_floats(3 * std::size_t(total_nodes_));

  sample_world_ = cc_.zero_floats(3 * std::size_t(total_samples_));
  for (int k = 0; k < instance_count_; ++k) instance_ids_.push_back(forest.id(k));

  wind_load_program_ = cc_.build("tree_wind_load.cl");
  wind_forces_ = Kernel(wind_load_program_, "tree_wind_forces");
  for (const FwTreeInstance& t : p.instances)
    instance_samples_.push_back(p.species[std::size_t(t.species)].sample_count);
  if (instance_count_ > 0)
    Kernel(wind_load_program_, "tree_sample_positions")
        .set_args(instance_count_, instances_, species_, sample_points_, sample_world_)
        .enqueue(cc_, cl::NDRange(cc_.flat_items(std::size_t(instance_count_))));
  samples_.emplace(cc_, spec, blocks, sample_world_, total_samples_);
  cl::Program step = cc_.build("tree_modal_step.cl");
  step_exact_ = Kernel(step, "tree_modal_step_exact");
  step_semi_implicit_ = Kernel(step, "tree_modal_step_semi_implicit");
  cl::Program deform = cc_.build("tree_deform.cl");
  deform_ = Kernel(deform, "tree_deform");
  deform_strong_ = Kernel(deform, "tree_deform_strong");
  equilibrium_ = Kernel(step, "tree_modal_equilibrium");
  if (BranchStages::needed(dynamics))
    branches_.emplace(cc_, spec, forest, dynamics, blocks, instances_, species_);
}

void ForestStages::enqueue_wind_load(DeviceVelocity& velocity) {
  samples_->enqueue_sample(velocity);  // collective over ranks, with or without trees of its own
  if (branches_) branches_->enqueue_sample(velocity);
  if (instance_count_ == 0) return;
  wind_forces_
      .set_args(drag_law_.to_device(), instance_count_, instances_, species_, projections_, samples_->wind(),
                forces_)
      .enqueue(cc_, cl::NDRange(cc_.flat_items(std::size_t(instance_count_))));
  if (unresolved_on_)
    unresolved_load_
        .set_args(instance_count_, instances_, species_, projections_, samples_->wind(), series_,
                  series_length_, float(series_spacing_), sample_offsets_, travel_, unresolved_intensity_,
                  forces_)
        .enqueue(cc_, cl::NDRange(cc_.flat_items(std::size_t(instance_count_))));
}

void ForestStages::enqueue_modal_step(float dt) {
  if (!std::isfinite(dt) || dt < 0.0f)
    throw std::invalid_argument(fmt::format("ForestStages: dt must be finite and >= 0, got {}", dt));
  if (branches_) branches_->enqueue_step(dt);
  if (total_modes_ == 0) return;
  Kernel& kernel = integrator_ == trees::ModalIntegrator::exact ? step_exact_ : step_semi_implicit_;
  kernel.set_args(total_modes_, dt, mode_instance_, instances_, species_, omega_, zeta_, forces_, state_)
      .enqueue(cc_, cl::NDRange(cc_.flat_items(std::size_t(total_modes_))));
  if (unresolved_on_)
    unresolved_advance_
        .set_args(instance_count_, instances_, samples_->wind(), series_length_, float(series_spacing_), dt,
                  travel_)
        .enqueue(cc_, cl::NDRange(cc_.flat_items(std::size_t(instance_count_))));
}

void ForestStages::enqueue_deform() {
  if (total_nodes_ == 0) return;
  // The modal kernels skip the element trees (their species have no modes), whose nodes the branch
  // kernels then write.
  enqueue_modal_deform();
  if (branches_) branches_->enqueue_deform(displacements_);
}

void ForestStages::enqueue_modal_deform() {
  if (strong_wind_correction_) {
    // Groups of a few instances per iteration (kernels/tree_deform.cl): as many items as instances is
    // enough, whatever the group size.
    deform_strong_
        .set_args(instance_count_, instances_, species_, walk_, strong_v_, strong_w_, strong_b_,
                  rest_elements_, state_, strong_amplitudes_buffer_, displacements_)
        .enqueue(cc_, cl::NDRange(cc_.flat_items(std::size_t(instance_count_))));
  } else {
    const cl::NDRange blocks(cc_.flat_items((std::size_t(total_nodes_) + 7) / 8));  // blocks of 8 nodes
    deform_.set_args(total_nodes_, node_instance_, instances_, species_, node_shapes_, state_, displacements_)
        .enqueue(cc_, blocks);
  }
}

StageState ForestStages::save_state() {
  StageState state;
  state.save(cc_, saved::kModalState, state_);
  if (unresolved_on_) state.save(cc_, saved::kTravelled, travel_);
  if (branches_) branches_->save_state(state);
  if (damage_) damage_->save_state(state);
  return state;
}

void ForestStages::restore_state(const StageState& state) {
  static constexpr const char* kStage = "trees";
  state.restore(cc_, kStage, saved::kModalState, state_);
  if (unresolved_on_) state.restore(cc_, kStage, saved::kTravelled, travel_);
  if (branches_) branches_->restore_state(state);
  if (damage_) damage_->restore_state(state);
}

void ForestStages::set_damage(const trees::Forest& forest, const trees::DamageSettings& settings) {
  damage_.reset();
  if (settings.enabled) damage_.emplace(cc_, forest, settings, branches());
}

void ForestStages::enqueue_equilibrium() {
  if (branches_) branches_->enqueue_equilibrium();
  if (total_modes_ == 0) return;
  equilibrium_.set_args(total_modes_, mode_instance_, instances_, species_, omega_, forces_, state_)
      .enqueue(cc_, cl::NDRange(cc_.flat_items(std::size_t(total_modes_))));
}

void ForestStages::reset_state() {
  if (branches_) branches_->reset_state();
  if (total_modes_ == 0) return;
  cc_.queue().enqueueFillBuffer(state_, 0.0f, 0, 2 * std::size_t(total_modes_) * sizeof(float));
  cc_.queue().enqueueFillBuffer(forces_, 0.0f, 0, std::size_t(total_modes_) * sizeof(float));
  if (unresolved_on_)
    cc_.queue().enqueueFillBuffer(travel_, 0.0f, 0,
                                  kTravelFloats * std::size_t(instance_count_) * sizeof(float));
}

std::vector<float> ForestStages::read(cl::Buffer& buffer, std::size_t count) {
  std::vector<float> values(count);
  if (count > 0) cc_.queue().enqueueReadBuffer(buffer, CL_TRUE, 0, count * sizeof(float), values.data());
  return values;
}

std::vector<float> ForestStages::download_displacements() {
  return read(displacements_, 3 * std::size_t(total_nodes_));
}

std::vector<float> ForestStages::download_sampled_wind() {
  return read(samples_->wind(), 3 * std::size_t(total_samples_));
}

std::vector<float> ForestStages::download_modal_forces() {
  return read(forces_, std::size_t(total_modes_));
}

ModalState ForestStages::download_modal_state() {
  const std::vector<float> interleaved = read(state_, 2 * std::size_t(total_modes_));
  ModalState state;
  state.q.resize(std::size_t(total_modes_));
  state.qdot.resize(std::size_t(total_modes_));
  for (std::size_t j = 0; j < state.q.size(); ++j) {
    state.q[j] = interleaved[2 * j];
    state.qdot[j] = interleaved[2 * j + 1];
  }
  return state;
}

void ForestStages::upload_modal_state(const ModalState& state) {
  const std::size_t m = std::size_t(total_modes_);
  if (state.q.size() != m || state.qdot.size() != m)
    throw std::invalid_argument(
        fmt::format("ForestStages: modal state needs {} values of q and qdot, got {} and {}", m,
                    state.q.size(), state.qdot.size()));
  std::vector<float> interleaved(2 * m);
  for (std::size_t j = 0; j < m; ++j) {
    interleaved[2 * j] = state.q[j];
    interleaved[2 * j + 1] = state.qdot[j];
  }
  if (m > 0)
    cc_.queue().enqueueWriteBuffer(state_, CL_TRUE, 0, interleaved.size() * sizeof(float),
                                   interleaved.data());
}

void ForestStages::set_unresolved_turbulence(const trees::UnresolvedTurbulence& series, double intensity) {
  if (!std::isfinite(intensity) || intensity < 0.0)
    throw std::invalid_argument(fmt::format(
        "ForestStages: unresolved turbulence intensity must be finite and >= 0, got {}", intensity));
  disable_unresolved_turbulence();
  if (instance_count_ == 0) return;  // nothing to force; stays off
  std::vector<fw_int> offsets(static_cast<std::size_t>(total_samples_));
  std::size_t flat = 0;
  for (int k = 0; k < instance_count_; ++k)
    for (int s = 0; s < instance_samples_[std::size_t(k)]; ++s)
      offsets[flat++] = series.offset(instance_ids_[std::size_t(k)], s);
  constexpr cl_mem_flags ro = CL_MEM_READ_ONLY;
  series_ = cc_.upload(series.device_table(), ro);
  sample_offsets_ = cc_.upload(offsets, ro);
  travel_ = cc_.zero_floats(kTravelFloats * std::size_t(instance_count_));
  series_length_ = series.length();
  series_spacing_ = series.spacing();
  unresolved_intensity_ = float(intensity);
  if (unresolved_load_.name().empty()) {
    unresolved_load_ = Kernel(wind_load_program_, "tree_unresolved_load");
    unresolved_advance_ = Kernel(wind_load_program_, "tree_unresolved_advance");
  }
  unresolved_on_ = true;
}

void ForestStages::set_unresolved_intensity(double intensity) {
  if (!unresolved_on_)
    throw std::invalid_argument(
        "ForestStages: set_unresolved_intensity needs set_unresolved_turbulence first");
  if (!std::isfinite(intensity) || intensity < 0.0)
    throw std::invalid_argument(fmt::format(
        "ForestStages: unresolved turbulence intensity must be finite and >= 0, got {}", intensity));
  unresolved_intensity_ = float(intensity);
}

void ForestStages::disable_unresolved_turbulence() {
  unresolved_on_ = false;
  series_ = sample_offsets_ = travel_ = cl::Buffer();
  series_length_ = 0;
  series_spacing_ = 0.0;
}

std::vector<double> ForestStages::download_travelled() {
  if (!unresolved_on_) return {};
  const std::vector<float> travel = read(travel_, kTravelFloats * std::size_t(instance_count_));
  std::vector<double> metres(static_cast<std::size_t>(instance_count_));
  for (std::size_t k = 0; k < metres.size(); ++k)
    metres[k] = (double(travel[kTravelFloats * k]) + double(travel[kTravelFloats * k + 1])) * series_spacing_;
  return metres;
}

namespace {

// Per tree (Forest::id) of every part, its slice of a per-instance array of `per_tree(id)` floats.
template <typename PerTree>
std::map<int, std::vector<float>> tree_slices(const std::vector<SavedShare>& parts, const std::string& name,
                                              PerTree per_tree) {
  std::map<int, std::vector<float>> slices;
  for (const SavedShare& part : parts) {
    std::size_t count = 0;
    for (const int id : part.tree_ids) count += per_tree(id);
    const std::vector<float> values = saved_values<float>(part.state->bytes("trees", name), count, name);
    std::size_t at = 0;
    for (const int id : part.tree_ids) {
      slices[id].assign(values.begin() + long(at), values.begin() + long(at + per_tree(id)));
      at += per_tree(id);
    }
  }
  return slices;
}

}  // namespace

StageState ForestStages::share_of(const std::vector<SavedShare>& parts, const trees::Forest& forest,
                                  const std::vector<trees::SpeciesDynamics>& dynamics,
                                  const trees::Forest& own) {
  if (parts.empty()) throw std::invalid_argument("checkpoint: no parts of the trees to take a share of");
  const StageState& first = *parts.front().state;
  StageState mine;
  const auto take = [&](const std::string& name, auto per_tree) {
    const std::map<int, std::vector<float>> slices = tree_slices(parts, name, per_tree);
    std::vector<float> values;
    for (int k = 0; k < own.instance_count(); ++k) {
      const auto at = slices.find(own.id(k));
      if (at == slices.end())
        throw std::invalid_argument(
            fmt::format("checkpoint: no part holds tree {}: it is another run's", own.id(k)));
      values.insert(values.end(), at->second.begin(), at->second.end());
    }
    mine.buffers[name] = saved_bytes(values);
  };
  const auto modal = [&](int id) {
    return 2 * std::size_t(forest.mode_offset(id + 1) - forest.mode_offset(id));
  };
  take(saved::kModalState, modal);
  if (first.buffers.count(saved::kTravelled) > 0) take(saved::kTravelled, [](int) { return kTravelFloats; });
  // Storm damage: each tree's record, moved as its bytes (the ints among them too).
  if (first.buffers.count(saved::kDamage) > 0)
    take(saved::kDamage, [](int) { return sizeof(FwTreeDamage) / sizeof(float); });
  if (first.buffers.count(saved::kJointState) > 0) {
    // An element model's tree: its joints, one entry a node; a modal tree has none.
    take(saved::kJointState, [&](int id) {
      return FW_JOINT_FLOATS * std::size_t(BranchStages::entries_of(forest, dynamics, id));
    });
    // The springs' clock is the run's time, the same on every rank.
    mine.numbers[saved::kBranchClock] = first.number("trees", saved::kBranchClock, 1);
  }
  return mine;
}

}  // namespace fw::host
