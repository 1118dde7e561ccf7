// The 3D Euler-Bernoulli frame element of the tree FEM model (docs/design.md, "Numerics: Trees"; the
// appendices of Diener 2008 and Stam 1997): two nodes, 6 DOF per node, axial stretch, torsion and
// bending in two planes.
//
//   const auto section = fw::trees::BeamSection::circle(0.5 * (r_a + r_b));   // element radius = mean
//   const auto K = fw::trees::global_stiffness(wood, section, a, b);         // 12x12, global frame
//   const auto M = fw::trees::global_mass(wood, section, a, b);
//
// DOF order (local and global alike), node a first, then node b:
//   index 0..5  = ux_a uy_a uz_a rx_a ry_a rz_a
//   index 6..11 = ux_b uy_b uz_b rx_b ry_b rz_b
// u are displacements (m), r are small rotations (rad) about the x, y, z axes, positive by the right-hand
// rule.
//
// Local frame (element_frame): x runs along the element from a to b, y and z complete a right-handed
// orthonormal frame. In that frame, with s in [0, L] the position along the element:
//   - ux and rx (torsion) are interpolated linearly;
//   - uy and uz are interpolated with cubic Hermite functions, the slopes coming from the rotations:
//       rz = +d(uy)/ds   (bending in the x-y plane),
//       ry = -d(uz)/ds   (bending in the x-z plane),
//     which is Diener's psi_z = du_y/dx, psi_y = -du_z/dx and what the right-hand rule gives.
// Section (solid circle of radius r): A = pi r^2, I = pi r^4 / 4 (each bending axis), J = pi r^4 / 2.
// Energies: V = 1/2 int EA ux'^2 + EI (uy''^2 + uz''^2) + GJ rx'^2 ds,
//           T = 1/2 int rho A (ux.^2 + uy.^2 + uz.^2) + rho J rx.^2 ds   (no rotary inertia of bending).
// Global matrices are T^T K_local T with T = diag(R, R, R, R), R = element_frame(a, b) (rows = local axes),
// so that u_local = T u_global.
#pragma once

#include <Eigen/Dense>

namespace fw::trees {

struct Material;

using Matrix12d = Eigen::Matrix<double, 12, 12>;

/// Section constants of a beam element (SI units).
struct BeamSection {
  double area = 0.0;           ///< A, m^2
  double second_moment = 0.0;  ///< I about either bending axis, m^4 (pi r^4 / 4 for a circle)
  double polar_moment = 0.0;   ///< J, torsion constant, m^4 (pi r^4 / 2 for a circle)

  /// The solid circular section of radius r (m). Throws std::invalid_argument("BeamSection: ...") unless r is
  /// finite and positive.
  static BeamSection circle(double radius);

  /// Throws std::invalid_argument("BeamSection: ...") unless all three constants are finite and positive.
  void validate() const;
};

/// Local 12x12 stiffness matrix (DOF order and signs as above) of an element of the given length (m): axial
/// EA/L, torsion GJ/L, and the Hermite cubic bending stiffness EI/L^3 [12 6L -12 6L; ...] in each plane.
/// Symmetric, positive semi-definite, with the 6 rigid-body modes as its null space. Validates its inputs
/// (std::invalid_argument).
Matrix12d local_stiffness(const Material& material, const BeamSection& section, double length);

/// Local 12x12 consistent mass matrix: rho A L/6 [2 1; 1 2] axially, rho J L/6 [2 1; 1 2] in torsion and the
/// Hermite consistent matrix rho A L/420 [156 22L 54 -13L; ...] in each bending plane; the rotary inertia of
/// bending is left out. Symmetric positive definite; a rigid translation d carries kinetic energy
/// 1/2 rho A L |d|^2. Validates its inputs (std::invalid_argument).
Matrix12d local_mass(const Material& material, const BeamSection& section, double length);

/// The rotation from the global to the element's local frame: row 0 = local x = (b - a)/|b - a|; row 1 =
/// local y, horizontal (perpendicular to global z) unless the element is within about 25 degrees of vertical,
/// where it is taken perpendicular to global x instead; row 2 = local z = x cross y. Always orthonormal and
/// right-handed. Throws std::invalid_argument("BeamElement: ...") for coincident or non-finite end points.
Eigen::Matrix3d element_frame(const Eigen::Vector3d& a, const Eigen::Vector3d& b);

/// The 12x12 transformation diag(R, R, R, R): u_local = T u_global.
Matrix12d element_transformation(const Eigen::Matrix3d& frame);

/// T^T local_stiffness T for the element from a to b (length |b - a|).
Matrix12d global_stiffness(const Material& material, const BeamSection& section, const Eigen::Vector3d& a,
                           const Eigen::Vector3d& b);

/// T^T local_mass T for the element from a to b (length |b - a|).
Matrix12d global_mass(const Material& material, const BeamSection& section, const Eigen::Vector3d& a,
                      const Eigen::Vector3d& b);

}  // namespace fw::trees
