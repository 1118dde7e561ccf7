// trees/StaticDeflection: the FEM's static answer to a steady wind bends a slender cantilever as beam theory
// says, and it is the modal static solution with every mode kept.
#include "trees/StaticDeflection.hpp"

#include <catch2/catch.hpp>

#include <Eigen/Eigenvalues>

#include <cmath>
#include <numbers>
#include <vector>

namespace {

using fw::trees::BeamModel;
using fw::trees::Material;
using fw::trees::Skeleton;
using fw::trees::SkeletonNode;
using fw::trees::WindBasisSettings;

const Material kWood{1.0e10, 3.85e9, 900.0};

// Wood drag only: the load per metre is 1/2 rho C_D D |v| v with D = r_a + r_b (trees/WindBasis.hpp).
WindBasisSettings wood_drag() {
  WindBasisSettings drag;
  drag.leaf_area_index = 0.0;
  return drag;
}

}  // namespace

TEST_CASE(
    "StaticDeflection: a uniform wind bends a slender cantilever as Euler-Bernoulli's w x^2 (6 L^2 - 4 L x "
    "+ x^2) / (24 E I)",
    "[trees]") {
  constexpr double kLength = 4.0, kRadius = 0.02;  // m: slender (L / r = 200), so shear hardly adds
  constexpr int kElements = 20;
  std::vector<SkeletonNode> nodes;
  for (int i = 0; i <= kElements; ++i)
    nodes.push_back({i - 1, Eigen::Vector3d(0.0, 0.0, kLength * i / kElements), kRadius});
  const Skeleton skeleton = Skeleton::from_nodes(nodes);
  const BeamModel model(skeleton, kWood);
  const WindBasisSettings drag = wood_drag();
  const double speed = 10.0;  // m/s along x
  const Eigen::MatrixX3d u = fw::trees::static_deflection(skeleton, model, drag, {speed, 0.0, 0.0});

  const double w =
      0.5 * drag.air_density * drag.branch_drag_coefficient * 2.0 * kRadius * speed * speed;  // N/m
  const double EI = kWood.youngs_modulus * std::numbers::pi * std::pow(kRadius, 4) / 4.0;
  const double tip = w * std::pow(kLength, 4) / (8.0 * EI);
  // Tolerance: cubic elements with consistent loads are exact at the nodes for Euler-Bernoulli; Timoshenko's
  // shear adds E r^2 / (kappa G L^2), about 1e-4 of the bending here.
  constexpr double kRelative = 1e-3;
  for (int i = 0; i <= kElements; ++i) {
    const double x = kLength * i / kElements;
    const double expected = w * x * x * (6 * kLength * kLength - 4 * kLength * x + x * x) / (24.0 * EI);
    INFO("node " << i << " at " << x << " m");
    CHECK(u(i, 0) == Approx(expected).margin(kRelative * tip));
    CHECK(std::abs(u(i, 1)) < 1e-12 * tip);  // no load across the wind, none along the axis
    CHECK(std::abs(u(i, 2)) < 1e-12 * tip);
  }
  CHECK(u(kElements, 0) == Approx(tip).epsilon(kRelative));
}

TEST_CASE("StaticDeflection: with every mode kept the modal static solution is the direct solve's",
          "[trees]") {
  // A trunk of 6 elements and two branches of 3, leaning: every DOF couples.
  const Skeleton skeleton = Skeleton::from_nodes({{-1, {0, 0, 0}, 0.12},
                                                  {0, {0, 0, 0.7}, 0.11},
                                                  {1, {0, 0, 1.4}, 0.10},
                                                  {2, {0, 0, 2.1}, 0.09},
                                                  {3, {0, 0, 2.8}, 0.07},
                                                  {4, {0, 0, 3.4}, 0.06},
                                                  {5, {0, 0, 4.0}, 0.04},
                                                  {3, {0.5, 0.2, 2.5}, 0.04},
                                                  {7, {1.0, 0.35, 2.8}, 0.03},
                                                  {8, {1.4, 0.5, 3.0}, 0.02},
                                                  {5, {-0.4, -0.3, 3.7}, 0.03},
                                                  {10, {-0.8, -0.5, 3.9}, 0.02},
                                                  {11, {-1.1, -0.7, 4.0}, 0.015}});
  const BeamModel model(skeleton, kWood);
  WindBasisSettings drag = wood_drag();
  drag.leaf_area_index = 2.0;  // foliage on the leaf-bearing elements too
  const Eigen::Vector3d wind(12.0, -5.0, 1.0);
  const Eigen::MatrixX3d direct = fw::trees::static_deflection(skeleton, model, drag, wind);

  // Every mode from a dense generalised eigensolve (K phi = omega^2 M phi, M-normalised), and the nodal load.
  const Eigen::MatrixXd K(model.stiffness()), M(model.mass());
  const Eigen::GeneralizedSelfAdjointEigenSolver<Eigen::MatrixXd> modes(K, M);
  REQUIRE(modes.info() == Eigen::Success);
  const Eigen::MatrixXd G = fw::trees::WindBasis::load_operator(skeleton, drag);
  const Eigen::VectorXd loads = G * fw::trees::WindBasis::squared_wind(wind.transpose());
  Eigen::VectorXd F = Eigen::VectorXd::Zero(model.dof_count());
  for (int node = 0; node < model.node_count(); ++node)
    for (int local = 0; local < 6; ++local)
      if (const int dof = model.free_dof_of(node, local); dof >= 0) F(dof) = loads(6 * node + local);
  Eigen::VectorXd modal = Eigen::VectorXd::Zero(model.dof_count());
  for (int i = 0; i < model.dof_count(); ++i) {
    const Eigen::VectorXd phi = modes.eigenvectors().col(i);
    modal += phi * (phi.dot(F) / modes.eigenvalues()(i));
  }
  const double largest = direct.cwiseAbs().maxCoeff();
  REQUIRE(largest > 0.0);
  for (int node = 0; node < model.node_count(); ++node)
    for (int axis = 0; axis < 3; ++axis) {
      const int dof = model.free_dof_of(node, axis);
      const double expected = dof >= 0 ? modal(dof) : 0.0;
      INFO("node " << node << " axis " << axis);
      // Tolerance: the dense eigensolve's round-off over the stiffness's spread of scales.
      CHECK(direct(node, axis) == Approx(expected).margin(1e-8 * largest));
    }
}
