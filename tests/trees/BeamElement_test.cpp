#include "trees/BeamElement.hpp"

#include <catch2/catch.hpp>

#include <Eigen/Eigenvalues>
#include <Eigen/Geometry>

#include <algorithm>
#include <cmath>
#include <numbers>
#include <stdexcept>
#include <vector>

#include "trees/Material.hpp"

using fw::trees::BeamSection;
using fw::trees::Material;
using fw::trees::Matrix12d;

namespace {

const Material kWood{1.0e10, 3.85e9, 900.0};

Eigen::VectorXd eigenvalues(const Matrix12d& m) {
  Eigen::SelfAdjointEigenSolver<Matrix12d> solver(m, Eigen::EigenvaluesOnly);
  REQUIRE(solver.info() == Eigen::Success);
  return solver.eigenvalues();  // ascending
}

// Element end points in several orientations: along each axis (the vertical ones take the other branch of
// element_frame), pointing down, near vertical on both sides of the switch, and oblique.
std::vector<std::pair<Eigen::Vector3d, Eigen::Vector3d>> orientations(double length) {
  std::vector<Eigen::Vector3d> directions = {
      Eigen::Vector3d::UnitX(),  Eigen::Vector3d::UnitY(), Eigen::Vector3d::UnitZ(),
      -Eigen::Vector3d::UnitZ(), {0.3, -0.2, 1.0},         {0.48, 0.0, 1.0},
      {0.49, 0.0, 1.0},          {1.0, 2.0, -0.5},         {-0.7, 0.1, 0.05}};
  std::vector<std::pair<Eigen::Vector3d, Eigen::Vector3d>> ends;
  const Eigen::Vector3d a(1.5, -2.0, 0.75);
  for (const auto& d : directions) ends.emplace_back(a, a + length * d.normalized());
  return ends;
}

// A rigid motion of both nodes: translation t plus small rotation theta about node a.
Eigen::Matrix<double, 12, 1> rigid_motion(const Eigen::Vector3d& a, const Eigen::Vector3d& b,
                                          const Eigen::Vector3d& t, const Eigen::Vector3d& theta) {
  Eigen::Matrix<double, 12, 1> u;
  u.segment<3>(0) = t;
  u.segment<3>(3) = theta;
  u.segment<3>(6) = t + theta.cross(b - a);
  u.segment<3>(9) = theta;
  return u;
}

}  // namespace

TEST_CASE("BeamSection: a circle has A = pi r^2, I = pi r^4/4, J = pi r^4/2") {
  const double r = 0.02;
  const auto s = BeamSection::circle(r);
  const double pi = std::numbers::pi;
  // Tolerance: rounding only, 1e-14 relative.
  CHECK(s.area == Approx(pi * r * r).epsilon(1e-14));
  CHECK(s.second_moment == Approx(pi * std::pow(r, 4) / 4.0).epsilon(1e-14));
  CHECK(s.polar_moment == Approx(pi * std::pow(r, 4) / 2.0).epsilon(1e-14));
  CHECK_NOTHROW(s.validate());
}

TEST_CASE("BeamSection: a non-positive or non-finite radius is rejected") {
  CHECK_THROWS_WITH(BeamSection::circle(0.0), Catch::Contains("BeamSection: radius"));
  CHECK_THROWS_AS(BeamSection::circle(-0.1), std::invalid_argument);
  CHECK_THROWS_AS(BeamSection::circle(std::nan("")), std::invalid_argument);
  CHECK_THROWS_AS(BeamSection::circle(INFINITY), std::invalid_argument);
  CHECK_THROWS_WITH((BeamSection{1.0, 0.0, 1.0}.validate()), Catch::Contains("second_moment"));
}

TEST_CASE("Material: non-positive or non-finite values are rejected with the field name") {
  CHECK_NOTHROW(kWood.validate());
  CHECK_THROWS_WITH((Material{0.0, 1.0, 1.0}.validate()), Catch::Contains("Material: youngs_modulus"));
  CHECK_THROWS_WITH((Material{1.0, -1.0, 1.0}.validate()), Catch::Contains("Material: shear_modulus"));
  CHECK_THROWS_WITH((Material{1.0, 1.0, std::nan("")}.validate()), Catch::Contains("Material: density"));
  CHECK_THROWS_AS((Material{1.0, INFINITY, 1.0}.validate()), std::invalid_argument);
}

TEST_CASE("BeamElement: invalid lengths, materials and end points are rejected") {
  const auto s = BeamSection::circle(0.05);
  CHECK_THROWS_WITH(fw::trees::local_stiffness(kWood, s, 0.0), Catch::Contains("BeamElement: length"));
  CHECK_THROWS_AS(fw::trees::local_mass(kWood, s, -1.0), std::invalid_argument);
  CHECK_THROWS_AS(fw::trees::local_stiffness(Material{1.0e10, 0.0, 900.0}, s, 1.0), std::invalid_argument);
  const Eigen::Vector3d p(1.0, 2.0, 3.0);
  CHECK_THROWS_WITH(fw::trees::element_frame(p, p),
                    Catch::Contains("BeamElement: element end points coincide"));
  CHECK_THROWS_AS(fw::trees::element_frame(p, Eigen::Vector3d(NAN, 0.0, 0.0)), std::invalid_argument);
}

TEST_CASE("BeamElement: element_frame is a right-handed orthonormal frame with x along the element") {
  for (const auto& [a, b] : orientations(0.8)) {
    const Eigen::Matrix3d r = fw::trees::element_frame(a, b);
    // Tolerance: rounding, 1e-14 absolute on unit-sized quantities.
    CHECK((r * r.transpose() - Eigen::Matrix3d::Identity()).cwiseAbs().maxCoeff() < 1e-14);
    CHECK(r.determinant() == Approx(1.0).epsilon(1e-14));
    CHECK((r.row(0).transpose() - (b - a).normalized()).norm() < 1e-14);
  }
  // A horizontal element keeps local y horizontal.
  const Eigen::Matrix3d h = fw::trees::element_frame(Eigen::Vector3d::Zero(), Eigen::Vector3d(1.0, 1.0, 0.2));
  CHECK(std::abs(h(1, 2)) < 1e-15);
}

TEST_CASE("BeamElement: local K is symmetric positive semi-definite with exactly 6 zero eigenvalues") {
  const auto s = BeamSection::circle(0.05);
  const Matrix12d k = fw::trees::local_stiffness(kWood, s, 0.5);
  // Tolerance: exact symmetry, the matrix is built entry by entry symmetrically.
  CHECK((k - k.transpose()).cwiseAbs().maxCoeff() == 0.0);
  const Eigen::VectorXd ev = eigenvalues(k);
  const double largest = ev.maxCoeff();
  // Tolerance: a zero eigenvalue is below 1e-11 of the largest (rounding is ~1e-15 of it); the smallest
  // non-zero one (torsion, 2 GJ/L) is ~1e-6 of the largest here, far above that.
  int zeros = 0;
  for (int i = 0; i < 12; ++i) {
    CHECK(ev(i) > -1e-11 * largest);
    if (std::abs(ev(i)) < 1e-11 * largest) ++zeros;
  }
  CHECK(zeros == 6);
  CHECK(ev(6) > 1e-8 * largest);
}

TEST_CASE("BeamElement: local K has the textbook axial, torsion and bending entries and signs") {
  const auto s = BeamSection::circle(0.05);
  const double L = 0.5;
  const Matrix12d k = fw::trees::local_stiffness(kWood, s, L);
  const double ea = kWood.youngs_modulus * s.area, gj = kWood.shear_modulus * s.polar_moment;
  const double ei = kWood.youngs_modulus * s.second_moment;
  // Tolerance: rounding, 1e-13 relative.
  CHECK(k(0, 0) == Approx(ea / L).epsilon(1e-13));
  CHECK(k(0, 6) == Approx(-ea / L).epsilon(1e-13));
  CHECK(k(3, 9) == Approx(-gj / L).epsilon(1e-13));
  CHECK(k(1, 1) == Approx(12 * ei / (L * L * L)).epsilon(1e-13));
  CHECK(k(1, 5) == Approx(6 * ei / (L * L)).epsilon(1e-13));   // rz = +duy/dx
  CHECK(k(2, 4) == Approx(-6 * ei / (L * L)).epsilon(1e-13));  // ry = -duz/dx
  CHECK(k(5, 11) == Approx(2 * ei / L).epsilon(1e-13));
  CHECK(k(4, 4) == Approx(4 * ei / L).epsilon(1e-13));
}

TEST_CASE("BeamElement: a one-element cantilever gives PL^3/(3EI) and the right-handed tip rotation") {
  // Node a clamped, a unit tip force on node b: the Hermite cubic is exact for this load.
  const auto s = BeamSection::circle(0.05);
  const double L = 0.5, P = 1.0;
  const Matrix12d k = fw::trees::local_stiffness(kWood, s, L);
  const Eigen::Matrix<double, 6, 6> kbb = k.block<6, 6>(6, 6);
  const double ei = kWood.youngs_modulus * s.second_moment;
  Eigen::Matrix<double, 6, 1> f = Eigen::Matrix<double, 6, 1>::Zero();
  f(1) = P;  // +y
  Eigen::Matrix<double, 6, 1> u = kbb.ldlt().solve(f);
  // Tolerance: 1e-10 relative (exact up to the 6x6 solve).
  CHECK(u(1) == Approx(P * L * L * L / (3 * ei)).epsilon(1e-10));
  CHECK(u(5) == Approx(P * L * L / (2 * ei)).epsilon(1e-10));  // bends towards +y: rotation about +z
  f.setZero();
  f(2) = P;  // +z
  u = kbb.ldlt().solve(f);
  CHECK(u(2) == Approx(P * L * L * L / (3 * ei)).epsilon(1e-10));
  CHECK(u(4) == Approx(-P * L * L / (2 * ei)).epsilon(1e-10));  // bends towards +z: rotation about -y
}

TEST_CASE("BeamElement: global K annihilates rigid translations and rotations in any orientation") {
  const auto s = BeamSection::circle(0.05);
  for (const auto& [a, b] : orientations(0.5)) {
    const Matrix12d k = fw::trees::global_stiffness(kWood, s, a, b);
    const double scale = k.cwiseAbs().maxCoeff();
    for (int axis = 0; axis < 3; ++axis) {
      const Eigen::Vector3d e = Eigen::Vector3d::Unit(axis);
      // Tolerance: the force of a unit rigid motion is rounding, below 1e-12 of the largest entry of K.
      CHECK((k * rigid_motion(a, b, e, Eigen::Vector3d::Zero())).cwiseAbs().maxCoeff() < 1e-12 * scale);
      CHECK((k * rigid_motion(a, b, Eigen::Vector3d::Zero(), e)).cwiseAbs().maxCoeff() < 1e-12 * scale);
    }
  }
}

TEST_CASE("BeamElement: local M is symmetric positive definite with the translational mass rho A L") {
  const auto s = BeamSection::circle(0.05);
  const double L = 0.5;
  const Matrix12d m = fw::trees::local_mass(kWood, s, L);
  CHECK((m - m.transpose()).cwiseAbs().maxCoeff() == 0.0);
  const Eigen::VectorXd ev = eigenvalues(m);
  CHECK(ev(0) > 0.0);
  const double mass = kWood.density * s.area * L;
  for (int axis = 0; axis < 3; ++axis) {
    Eigen::Matrix<double, 12, 1> u = Eigen::Matrix<double, 12, 1>::Zero();
    u(axis) = u(6 + axis) = 1.0;
    // Tolerance: rounding, 1e-13 relative.
    CHECK(u.dot(m * u) == Approx(mass).epsilon(1e-13));
  }
  // Torsion about the element axis: inertia rho J L.
  Eigen::Matrix<double, 12, 1> twist = Eigen::Matrix<double, 12, 1>::Zero();
  twist(3) = twist(9) = 1.0;
  CHECK(twist.dot(m * twist) == Approx(kWood.density * s.polar_moment * L).epsilon(1e-13));
  // No rotary inertia of bending: the inertia of ry alone comes only from the transverse motion of its
  // Hermite slope function, rho A L * 4 L^2 / 420 = rho A L^3 / 105.
  CHECK(m(4, 4) == Approx(mass * L * L / 105.0).epsilon(1e-13));
}

TEST_CASE("BeamElement: global M carries rho A L for a rigid translation in any direction") {
  const auto s = BeamSection::circle(0.03);
  const double L = 0.7;
  const double mass = kWood.density * s.area * L;
  const Eigen::Vector3d dir = Eigen::Vector3d(0.2, -0.9, 0.4).normalized();
  for (const auto& [a, b] : orientations(L)) {
    const Matrix12d m = fw::trees::global_mass(kWood, s, a, b);
    CHECK(eigenvalues(m)(0) > 0.0);
    for (const Eigen::Vector3d& d : {Eigen::Vector3d::UnitX().eval(), Eigen::Vector3d::UnitZ().eval(), dir}) {
      const auto u = rigid_motion(a, b, d, Eigen::Vector3d::Zero());
      // Tolerance: rounding, 1e-12 relative.
      CHECK(u.dot(m * u) == Approx(mass).epsilon(1e-12));
    }
  }
}

TEST_CASE("BeamElement: rotating the element leaves the eigenvalues of K and M unchanged") {
  const auto s = BeamSection::circle(0.04);
  const double L = 0.6;
  const Eigen::VectorXd k_local = eigenvalues(fw::trees::local_stiffness(kWood, s, L));
  const Eigen::VectorXd m_local = eigenvalues(fw::trees::local_mass(kWood, s, L));
  for (const auto& [a, b] : orientations(L)) {
    const Eigen::VectorXd k_global = eigenvalues(fw::trees::global_stiffness(kWood, s, a, b));
    const Eigen::VectorXd m_global = eigenvalues(fw::trees::global_mass(kWood, s, a, b));
    // Tolerance: 1e-11 of the largest eigenvalue (rounding in T^T K T and in the solver).
    CHECK((k_global - k_local).cwiseAbs().maxCoeff() < 1e-11 * k_local.maxCoeff());
    CHECK((m_global - m_local).cwiseAbs().maxCoeff() < 1e-11 * m_local.maxCoeff());
  }
}
