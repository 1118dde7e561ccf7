#include "trees/BeamElement.hpp"

#include <cmath>
#include <numbers>
#include <stdexcept>
#include <string>

#include <fmt/format.h>

#include "trees/Material.hpp"

namespace fw::trees {

namespace {

// Beyond this |cos| between the element and global z, the element counts as vertical for the frame choice.
constexpr double kVerticalCosine = 0.9;

void check_length(double length) {
  if (!std::isfinite(length) || !(length > 0.0)) {
    throw std::invalid_argument(
        fmt::format("BeamElement: length must be finite and positive, got {}", length));
  }
}

// Adds the 2x2 matrix c [a b; b a] on DOFs (i, j).
void add_two_node(Matrix12d& m, int i, int j, double c, double diag, double off) {
  m(i, i) += c * diag;
  m(j, j) += c * diag;
  m(i, j) += c * off;
  m(j, i) += c * off;
}

// Adds a 4x4 bending-plane matrix given in (v_a, v'_a, v_b, v'_b), where v' = dv/ds, on the DOFs
// (v_a, r_a, v_b, r_b) with r = sign * v'.
void add_bending_plane(Matrix12d& m, const Eigen::Matrix4d& plane, int v_a, int r_a, int v_b, int r_b,
                       double sign) {
  const int dof[4] = {v_a, r_a, v_b, r_b};
  const double scale[4] = {1.0, sign, 1.0, sign};
  for (int i = 0; i < 4; ++i) {
    for (int j = 0; j < 4; ++j) m(dof[i], dof[j]) += scale[i] * scale[j] * plane(i, j);
  }
}

// Signs of the rotation DOFs relative to the slopes: rz = +uy', ry = -uz'.
constexpr double kSignXY = 1.0;
constexpr double kSignXZ = -1.0;

}  // namespace

BeamSection BeamSection::circle(double radius) {
  if (!std::isfinite(radius) || !(radius > 0.0)) {
    throw std::invalid_argument(
        fmt::format("BeamSection: radius must be finite and positive, got {}", radius));
  }
  const double r2 = radius * radius;
  const double pi = std::numbers::pi;
  return BeamSection{pi * r2, pi * r2 * r2 / 4.0, pi * r2 * r2 / 2.0};
}

void BeamSection::validate() const {
  const auto check = [](const char* name, double value) {
    if (!std::isfinite(value) || !(value > 0.0)) {
      throw std::invalid_argument(
          fmt::format("BeamSection: {} must be finite and positive, got {}", name, value));
    }
  };
  check("area (A, m^2)", area);
  check("second_moment (I, m^4)", second_moment);
  check("polar_moment (J, m^4)", polar_moment);
}

Matrix12d local_stiffness(const Material& material, const BeamSection& section, double length) {
  material.validate();
  section.validate();
  check_length(length);
  const double L = length;
  const double E = material.youngs_modulus;
  const double G = material.shear_modulus;

  Matrix12d k = Matrix12d::Zero();
  add_two_node(k, 0, 6, E * section.area / L, 1.0, -1.0);          // axial
  add_two_node(k, 3, 9, G * section.polar_moment / L, 1.0, -1.0);  // torsion

  // Hermite cubic bending, in (v_a, v'_a, v_b, v'_b).
  Eigen::Matrix4d bend;
  bend << 12.0, 6.0 * L, -12.0, 6.0 * L,            //
      6.0 * L, 4.0 * L * L, -6.0 * L, 2.0 * L * L,  //
      -12.0, -6.0 * L, 12.0, -6.0 * L,              //
      6.0 * L, 2.0 * L * L, -6.0 * L, 4.0 * L * L;
  bend *= E * section.second_moment / (L * L * L);
  add_bending_plane(k, bend, 1, 5, 7, 11, kSignXY);  // uy, rz
  add_bending_plane(k, bend, 2, 4, 8, 10, kSignXZ);  // uz, ry
  return k;
}

Matrix12d local_mass(const Material& material, const BeamSection& section, double length) {
  material.validate();
  section.validate();
  check_length(length);
  const double L = length;
  const double rho = material.density;

  Matrix12d m = Matrix12d::Zero();
  add_two_node(m, 0, 6, rho * section.area * L / 6.0, 2.0, 1.0);          // axial, linear shape functions
  add_two_node(m, 3, 9, rho * section.polar_moment * L / 6.0, 2.0, 1.0);  // torsion, linear

  // Consistent translational mass of the Hermite cubic, in (v_a, v'_a, v_b, v'_b).
  Eigen::Matrix4d bend;
  bend << 156.0, 22.0 * L, 54.0, -13.0 * L,           //
      22.0 * L, 4.0 * L * L, 13.0 * L, -3.0 * L * L,  //
      54.0, 13.0 * L, 156.0, -22.0 * L,               //
      -13.0 * L, -3.0 * L * L, -22.0 * L, 4.0 * L * L;
  bend *= rho * section.area * L / 420.0;
  add_bending_plane(m, bend, 1, 5, 7, 11, kSignXY);
  add_bending_plane(m, bend, 2, 4, 8, 10, kSignXZ);
  return m;
}

Eigen::Matrix3d element_frame(const Eigen::Vector3d& a, const Eigen::Vector3d& b) {
  if (!a.allFinite() || !b.allFinite()) {
    throw std::invalid_argument("BeamElement: element end points must be finite");
  }
  const Eigen::Vector3d d = b - a;
  const double length = d.norm();
  if (!(length > 0.0) || !std::isfinite(length)) {
    throw std::invalid_argument(
        fmt::format("BeamElement: element end points coincide at ({}, {}, {})", a.x(), a.y(), a.z()));
  }
  const Eigen::Vector3d x = d / length;
  const Eigen::Vector3d reference =
      std::abs(x.z()) < kVerticalCosine ? Eigen::Vector3d::UnitZ() : Eigen::Vector3d::UnitX();
  // |reference x x| >= sqrt(1 - 0.9^2) > 0.43 for either choice, so the normalisation is well conditioned.
  const Eigen::Vector3d y = reference.cross(x).normalized();
  const Eigen::Vector3d z = x.cross(y);
  Eigen::Matrix3d frame;
  frame.row(0) = x.transpose();
  frame.row(1) = y.transpose();
  frame.row(2) = z.transpose();
  return frame;
}

Matrix12d element_transformation(const Eigen::Matrix3d& frame) {
  Matrix12d t = Matrix12d::Zero();
  for (int block = 0; block < 4; ++block) t.block<3, 3>(3 * block, 3 * block) = frame;
  return t;
}

Matrix12d global_stiffness(const Material& material, const BeamSection& section, const Eigen::Vector3d& a,
                           const Eigen::Vector3d& b) {
  const Matrix12d t = element_transformation(element_frame(a, b));
  const Matrix12d k = local_stiffness(material, section, (b - a).norm());
  Matrix12d g = t.transpose() * k * t;
  return 0.5 * (g + g.transpose());  // exactly symmetric despite rounding
}

Matrix12d global_mass(const Material& material, const BeamSection& section, const Eigen::Vector3d& a,
                      const Eigen::Vector3d& b) {
  const Matrix12d t = element_transformation(element_frame(a, b));
  const Matrix12d m = local_mass(material, section, (b - a).norm());
  Matrix12d g = t.transpose() * m * t;
  return 0.5 * (g + g.transpose());
}

}  // namespace fw::trees
