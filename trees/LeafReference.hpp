// The CPU oracle of the leaves' physics (docs/leaves.md): flutter of attached leaves (both models),
// shedding, flight in a MAC wind, landing and exits, in double precision, one leaf after another. The device
// stage (host/stages/LeafStages, kernels/leaves.cl) is checked against it.
//
//   fw::trees::LeafReference ref(forest, leaves_per_species);   // every instance's leaves, at rest, attached
//   ref.step(spec, solid, wind, time, dt);                        // one step in the wind
//   (fluid::MacVelocity) ref.counts();                                                 // shed, flying,
//   landed, exited ref.leaf(j).position;                                         // world, m
//
// Flat leaf index j: instances in order, each instance's species leaves in order (SpeciesLeaves::leaves()).
// World frame of instance k: x = position_k + s_k R(yaw_k) p for a skeleton point p; directions R(yaw_k) d;
// lengths (lever, side) times s_k, areas times s_k^2, the mass times s_k^2 (mass per area unchanged).
#pragma once

#include <Eigen/Core>
#include <cstdint>
#include <vector>

#include "fluid/GridSpec.hpp"
#include "fluid/MacVelocity.hpp"
#include "trees/Forest.hpp"
#include "trees/LeafState.hpp"
#include "trees/SpeciesLeaves.hpp"

namespace fw::trees {

/// One leaf of one instance in the world frame: its rest geometry and its state.
struct WorldLeaf {
  int tree = 0;  ///< instance index
  int species = 0;
  Eigen::Vector3d anchor, petiole, hinge, rest_normal, tumble_axis;  // m; unit directions
  double lever = 0.0, side = 0.0, area = 0.0, mass = 0.0, strength = 0.0;
  std::array<double, 3> phase{}, frequency{};

  LeafState state = LeafState::attached;
  double theta = 0.0, theta_rate = 0.0;  ///< pseudo-branch angle (rad) and rate (rad/s)
  Eigen::Vector3d position;              ///< blade centre, m (attached: at rest position, turned by theta)
  Eigen::Vector3d velocity = Eigen::Vector3d::Zero();  ///< m/s (flying)
  Eigen::Vector3d normal;                              ///< blade normal now, unit
};

/// One step of x'' + gamma x' + w2 x = f over dt (s), f held, w2 > 0, gamma >= 0: the two-stage Radau IIA
/// method (third order, L-stable), which for this linear system is y1 = R(M) y0 with R(z) = (1 + z/3) /
/// (1 - 2z/3 + z^2/6) on y = (x - f/w2, dt x'). No exponential, sine or square root, which the exact step
/// (exact_modal_step) needs per leaf and step; motions far faster than the step are damped, not rung.
void radau_oscillator_step(double& x, double& v, double f, double w2, double gamma, double dt);
/// v_t = sqrt(2 sigma g / (rho C_D)), m/s: the still-air fall speed of the flight model.
double terminal_speed(const LeafSettings& settings);
/// The normal pressure force on a blade of area a, normal n, in wind u: 1/2 rho C_n a |u.n| |u|, N.
double blade_force(double area, const Eigen::Vector3d& normal, const Eigen::Vector3d& wind);

class LeafReference {
 public:
  /// leaves_per_species: one SpeciesLeaves per forest species (empty ones allowed). Throws
  /// std::invalid_argument("LeafReference: ...") for a count that differs from the forest's species.
  LeafReference(const Forest& forest, const std::vector<SpeciesLeaves>& leaves_per_species);

  int count() const { return int(leaves_.size()); }
  const WorldLeaf& leaf(int j) const { return leaves_.at(std::size_t(j)); }
  WorldLeaf& leaf(int j) { return leaves_.at(std::size_t(j)); }
  LeafCounts counts() const;

  /// One step of dt (s) ending at time + dt: attached leaves, in the wind of the cell that holds their rest
  /// centre (cell_centred_velocity), are shed where that wind's force on the blade in its pose at the step's
  /// start exceeds their strength (they fly from that pose, at rest, from the next step on), and the others
  /// flutter; flying leaves move, land or exit. `solid`: one byte a cell, non-zero = solid, or empty.
  void step(const fluid::GridSpec& spec, const std::vector<std::uint8_t>& solid,
            const fluid::MacVelocity& wind, double time, double dt);

 private:
  std::vector<LeafSettings> species_settings_;
  std::vector<WorldLeaf> leaves_;
};

}  // namespace fw::trees
