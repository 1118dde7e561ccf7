// The trees' half of a step on the OpenCL device: sample the wind at every tree, modal forces, the modal
// time step, and on output frames the skeleton deformation (docs/design.md, "Data flow" 3-4; Diener 2008,
// figure 5). The packed forest (trees/Forest.hpp) is uploaded once; per step nothing leaves the device.
//
//   fw::host::ForestStages trees(cc, spec, forest);      // uploads species and instances, state = 0
//   trees.set_integrator(fw::trees::ModalIntegrator::exact);
//   trees.set_unresolved_turbulence(series, 0.15);      // optional: trees/UnresolvedTurbulence
//   for (int n = 0; n < steps; ++n) {
//     wind.step();
//     trees.enqueue_wind_load(wind.velocity());           // sampled wind and modal forces
//     trees.enqueue_modal_step(float(dt));                // q, qdot of every instance-mode
//   }
//   trees.set_strong_wind_correction(true);               // the default: Diener's correction + exact lengths
//   trees.enqueue_deform();                               // output frame: u = s^-3/2 R Phi q, corrected
//   std::vector<float> u = trees.download_displacements();   // #total nodes by 3, m, world frame
//
// Over MPI ranks (WindBlocks, docs/parallel.md) a rank holds the trees whose roots lie in its block (a
// Forest::subset) and samples the wind on its block; the samples that lie in another rank's block come from
// that rank (PointWindOnDevice), so enqueue_wind_load is collective.
//
// Kernels: kernels/tree_wind_load.cl (the sample points' world positions once; then the wind at them through
// kernels/probe_sample.cl, and the modal forces, one instance per iteration), kernels/tree_modal_step.cl and
// kernels/tree_deform.cl (one instance-mode / block of 8 instance nodes per iteration; with the strong-wind
// correction tree_deform_strong, a few instances of a species per iteration; tree_deform without). The CPU
// oracle is trees/ForestReference.
#pragma once

#include <optional>
#include <vector>

#include "fluid/DragLaw.hpp"
#include "fluid/GridSpec.hpp"
#include "host/runtime/ComputeContext.hpp"
#include "host/stages/BlockGrid.hpp"
#include "host/stages/BranchStages.hpp"
#include "host/stages/DamageStages.hpp"
#include "host/stages/FluidStages.hpp"
#include "host/stages/PointWindOnDevice.hpp"
#include "host/stages/SavedShare.hpp"
#include "host/stages/StageState.hpp"
#include "kernels/shared_types.h"
#include "trees/Forest.hpp"
#include "trees/ModalIntegrator.hpp"
#include "trees/UnresolvedTurbulence.hpp"

namespace fw::host {

/// Modal coordinates of every instance-mode in flat order: q (kg^1/2 m) and qdot (kg^1/2 m/s).
struct ModalState {
  std::vector<float> q, qdot;
};

class ForestStages {
 public:
  /// Per instance in the unresolved turbulence's travel buffer: whole points, fraction, last step (points).
  static constexpr std::size_t kTravelFloats = 3;

  /// Packs `forest` and uploads it. The forest is not referenced afterwards. Throws
  /// std::invalid_argument("ForestStages: ...") when `spec` is invalid. Over ranks: spec is this rank's
  /// block_spec, forest its own trees, and every rank constructs one (collective).
  /// dynamics: the model of each species (trees/TreeDynamics.hpp; empty, all modal): the trees of an element
  /// model's species are moved by a BranchStages of this stage's own, and their modes stay at rest.
  ForestStages(ComputeContext& cc, const fluid::GridSpec& spec, const trees::Forest& forest,
               const WindBlocks* blocks = nullptr, const std::vector<trees::SpeciesDynamics>& dynamics = {});

  /// Bytes of device memory the constructor allocates for `forest` (the packed species and instances, the
  /// modal state, forces, sampled wind and displacements).
  static std::size_t estimate_device_bytes(const trees::Forest& forest,
                                           const std::vector<trees::SpeciesDynamics>& dynamics = {});
  /// Bytes set_unresolved_turbulence allocates for a series of `settings` over `forest`.
  static std::size_t estimate_unresolved_bytes(const trees::UnresolvedTurbulenceSettings& settings,
                                               const trees::Forest& forest);

  int instance_count() const { return instance_count_; }
  int total_modes() const { return total_modes_; }
  int total_nodes() const { return total_nodes_; }
  int total_samples() const { return total_samples_; }

  void set_integrator(trees::ModalIntegrator integrator) { integrator_ = integrator; }
  trees::ModalIntegrator integrator() const { return integrator_; }

  /// Whether enqueue_deform applies the strong-wind correction (trees/StrongWindCorrection.hpp): Diener's
  /// quadratic correction, then the pass that restores every element's rest length, so branch lengths stay
  /// constant under large q; on by default. Off, frames are the linear modal sum exactly as before the
  /// correction existed. Affects only the deformation, not the modal state.
  void set_strong_wind_correction(bool on) { strong_wind_correction_ = on; }
  /// How the drag coefficients vary with the sampled speed (fluid/DragLaw.hpp; default constant): the
  /// modal forces scale as the air's canopy drag does (WindGrid::set_canopy), so momentum still balances.
  void set_drag_law(const fluid::DragLaw& law) {
    law.validate();
    drag_law_ = law;
    if (branches_) branches_->set_drag_law(law);
  }
  bool strong_wind_correction() const { return strong_wind_correction_; }

  /// Samples `velocity` at every instance's sample points and computes the modal forces. Over ranks it
  /// waits for the samples other ranks take, and is collective.
  void enqueue_wind_load(DeviceVelocity& velocity);
  /// The samples another rank's block holds, which travel between ranks every step (0 alone).
  int remote_samples() const { return samples_->remote_count(); }
  /// Advances every instance-mode by dt (s, finite and >= 0, else std::invalid_argument) with the forces of
  /// the last wind load held constant.
  void enqueue_modal_step(float dt);
  /// Nodal displacements from the current modal state (with or without the strong-wind correction), and
  /// the element trees' from their joints.
  void enqueue_deform();
  /// q = qdot = 0 and forces = 0; the element trees' joints at rest.
  void reset_state();
  /// Every tree in equilibrium with the last wind load (the run's start, docs/design.md): q = f / omega^2
  /// and qdot = 0 for each mode, the rigid bodies' joints at rest under their load, the springs bent by it.
  void enqueue_equilibrium();

  /// The element models' stage, when any species has one (over ranks on every rank); else null.
  BranchStages* branches() { return branches_ ? &*branches_ : nullptr; }

  /// Storm damage (docs/damage.md) for `forest`, the forest this stage was built from: from now on
  /// enqueue_damage_check computes every tree's loads against its strength and records its failure. Throws
  /// what DamageStages throws.
  void set_damage(const trees::Forest& forest, const trees::DamageSettings& settings);
  /// The damage stage, when set; else null.
  DamageStages* damage() { return damage_ ? &*damage_ : nullptr; }
  bool has_damage() const { return damage_.has_value(); }
  /// An output frame's falling and fallen trees at `time` (s), after enqueue_deform (DamageStages).
  void enqueue_falls(double time) {
    if (damage_) damage_->enqueue_falls(time, instances_, species_, displacements_);
  }
  /// Every tree's loads and failure check at `time` (s, after the step), after enqueue_modal_step; nothing
  /// without damage.
  void enqueue_damage_check(float time) {
    if (damage_) damage_->enqueue_loads(time, instances_, species_, state_, samples_->wind());
  }

  /// Blocking reads. Displacements: #total nodes by 3 (m, world frame); sampled wind: #total samples by 3
  /// (m/s, world frame); forces: #total modes (N / kg^1/2).
  std::vector<float> download_displacements();
  std::vector<float> download_sampled_wind();
  std::vector<float> download_modal_forces();
  ModalState download_modal_state();
  /// Sets the modal state (restarts, tests). Throws std::invalid_argument unless both have total_modes().
  void upload_modal_state(const ModalState& state);

  /// What the next step reads (StageState, for checkpoints): every instance-mode's q and qdot, and with the
  /// unresolved forcing each tree's travelled distance along its series. Blocking.
  StageState save_state();
  /// Sets what save_state() saved from the same forest and settings; std::invalid_argument otherwise.
  void restore_state(const StageState& state);
  /// This rank's state from a checkpoint saved over other blocks (`parts`: every saved rank's trees stage
  /// and the trees it held): each tree's slices of the saved arrays, for the trees of `own` (this rank's) in
  /// its order. `forest` and `dynamics`: the whole forest and its species' models, which size the slices.
  /// What restore_state then reads; throws std::invalid_argument naming a tree no part holds.
  static StageState share_of(const std::vector<SavedShare>& parts, const trees::Forest& forest,
                             const std::vector<trees::SpeciesDynamics>& dynamics, const trees::Forest& own);

  /// Per-tree stochastic forcing of the unresolved turbulence (trees/UnresolvedTurbulence.hpp), off by
  /// default (and then nothing of it runs: the results are bit for bit those without it). Uploads the series
  /// table (6 floats a point) and every sample's offset once and zeroes the travelled distances. From then on
  /// enqueue_wind_load adds delta f after the resolved forces (kernel tree_unresolved_load), and
  /// enqueue_modal_step(dt) advances each tree's travelled distance by |v| dt, v its first sample's wind from
  /// the last load (tree_unresolved_advance): a caller adds no call per step. Throws
  /// std::invalid_argument("ForestStages: ...") for an intensity (sigma_u / U) that is not finite and >= 0.
  void set_unresolved_turbulence(const trees::UnresolvedTurbulence& series, double intensity);
  /// A new intensity for the forcing already set (std::invalid_argument when it is off or the value bad).
  void set_unresolved_intensity(double intensity);
  /// Turns the forcing off and releases its buffers.
  void disable_unresolved_turbulence();
  bool unresolved_turbulence() const { return unresolved_on_; }
  /// Each instance's travelled distance X_k within the series' period, m (empty when the forcing is off).
  std::vector<double> download_travelled();

  /// Device buffers, for coupling stages: forces (total_modes floats), state (2 floats per mode: q, qdot),
  /// sampled wind (3 per sample), displacements (3 per node), instances (FwTreeInstance each).
  cl::Buffer& forces() { return forces_; }
  cl::Buffer& state() { return state_; }
  cl::Buffer& sampled_wind() { return samples_->wind(); }
  cl::Buffer& displacements() { return displacements_; }
  cl::Buffer& instances() { return instances_; }

 private:
  std::vector<float> read(cl::Buffer& buffer, std::size_t count);
  void enqueue_modal_deform();

  ComputeContext& cc_;
  FwGrid grid_;
  trees::ModalIntegrator integrator_ = trees::ModalIntegrator::exact;
  bool strong_wind_correction_ = true;
  fluid::DragLaw drag_law_;
  int instance_count_ = 0, total_modes_ = 0, total_nodes_ = 0, total_samples_ = 0;
  cl::Buffer species_, instances_, node_shapes_, projections_, sample_points_, omega_, zeta_, mode_instance_,
      node_instance_;
  cl::Buffer strong_v_, strong_w_, strong_b_;  // the strong-wind correction (trees/Forest.hpp, ForestPacking)
  cl::Buffer strong_amplitudes_buffer_;        // its q~ and q~^2 per instance-mode, on each output frame
  cl::Buffer walk_, rest_elements_;  // its length-restoring pass (ForestPacking::walk, rest_elements)
  cl::Buffer forces_, state_, displacements_;
  cl::Buffer sample_world_;  // the sample points' world positions, 3 floats a flat sample
  std::optional<PointWindOnDevice>
      samples_;                    // the wind at sample_world_, each sampled by the rank holding it
  std::vector<int> instance_ids_;  // Forest::id of each instance: what seeds its unresolved series
  Kernel wind_forces_, step_exact_, step_semi_implicit_, deform_, deform_strong_;
  // Unresolved turbulence: wind samples per instance (for the offsets), the series' size, and its buffers:
  // series table (6 N floats), offsets (an int per flat sample), travel (whole points, fraction and last
  // step per instance).
  cl::Program wind_load_program_;
  std::vector<int> instance_samples_;
  bool unresolved_on_ = false;
  float unresolved_intensity_ = 0.0f;
  int series_length_ = 0;
  double series_spacing_ = 0.0;
  cl::Buffer series_, sample_offsets_, travel_;
  Kernel unresolved_load_, unresolved_advance_;
  Kernel equilibrium_;
  std::optional<BranchStages> branches_;
  std::optional<DamageStages> damage_;
};

}  // namespace fw::host
