// The trees' half of a step on the OpenCL device: sample the wind at every tree, modal forces, the modal
// time step, and on output frames the skeleton deformation (DESIGN.md, "Data flow" 3-4; Diener 2008,
// figure 5). The packed forest (trees/Forest.hpp) is uploaded once; per step nothing leaves the device.
//
//   fw::host::ForestStages trees(cc, spec, forest);      // uploads species and instances, state = 0
//   trees.set_integrator(fw::trees::ModalIntegrator::exact);
//   for (int n = 0; n < steps; ++n) {
//     wind.step();
//     trees.enqueue_wind_load(wind.velocity());           // sampled wind and modal forces
//     trees.enqueue_modal_step(float(dt));                // q, qdot of every instance-mode
//   }
//   trees.enqueue_deform();                               // output frame: u = s^-3/2 R Phi q
//   std::vector<float> u = trees.download_displacements();   // #total nodes by 3, m, world frame
//
// Kernels: kernels/tree_wind_load.cl (one instance per iteration: sample once, reuse for all modes),
// kernels/tree_modal_step.cl and kernels/tree_deform.cl (one instance-mode / instance node per iteration).
// The CPU oracle is trees/ForestReference.
#pragma once

#include <vector>

#include "fluid/GridSpec.hpp"
#include "host/runtime/ComputeContext.hpp"
#include "host/stages/FluidStages.hpp"
#include "kernels/shared_types.h"
#include "trees/Forest.hpp"
#include "trees/ModalIntegrator.hpp"

namespace fw::host {

/// Modal coordinates of every instance-mode in flat order: q (kg^1/2 m) and qdot (kg^1/2 m/s).
struct ModalState {
  std::vector<float> q, qdot;
};

class ForestStages {
 public:
  /// Packs `forest` and uploads it. The forest is not referenced afterwards. Throws
  /// std::invalid_argument("ForestStages: ...") when `spec` is invalid.
  ForestStages(ComputeContext& cc, const fluid::GridSpec& spec, const trees::Forest& forest);

  int instance_count() const { return instance_count_; }
  int total_modes() const { return total_modes_; }
  int total_nodes() const { return total_nodes_; }
  int total_samples() const { return total_samples_; }

  void set_integrator(trees::ModalIntegrator integrator) { integrator_ = integrator; }
  trees::ModalIntegrator integrator() const { return integrator_; }

  /// Samples `velocity` at every instance's sample points and computes the modal forces.
  void enqueue_wind_load(DeviceVelocity& velocity);
  /// Advances every instance-mode by dt (s, finite and >= 0, else std::invalid_argument) with the forces of
  /// the last wind load held constant.
  void enqueue_modal_step(float dt);
  /// Nodal displacements from the current modal state.
  void enqueue_deform();
  /// q = qdot = 0 and forces = 0.
  void reset_state();

  /// Blocking reads. Displacements: #total nodes by 3 (m, world frame); sampled wind: #total samples by 3
  /// (m/s, world frame); forces: #total modes (N / kg^1/2).
  std::vector<float> download_displacements();
  std::vector<float> download_sampled_wind();
  std::vector<float> download_modal_forces();
  ModalState download_modal_state();
  /// Sets the modal state (restarts, tests). Throws std::invalid_argument unless both have total_modes().
  void upload_modal_state(const ModalState& state);

  /// Device buffers, for coupling stages: forces (total_modes floats), state (2 floats per mode: q, qdot),
  /// sampled wind (3 per sample), displacements (3 per node), instances (FwTreeInstance each).
  cl::Buffer& forces() { return forces_; }
  cl::Buffer& state() { return state_; }
  cl::Buffer& sampled_wind() { return sampled_wind_; }
  cl::Buffer& displacements() { return displacements_; }
  cl::Buffer& instances() { return instances_; }

 private:
  std::vector<float> read(cl::Buffer& buffer, std::size_t count);

  ComputeContext& cc_;
  FwGrid grid_;
  trees::ModalIntegrator integrator_ = trees::ModalIntegrator::exact;
  int instance_count_ = 0, total_modes_ = 0, total_nodes_ = 0, total_samples_ = 0;
  cl::Buffer species_, instances_, node_shapes_, projections_, sample_points_, omega_, zeta_, mode_instance_,
      node_instance_;
  cl::Buffer forces_, state_, sampled_wind_, displacements_;
  Kernel wind_load_, step_exact_, step_semi_implicit_, deform_;
};

}  // namespace fw::host
