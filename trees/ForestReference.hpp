// The CPU oracle of the trees' device stage (host/ForestStages, kernels/tree_*.cl): wind sampling, modal
// forces, the modal time step and the skeleton deformation, in double precision, straight from the species'
// SpeciesBasis (not from the float packing).
//
//   fw::trees::ForestReference ref(forest);
//   Eigen::VectorXd f = ref.modal_forces(spec, velocity);          // #total modes, N / kg^1/2
//   Eigen::VectorXd q = Eigen::VectorXd::Zero(ref.total_modes()), qdot = q;
//   for (int n = 0; n < 100; ++n) ref.step(q, qdot, f, 0.01, fw::trees::ModalIntegrator::exact);
//   Eigen::MatrixX3d u = ref.displacements(q);                      // #total nodes by 3, m, world frame
//   Eigen::MatrixX3d u_linear = ref.displacements(q, false);        // without the strong-wind correction
//
// Model, instance k of scale s, yaw psi (R = R(psi)) at x (see trees/Forest.hpp):
//   wind sample  v_s = trilinear MAC sample of the grid at x + s R p_s (each component on its own staggered
//                lattice, positions clamped to that lattice: constant extrapolation beyond the outer faces);
//   modal force  f_i = sum_s |v_s| v_s . (s^1/2 R p_i^s);
//   modal step   q'' + gamma q' + omega^2 q = f, f held over dt, omega = omega_i / s, gamma = 2 zeta_i omega;
//   deformation  u_node = s^-3/2 R sum_i phi_node_i q_i (linear), or with Diener's strong-wind correction
//                (trees/StrongWindCorrection.hpp) u_node = s R sum_i (q~_i v_node_i + q~_i^2 w_node_i),
//                q~_i = arctan(b_i s^-5/2 q_i) / b_i (q~_i = s^-5/2 q_i for b_i = 0), followed by the
//                length-restoring walk from the root (every element back at its rest length s L_e).
// Instances keep their species' damping ratios (exact for modal-ratio damping; Rayleigh damping is taken at
// the species' own frequencies, not re-evaluated at omega / s).
#pragma once

#include <Eigen/Core>
#include <array>

#include <vector>

#include "fluid/GridSpec.hpp"
#include "fluid/ReferenceStages.hpp"
#include "trees/Forest.hpp"
#include "trees/ModalIntegrator.hpp"

namespace fw::trees {

class UnresolvedTurbulence;  // trees/UnresolvedTurbulence.hpp
struct TreeTravel;

/// Trilinear sample of the face velocities at a world position (m), m/s, with the clamping described above.
Eigen::Vector3d sample_mac_velocity(const fluid::GridSpec& spec, const fluid::MacVelocity& velocity,
                                    const Eigen::Vector3d& world);
/// The velocity of the cell that holds a world position (m), m/s (fluid::GridSpec::cell_holding): at the
/// cell's centre, each component the mean of the cell's two faces along its axis. Positions outside the grid
/// take the nearest cell.
Eigen::Vector3d cell_centred_velocity(const fluid::GridSpec& spec, const fluid::MacVelocity& velocity,
                                      const Eigen::Vector3d& world);

/// One exact step of q'' + gamma q' + omega^2 q = f over dt, f constant: x = q - f / omega^2 decays as a free
/// damped oscillator, written so that it stays accurate through critical damping. omega > 0, gamma >= 0.
void exact_modal_step(double& q, double& qdot, double f, double omega, double gamma, double dt);
/// One semi-implicit (symplectic) Euler step of the same equation.
void semi_implicit_modal_step(double& q, double& qdot, double f, double omega, double gamma, double dt);

class ForestReference {
 public:
  /// Keeps a reference: `forest` must outlive this object.
  explicit ForestReference(const Forest& forest) : forest_(forest) {}

  int total_modes() const { return forest_.total_modes(); }
  int total_nodes() const { return forest_.total_nodes(); }
  int total_samples() const { return forest_.total_samples(); }

  /// World positions of every instance's wind samples, #total samples by 3, m.
  Eigen::MatrixX3d sample_positions() const;
  /// The wind at every sample, #total samples by 3, m/s, world frame.
  Eigen::MatrixX3d sample_wind(const fluid::GridSpec& spec, const fluid::MacVelocity& velocity) const;
  /// Modal forces from sampled wind (#total samples by 3, m/s): #total modes, N / kg^1/2.
  /// `law`: the drag law's factor f(|v_s|) on each sample's load (fluid/DragLaw.hpp; default constant).
  Eigen::VectorXd modal_forces(const Eigen::MatrixX3d& sampled_wind, const fluid::DragLaw& law = {}) const;
  Eigen::VectorXd modal_forces(const fluid::GridSpec& spec, const fluid::MacVelocity& velocity,
                               const fluid::DragLaw& law = {}) const;

  /// Per flat mode: omega_i / s (rad/s) and gamma = 2 zeta_i omega_i / s (1/s) of the owning instance.
  Eigen::VectorXd omega() const;
  Eigen::VectorXd gamma() const;

  /// Advances every flat mode by dt (s) with the forces f held constant. Throws std::invalid_argument
  /// ("ForestReference: ...") for wrong sizes or a dt that is not finite and >= 0.
  void step(Eigen::VectorXd& q, Eigen::VectorXd& qdot, const Eigen::VectorXd& forces, double dt,
            ModalIntegrator integrator) const;

  /// Nodal displacements of every instance for the modal coordinates q: #total nodes by 3, m, world frame.
  /// strong_wind_correction: the strong-wind correction, Diener's quadratic part and the length-restoring
  /// pass (the default, as on the device), or the linear modal sum.
  /// Every instance through Forest::instance_displacements (host code the run uses too: the oracle of the
  /// device's deformation kernels, not a second copy of it).
  Eigen::MatrixX3d displacements(const Eigen::VectorXd& q, bool strong_wind_correction = true) const;

  /// The equilibrium under constant forces, q_i = f_i / omega_i^2 (omega of the instance).
  Eigen::VectorXd static_modal_response(const Eigen::VectorXd& forces) const;
  Eigen::VectorXd static_modal_response(const fluid::GridSpec& spec,
                                        const fluid::MacVelocity& velocity) const;

  /// The unresolved turbulence's modal forces delta f (trees/UnresolvedTurbulence.hpp), #total modes,
  /// N / kg^1/2, to add to modal_forces: sampled wind (#total samples by 3, m/s), every instance's travel
  /// (X_k and the last step's distance, the read window; #instances each, m), the series, its per-sample
  /// offsets (series.offsets(forest)) and the intensity sigma_u / U. Sample s of tree k reads
  /// series.average(X_k + dx o_s, last_step_k). Throws std::invalid_argument ("ForestReference: ...") for
  /// wrong sizes or an intensity that is not finite and >= 0.
  Eigen::VectorXd unresolved_modal_forces(const Eigen::MatrixX3d& sampled_wind, const TreeTravel& travel,
                                          const UnresolvedTurbulence& series, const std::vector<int>& offsets,
                                          double intensity) const;
  /// last_step_k = |v| dt and X_k += last_step_k, v the wind at instance k's first sample: the step after
  /// the forces that read X_k. Throws std::invalid_argument for wrong sizes or a dt that is not finite and
  /// >= 0.
  void advance_travelled(TreeTravel& travel, const Eigen::MatrixX3d& sampled_wind, double dt) const;

 private:
  /// Throws std::invalid_argument unless the sampled wind has a row a sample (and the travel a value a tree).
  void check_sampled_wind(const Eigen::MatrixX3d& sampled_wind) const;
  void check_wind_and_travel(const Eigen::MatrixX3d& sampled_wind, const TreeTravel& travel) const;
  const Forest& forest_;
};

}  // namespace fw::trees
