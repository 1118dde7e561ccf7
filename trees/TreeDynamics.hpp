// Which model moves a species' trees (docs/trees.md, "Three tree models"), and each model's own settings.
//
//   fw::trees::SpeciesDynamics dynamics;                    // modal by default
//   dynamics.model = fw::trees::TreeDynamics::springs;
//   dynamics.springs.max_angle_deg = 15.0;
//   dynamics.validate();                                    // std::invalid_argument for a bad value
//
//   - modal: Diener's modes and wind projection basis (trees/ModalBasis, trees/WindBasis);
//   - rigid_bodies: Oliapuram & Kumar (2010, section 3.1): every element a rigid body rotating about its
//     parent's end against a joint spring, integrated implicitly (trees/RigidBranches);
//   - springs: Ota et al. (2004) as Yildiz implements it: every element a quasi-static cantilever flat
//     spring bent by its own wind load, with a stochastic sine on top (trees/SpringBranches).
#pragma once

#include <optional>
#include <string_view>

namespace fw::trees {

enum class TreeDynamics { modal, rigid_bodies, springs };

/// The scenario word of each model: "modal", "rigid_bodies", "springs".
const char* dynamics_name(TreeDynamics model);
/// The model a scenario word names; nullopt for any other word.
std::optional<TreeDynamics> parse_dynamics(std::string_view word);

/// Oliapuram's articulated rigid branches.
struct RigidBodySettings {
  /// Damping ratio of the tree's first mode (dimensionless, >= 0): the joints' damping is proportional to
  /// their stiffness (C = beta K), beta = 2 zeta / omega_1 with omega_1 the species' first FEM frequency, so
  /// that the slowest sway decays as the modal model's does with the same ratio.
  double damping_ratio = 0.05;
};

/// Ota's quasi-static cantilever springs.
struct SpringSettings {
  /// The largest bend of one element from its parent, degrees (Yildiz: 20), in (0, 90).
  double max_angle_deg = 20.0;
  /// The stochastic sine's amplitude at the largest bend: the load is F (1 + a sin(2 pi f t + b)) with
  /// a = sway_amplitude theta / theta_max (a bent element sways more) and b random per element; >= 0.
  double sway_amplitude = 0.2;
  /// f, Hz, > 0.
  double sway_frequency_hz = 0.5;
};

/// One species' model and the settings of each model (only the chosen model's are read).
struct SpeciesDynamics {
  TreeDynamics model = TreeDynamics::modal;
  RigidBodySettings rigid_bodies;
  SpringSettings springs;

  /// Throws std::invalid_argument("SpeciesDynamics: ...") for a value out of the ranges above.
  void validate() const;
};

}  // namespace fw::trees
