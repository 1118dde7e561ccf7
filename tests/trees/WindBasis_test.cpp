#include "trees/WindBasis.hpp"

#include <catch2/catch.hpp>

#include <Eigen/Dense>
#include <Eigen/Eigenvalues>

#include <algorithm>
#include <cmath>
#include <limits>
#include <numbers>
#include <stdexcept>
#include <string>
#include <vector>

#include "trees/BeamModel.hpp"
#include "trees/Foliage.hpp"
#include "trees/Material.hpp"
#include "trees/Skeleton.hpp"

using fw::trees::BeamModel;
using fw::trees::Foliage;
using fw::trees::integrated_shape_functions;
using fw::trees::Material;
using fw::trees::Skeleton;
using fw::trees::SkeletonNode;
using fw::trees::WindBasis;
using fw::trees::WindBasisSettings;

namespace {

const Material kWood{1.0e10, 3.85e9, 900.0};
// 1/2 rho_air C_Db with the defaults: the woody drag per unit diameter and length, kg/m^3.
constexpr double kDrag = 0.5 * WindBasisSettings::kAirDensity * WindBasisSettings::kCylinderDragCoefficient;
// A leaf area index that makes the foliage's drag comparable to the wood's on branched_tree().
constexpr double kLeafAreaIndex = 3.0;

// Appends a straight branch of `count` elements from node `from` to `end`, the radius tapering linearly from
// the parent's radius to `end_radius`. Returns the index of its last node.
int add_branch(std::vector<SkeletonNode>& nodes, int from, const Eigen::Vector3d& end, double end_radius,
               int count) {
  const Eigen::Vector3d start = nodes[std::size_t(from)].position;
  const double start_radius = nodes[std::size_t(from)].radius;
  int parent = from;
  for (int k = 1; k <= count; ++k) {
    const double t = double(k) / count;
    nodes.push_back({parent, start + t * (end - start), start_radius + t * (end_radius - start_radius)});
    parent = int(nodes.size()) - 1;
  }
  return parent;
}

// A small branched tree, 40 nodes: a vertical trunk of 11 elements to z = 4 m, an inclined branch with a
// horizontal side branch, a horizontal branch, a drooping branch and an inclined top branch that holds the
// highest node (z = 4.6 m). With 3 height bands (borders at 1.533 and 3.067 m) the trunk and the inclined
// branches cross the borders in the middle of elements.
Skeleton branched_tree() {
  std::vector<SkeletonNode> nodes;
  nodes.push_back({-1, {0.0, 0.0, 0.0}, 0.12});
  add_branch(nodes, 0, {0.0, 0.0, 4.0}, 0.04, 11);  // trunk: nodes 1..11, node k at z = 4k/11
  const int fork = add_branch(nodes, 4, {1.8, 0.3, 3.2}, 0.02, 7);
  add_branch(nodes, 7, {0.0, -1.5, 4.0 * 7 / 11}, 0.015, 6);                                    // horizontal
  add_branch(nodes, 9, {-0.8, 0.9, 4.6}, 0.015, 6);                                             // the top
  add_branch(nodes, 3, {-1.0, -0.3, 0.9}, 0.015, 5);                                            // drooping
  add_branch(nodes, fork - 4, {1.0, 1.2, nodes[std::size_t(fork - 4)].position.z()}, 0.01, 4);  // horizontal
  return Skeleton::from_nodes(std::move(nodes));
}

// The vertical uniform cantilever: L = 2 m, r = 0.02 m, 20 elements.
constexpr double kCantileverLength = 2.0;
constexpr double kCantileverRadius = 0.02;
constexpr int kCantileverElements = 20;

Skeleton vertical_cantilever() {
  std::vector<SkeletonNode> nodes;
  for (int i = 0; i <= kCantileverElements; ++i) {
    nodes.push_back(
        {i - 1, Eigen::Vector3d(0.0, 0.0, kCantileverLength * i / kCantileverElements), kCantileverRadius});
  }
  return Skeleton::from_nodes(std::move(nodes));
}

struct Modes {
  Eigen::VectorXd omega;    // rad/s, ascending
  Eigen::MatrixXd vectors;  // columns, M-normalised
};

// The lowest `count` modes (all when count < 0) from the dense generalized eigensolver.
Modes dense_modes(const BeamModel& model, int count = -1) {
  const Eigen::MatrixXd k(model.stiffness());
  const Eigen::MatrixXd m(model.mass());
  Eigen::GeneralizedSelfAdjointEigenSolver<Eigen::MatrixXd> solver(k, m);
  REQUIRE(solver.info() == Eigen::Success);
  const Eigen::Index n = count < 0 ? k.rows() : count;
  return {solver.eigenvalues().head(n).cwiseMax(0.0).cwiseSqrt(), solver.eigenvectors().leftCols(n)};
}

// max |a - b| / max |b|: the error relative to the reference's largest entry.
double relative_error(const Eigen::MatrixXd& a, const Eigen::MatrixXd& b) {
  return (a - b).cwiseAbs().maxCoeff() / b.cwiseAbs().maxCoeff();
}

Eigen::Matrix3d skew(const Eigen::Vector3d& v) {
  Eigen::Matrix3d m;
  m << 0.0, -v.z(), v.y(), v.z(), 0.0, -v.x(), -v.y(), v.x(), 0.0;
  return m;
}

// Everything the brute-force integrator hands to its callback at one quadrature point.
struct QuadraturePoint {
  Eigen::Vector3d position;  // m
  Eigen::Vector3d axis;      // unit element axis
  double diameter;           // m
  double weight;             // quadrature weight, m
  int band;                  // height band of the point
  std::size_t element;       // index into skeleton.elements()
  Eigen::Matrix3Xd phi;      // global displacement of every mode at the point (3 x m)
};

// Brute-force integration over the tree, written without the library's element frames or sign tables: the
// displacement along an element is interpolated in global vectors, axial part linear, transverse part cubic
// Hermite with end slopes r x axis (the rotation vector crossed with the axis, which is what rz = uy',
// ry = -uz' say in any local frame). Each element is cut where it crosses a band border (heights found here
// independently) and every piece is integrated with a composite 3-point Gauss-Legendre rule (sub_pieces
// sub-pieces), exact for the cubic integrand up to rounding.
template <class Callback>
void integrate_tree(const Skeleton& skeleton, const BeamModel& model, const Eigen::MatrixXd& shapes,
                    int bands, Callback&& callback, int sub_pieces = 4) {
  const double z_root = skeleton.node(skeleton.root()).position.z();
  double z_top = z_root;
  for (const auto& node : skeleton.nodes()) z_top = std::max(z_top, node.position.z());
  const double band_height = (z_top - z_root) / bands;
  const auto band_of = [&](double z) {
    return std::clamp(int(std::floor((z - z_root) / band_height)), 0, bands - 1);
  };
  const auto node_rows = [&](int node, int first) {
    Eigen::Matrix3Xd rows = Eigen::Matrix3Xd::Zero(3, shapes.cols());
    for (int k = 0; k < 3; ++k) {
      const int dof = model.free_dof_of(node, first + k);
      if (dof >= 0) rows.row(k) = shapes.row(dof);
    }
    return rows;
  };
  const double gauss_x[3] = {-std::sqrt(0.6), 0.0, std::sqrt(0.6)};
  const double gauss_w[3] = {5.0 / 9.0, 8.0 / 9.0, 5.0 / 9.0};

  for (std::size_t element = 0; element < skeleton.elements().size(); ++element) {
    const auto [parent, child] = skeleton.elements()[element];
    const Eigen::Vector3d a = skeleton.node(parent).position;
    const Eigen::Vector3d b = skeleton.node(child).position;
    const double length = (b - a).norm();
    const Eigen::Vector3d axis = (b - a) / length;
    const double diameter = skeleton.node(parent).radius + skeleton.node(child).radius;
    const Eigen::Matrix3Xd ua = node_rows(parent, 0), ub = node_rows(child, 0);
    const Eigen::Matrix3Xd slope_a = -skew(axis) * node_rows(parent, 3);  // r x axis
    const Eigen::Matrix3Xd slope_b = -skew(axis) * node_rows(child, 3);
    const Eigen::Matrix3d normal = Eigen::Matrix3d::Identity() - axis * axis.transpose();

    std::vector<double> cuts = {0.0, length};
    for (int k = 1; k < bands; ++k) {
      const double border = z_root + k * band_height;
      const double lo = std::min(a.z(), b.z()), hi = std::max(a.z(), b.z());
      if (border > lo && border < hi) cuts.push_back(length * (border - a.z()) / (b.z() - a.z()));
    }
    std::sort(cuts.begin(), cuts.end());

    for (std::size_t piece = 0; piece + 1 < cuts.size(); ++piece) {
      const double s0 = cuts[piece], s1 = cuts[piece + 1];
      const int band = band_of(a.z() + (b.z() - a.z()) * 0.5 * (s0 + s1) / length);
      for (int sub = 0; sub < sub_pieces; ++sub) {
        const double lo = s0 + (s1 - s0) * sub / sub_pieces, hi = s0 + (s1 - s0) * (sub + 1) / sub_pieces;
        for (int g = 0; g < 3; ++g) {
          const double s = 0.5 * (lo + hi) + 0.5 * (hi - lo) * gauss_x[g];
          const double t = s / length;
          const double h1 = 1.0 - 3.0 * t * t + 2.0 * t * t * t;
          const double h2 = length * t * (1.0 - t) * (1.0 - t);
          const double h3 = t * t * (3.0 - 2.0 * t);
          const double h4 = length * t * t * (t - 1.0);
          QuadraturePoint point{a + s * axis, axis,    diameter,          0.5 * (hi - lo) * gauss_w[g],
                                band,         element, Eigen::Matrix3Xd()};
          point.phi = axis * (axis.transpose() * ((1.0 - t) * ua + t * ub)) + normal * (h1 * ua + h3 * ub) +
                      h2 * slope_a + h4 * slope_b;
          callback(point);
        }
      }
    }
  }
}

struct Reference {
  Eigen::MatrixXd projection;      // (3S) x m
  Eigen::MatrixX3d sample_points;  // S x 3
};

Reference reference_basis(const Skeleton& skeleton, const BeamModel& model, const Eigen::MatrixXd& shapes,
                          const WindBasisSettings& settings) {
  const int bands = settings.samples;
  Reference ref{Eigen::MatrixXd::Zero(3 * bands, shapes.cols()), Eigen::MatrixX3d::Zero(bands, 3)};
  Eigen::VectorXd weight = Eigen::VectorXd::Zero(bands);
  const Foliage foliage = Foliage::of(skeleton, settings.leaf_area_index);
  const double half_rho = 0.5 * settings.air_density;
  integrate_tree(skeleton, model, shapes, bands, [&](const QuadraturePoint& q) {
    Eigen::Matrix3Xd wood = q.phi;
    // f . phi with f = C D P v equals C D v . (P phi): P is symmetric. The leaves drag with the whole wind.
    if (settings.branch_normal_drag) wood = wood - q.axis * (q.axis.transpose() * wood);
    const double leaf = foliage.leaf_area_per_metre[q.element];
    ref.projection.middleRows(3 * q.band, 3) += half_rho * q.weight *
                                                (settings.branch_drag_coefficient * q.diameter * wood +
                                                 settings.leaf_drag_coefficient * leaf * q.phi);
    const double width =
        settings.branch_drag_coefficient * q.diameter + settings.leaf_drag_coefficient * leaf;
    ref.sample_points.row(q.band) += width * q.weight * q.position.transpose();
    weight(q.band) += width * q.weight;
  });
  for (int band = 0; band < bands; ++band) ref.sample_points.row(band) /= weight(band);
  return ref;
}

WindBasisSettings make_settings(bool normal, int samples, double leaf_area_index = 0.0) {
  WindBasisSettings settings;
  settings.air_density = WindBasisSettings::kAirDensity;
  settings.branch_drag_coefficient = WindBasisSettings::kCylinderDragCoefficient;
  settings.leaf_area_index = leaf_area_index;
  settings.branch_normal_drag = normal;
  settings.samples = samples;
  return settings;
}

}  // namespace

TEST_CASE("integrated_shape_functions matches quadrature of the Hermite functions", "[windbasis]") {
  const double length = 0.7;
  // Local shape functions written out: rows ux, uy, uz; rz = +uy', ry = -uz'.
  const auto shape = [&](double s) {
    const double t = s / length;
    const double h1 = 1.0 - 3.0 * t * t + 2.0 * t * t * t, h2 = length * (t - 2.0 * t * t + t * t * t);
    const double h3 = 3.0 * t * t - 2.0 * t * t * t, h4 = length * (t * t * t - t * t);
    Eigen::Matrix<double, 3, 12> n = Eigen::Matrix<double, 3, 12>::Zero();
    n(0, 0) = 1.0 - t;
    n(0, 6) = t;
    n(1, 1) = h1, n(1, 5) = h2, n(1, 7) = h3, n(1, 11) = h4;
    n(2, 2) = h1, n(2, 4) = -h2, n(2, 8) = h3, n(2, 10) = -h4;
    return n;
  };
  const double ranges[][2] = {{0.0, length}, {0.0, 0.2}, {0.13, 0.51}, {0.4, length}, {0.3, 0.3}};
  double worst = 0.0;
  for (const auto& range : ranges) {
    // Midpoint rule with 20000 cells: error ~ L^3 / (24 n^2) times the second derivative, below 1e-9.
    constexpr int kCells = 20000;
    Eigen::Matrix<double, 3, 12> sum = Eigen::Matrix<double, 3, 12>::Zero();
    const double h = (range[1] - range[0]) / kCells;
    for (int c = 0; c < kCells; ++c) sum += h * shape(range[0] + (c + 0.5) * h);
    const Eigen::Matrix<double, 3, 12> closed = integrated_shape_functions(length, range[0], range[1]);
    worst = std::max(worst, (closed - sum).cwiseAbs().maxCoeff());
  }
  INFO("max abs error vs midpoint rule (entries up to 0.35 m): " << worst);
  CHECK(worst < 1e-9);

  // Stam's B matrix over the whole element.
  const Eigen::Matrix<double, 3, 12> whole = integrated_shape_functions(length, 0.0, length);
  const double L = length;
  CHECK(whole(0, 0) == Approx(L / 2));
  CHECK(whole(1, 1) == Approx(L / 2));
  CHECK(whole(1, 5) == Approx(L * L / 12));
  CHECK(whole(1, 11) == Approx(-L * L / 12));
  CHECK(whole(2, 4) == Approx(-L * L / 12));
  CHECK(whole(2, 10) == Approx(L * L / 12));

  CHECK_THROWS_AS(integrated_shape_functions(0.0, 0.0, 0.0), std::invalid_argument);
  CHECK_THROWS_AS(integrated_shape_functions(1.0, 0.5, 0.4), std::invalid_argument);
  CHECK_THROWS_AS(integrated_shape_functions(1.0, -0.1, 0.4), std::invalid_argument);
  CHECK_THROWS_AS(integrated_shape_functions(1.0, 0.1, 1.1), std::invalid_argument);
}

TEST_CASE("WindBasis closed form matches brute-force quadrature", "[windbasis]") {
  const Skeleton skeleton = branched_tree();
  REQUIRE(skeleton.size() == 40);
  const BeamModel model(skeleton, kWood);
  const Modes modes = dense_modes(model, 10);

  for (const bool normal : {false, true}) {
    for (const int samples : {1, 3}) {
      for (const double lai : {0.0, kLeafAreaIndex}) {
        const WindBasisSettings settings = make_settings(normal, samples, lai);
        const WindBasis basis = WindBasis::compute(skeleton, model, modes.vectors, settings);
        const Reference ref = reference_basis(skeleton, model, modes.vectors, settings);
        REQUIRE(basis.sample_count() == samples);
        REQUIRE(basis.mode_count() == 10);
        const double p_error = relative_error(basis.projection_matrix(), ref.projection);
        const double x_error = relative_error(basis.sample_points(), ref.sample_points);
        INFO("branch_normal_drag " << normal << ", samples " << samples << ", LAI " << lai);
        INFO("projection: max rel error (to the largest |p|) " << p_error);
        INFO("sample points: max rel error (to the largest |x|) " << x_error);
        CHECK(p_error < 1e-10);
        CHECK(x_error < 1e-12);
      }
    }
  }
}

TEST_CASE("WindBasis bands: per-point band membership agrees with the element splitting", "[windbasis]") {
  // A coarse but fully independent check of the band splitting: a fine midpoint rule that assigns every
  // point to the band of its own height, with no cuts at the borders.
  const Skeleton skeleton = branched_tree();
  const BeamModel model(skeleton, kWood);
  const Modes modes = dense_modes(model, 6);
  const int bands = 3;
  const WindBasis basis = WindBasis::compute(skeleton, model, modes.vectors, make_settings(false, bands));

  const double z_top = 4.6;
  Eigen::MatrixXd sum = Eigen::MatrixXd::Zero(3 * bands, modes.vectors.cols());
  // Reuse the quadrature with one band (no cuts) and 500 sub-pieces per element, splitting the points by
  // height here.
  integrate_tree(
      skeleton, model, modes.vectors, 1,
      [&](const QuadraturePoint& q) {
        const int band = std::clamp(int(std::floor(q.position.z() / z_top * bands)), 0, bands - 1);
        sum.middleRows(3 * band, 3) += kDrag * q.diameter * q.weight * q.phi;
      },
      500);
  const double error = relative_error(basis.projection_matrix(), sum);
  INFO("max rel error with per-point bands (Gauss points, no cuts): " << error);
  // Only the sub-piece holding a border is split wrongly: an error of order 1/500 of a crossing element's
  // share. Putting a whole crossing element into one band gives errors of order 1e-2.
  CHECK(error < 1e-3);
  const Eigen::MatrixXd one_band =
      WindBasis::compute(skeleton, model, modes.vectors, make_settings(false, 1)).projection_matrix();
  // The bands really differ from an even split of the total.
  CHECK((basis.projection_matrix().middleRows(0, 3) - one_band / bands).cwiseAbs().maxCoeff() >
        0.1 * one_band.cwiseAbs().maxCoeff());
}

TEST_CASE("WindBasis bands sum to the single-sample basis and sample points lie in their bands",
          "[windbasis]") {
  const Skeleton skeleton = branched_tree();
  const BeamModel model(skeleton, kWood);
  const Modes modes = dense_modes(model, 12);

  for (const bool normal : {false, true}) {
    const WindBasis one =
        WindBasis::compute(skeleton, model, modes.vectors, make_settings(normal, 1, kLeafAreaIndex));
    for (const int samples : {2, 3, 5}) {
      const WindBasis banded =
          WindBasis::compute(skeleton, model, modes.vectors, make_settings(normal, samples, kLeafAreaIndex));
      Eigen::MatrixXd sum = Eigen::MatrixXd::Zero(3, modes.vectors.cols());
      for (int s = 0; s < samples; ++s) sum += banded.projection_matrix().middleRows(3 * s, 3);
      const double error = relative_error(sum, one.projection_matrix());
      INFO("branch_normal_drag " << normal << ", samples " << samples
                                 << ": sum of bands vs S = 1, max rel error " << error);
      CHECK(error < 1e-12);

      const double z_top = 4.6, band_height = z_top / samples;
      const Eigen::AlignedBox3d box = skeleton.bounding_box();
      for (int s = 0; s < samples; ++s) {
        const Eigen::Vector3d x = banded.sample_points().row(s).transpose();
        INFO("sample " << s << " at " << x.transpose());
        CHECK(x.z() >= s * band_height - 1e-12);
        CHECK(x.z() <= (s + 1) * band_height + 1e-12);
        CHECK(box.contains(x));
      }
    }
  }

  // S = 1: the diameter-weighted centroid of the branch length, from the node positions.
  Eigen::Vector3d moment = Eigen::Vector3d::Zero();
  double weight = 0.0;
  for (const auto& [parent, child] : skeleton.elements()) {
    const auto& a = skeleton.node(parent);
    const auto& b = skeleton.node(child);
    const double w = (a.radius + b.radius) * (b.position - a.position).norm();
    moment += w * 0.5 * (a.position + b.position);
    weight += w;
  }
  const WindBasis one = WindBasis::compute(skeleton, model, modes.vectors, make_settings(false, 1));
  const double error =
      (one.sample_points().row(0).transpose() - moment / weight).norm() / (moment / weight).norm();
  INFO("S = 1 sample point vs D-weighted centroid, rel error " << error);
  CHECK(error < 1e-13);

  // With leaves: weighted by the drag width C_Db D_e + C_Df lambda_e, which pulls it into the crown.
  const Foliage foliage = Foliage::of(skeleton, kLeafAreaIndex);
  Eigen::Vector3d leafy_moment = Eigen::Vector3d::Zero();
  double leafy_weight = 0.0;
  for (std::size_t e = 0; e < skeleton.elements().size(); ++e) {
    const auto& a = skeleton.node(skeleton.elements()[e].first);
    const auto& b = skeleton.node(skeleton.elements()[e].second);
    const double w = (WindBasisSettings::kCylinderDragCoefficient * (a.radius + b.radius) +
                      WindBasisSettings::kFoliageDragCoefficient * foliage.leaf_area_per_metre[e]) *
                     (b.position - a.position).norm();
    leafy_moment += w * 0.5 * (a.position + b.position);
    leafy_weight += w;
  }
  const WindBasis leafy =
      WindBasis::compute(skeleton, model, modes.vectors, make_settings(false, 1, kLeafAreaIndex));
  const Eigen::Vector3d leafy_centroid = leafy_moment / leafy_weight;
  CHECK((leafy.sample_points().row(0).transpose() - leafy_centroid).norm() < 1e-13 * leafy_centroid.norm());
  CHECK(leafy_centroid.z() > (moment / weight).z());  // the trunk's base weighs less against the leaves
}

TEST_CASE("WindBasis cantilever: rigid translation and the static deflection q L^4 / (8 E I)",
          "[windbasis]") {
  const Skeleton skeleton = vertical_cantilever();
  const BeamModel model(skeleton, kWood);
  const int tip = kCantileverElements;
  const double L = kCantileverLength, r = kCantileverRadius, D = 2.0 * r;
  const double element = L / kCantileverElements;

  SECTION("rigid translation fields") {
    // ux = 1 (or uz = 1) at every free node, rotations 0: the root element ramps from 0 (Hermite h3, whose
    // integral is L_e / 2), so p = C D (L - L_e / 2) along that direction.
    Eigen::MatrixXd shapes = Eigen::MatrixXd::Zero(model.dof_count(), 2);
    for (int node = 1; node <= tip; ++node) {
      shapes(model.free_dof_of(node, 0), 0) = 1.0;
      shapes(model.free_dof_of(node, 2), 1) = 1.0;
    }
    const double expected = kDrag * D * (L - 0.5 * element);
    const WindBasis plain = WindBasis::compute(skeleton, model, shapes, make_settings(false, 1));
    CHECK(plain.projection(0, 0).x() == Approx(expected).epsilon(1e-13));
    CHECK(plain.projection(0, 0).tail<2>().norm() < 1e-15);
    CHECK(plain.projection(0, 1).z() == Approx(expected).epsilon(1e-13));
    CHECK(plain.projection(0, 1).head<2>().norm() < 1e-15);
    // Axial wind drags nothing with branch_normal_drag.
    const WindBasis normal = WindBasis::compute(skeleton, model, shapes, make_settings(true, 1));
    CHECK(normal.projection(0, 0).x() == Approx(expected).epsilon(1e-13));
    CHECK(normal.projection(0, 1).norm() < 1e-15);
    // Uniform wind v along x: f = C D (L - L_e/2) |v| v_x on the x translation.
    Eigen::MatrixX3d wind(1, 3);
    wind << 7.0, 0.0, 0.0;
    CHECK(plain.modal_forces(wind)(0) == Approx(expected * 49.0).epsilon(1e-13));
  }

  SECTION("static response from all modes") {
    // K^-1 = sum_i phi_i phi_i^T / omega_i^2 for M-normalised modes, and phi_i^T F = f_i for the consistent
    // load F of q = C D |v| v, so u = sum_i phi_i f_i / omega_i^2 is the static deflection. Hermite elements
    // with consistent loads reproduce the Euler-Bernoulli nodal values exactly.
    const Modes modes = dense_modes(model);
    const double v = 12.0;
    const double q = kDrag * D * v * v;
    const double EI = kWood.youngs_modulus * std::numbers::pi * std::pow(r, 4) / 4.0;
    for (const bool normal : {false, true}) {
      const WindBasis basis = WindBasis::compute(skeleton, model, modes.vectors, make_settings(normal, 1));
      Eigen::MatrixX3d wind(1, 3);
      wind << v, 0.0, 0.0;
      const Eigen::VectorXd f = basis.modal_forces(wind);
      const Eigen::VectorXd u = modes.vectors * (f.array() / modes.omega.array().square()).matrix();

      double worst = 0.0, worst_other = 0.0;
      for (int node = 1; node <= tip; ++node) {
        const double z = L * node / kCantileverElements;
        const double deflection = q * z * z * (6.0 * L * L - 4.0 * L * z + z * z) / (24.0 * EI);
        const double slope = q * z * (3.0 * L * L - 3.0 * L * z + z * z) / (6.0 * EI);  // ry = +dux/dz
        worst = std::max(
            worst, std::abs(u(model.free_dof_of(node, 0)) - deflection) / (q * std::pow(L, 4) / (8.0 * EI)));
        worst = std::max(worst,
                         std::abs(u(model.free_dof_of(node, 4)) - slope) / (q * std::pow(L, 3) / (6.0 * EI)));
        for (const int other : {1, 2, 3, 5})
          worst_other = std::max(worst_other, std::abs(u(model.free_dof_of(node, other))));
      }
      const double tip_error =
          std::abs(u(model.free_dof_of(tip, 0)) / (q * std::pow(L, 4) / (8.0 * EI)) - 1.0);
      INFO("branch_normal_drag " << normal << ": tip deflection " << u(model.free_dof_of(tip, 0)) << " m vs "
                                 << q * std::pow(L, 4) / (8.0 * EI) << " m, rel error " << tip_error);
      INFO("max rel error of ux and ry at all nodes (to the tip values) " << worst);
      INFO("largest other DOF " << worst_other);
      CHECK(tip_error < 1e-8);
      CHECK(worst < 1e-8);
      CHECK(worst_other < 1e-8 * q * std::pow(L, 4) / (8.0 * EI));
    }
  }

  SECTION("branch-normal drag: vertical elements give no z component") {
    const Modes modes = dense_modes(model);
    const WindBasis plain = WindBasis::compute(skeleton, model, modes.vectors, make_settings(false, 2));
    const WindBasis normal = WindBasis::compute(skeleton, model, modes.vectors, make_settings(true, 2));
    double plain_z = 0.0, normal_z = 0.0;
    for (int s = 0; s < 2; ++s) {
      plain_z = std::max(plain_z, plain.projection_matrix().row(3 * s + 2).cwiseAbs().maxCoeff());
      normal_z = std::max(normal_z, normal.projection_matrix().row(3 * s + 2).cwiseAbs().maxCoeff());
    }
    const double scale = normal.projection_matrix().cwiseAbs().maxCoeff();
    INFO("max |p_z| plain " << plain_z << ", branch-normal " << normal_z << ", max |p| " << scale);
    CHECK(plain_z > 0.1 * scale);  // the axial modes do load the plain basis along z
    CHECK(normal_z < 1e-14 * scale);
  }
}

TEST_CASE("WindBasis modal forces", "[windbasis]") {
  const Skeleton skeleton = branched_tree();
  const BeamModel model(skeleton, kWood);
  const Modes modes = dense_modes(model, 10);

  const Foliage foliage = Foliage::of(skeleton, kLeafAreaIndex);
  REQUIRE(foliage.leaf_area > 0.0);
  for (const bool normal : {false, true}) {
    const int bands = 3;
    const WindBasis basis =
        WindBasis::compute(skeleton, model, modes.vectors, make_settings(normal, bands, kLeafAreaIndex));
    Eigen::MatrixX3d wind(bands, 3);
    wind << 4.0, -1.0, 0.3, 9.0, 2.5, -0.7, 14.0, 6.0, 1.1;

    // Direct evaluation: f_i = int 1/2 rho (C_Db D (P) + C_Df lambda) |v| v . phi_i ds with the wind of each
    // point's band.
    Eigen::VectorXd direct = Eigen::VectorXd::Zero(modes.vectors.cols());
    integrate_tree(skeleton, model, modes.vectors, bands, [&](const QuadraturePoint& q) {
      Eigen::Vector3d v = wind.row(q.band).transpose();
      Eigen::Vector3d load = kDrag * q.diameter * v.norm() * v;
      if (normal) load -= q.axis * q.axis.dot(load);
      load += 0.5 * WindBasisSettings::kAirDensity * WindBasisSettings::kFoliageDragCoefficient *
              foliage.leaf_area_per_metre[q.element] * v.norm() * v;
      direct += q.weight * q.phi.transpose() * load;
    });
    const Eigen::VectorXd f = basis.modal_forces(wind);
    const double error = relative_error(f, direct);
    INFO("branch_normal_drag " << normal << ": modal_forces vs direct quadrature, max rel error " << error);
    CHECK(error < 1e-10);

    // Uniform wind: S bands give the S = 1 forces.
    const WindBasis one =
        WindBasis::compute(skeleton, model, modes.vectors, make_settings(normal, 1, kLeafAreaIndex));
    Eigen::MatrixX3d uniform(bands, 3), single(1, 3);
    single << 8.0, -3.0, 0.5;
    uniform = single.replicate(bands, 1);
    const double uniform_error = relative_error(basis.modal_forces(uniform), one.modal_forces(single));
    INFO("uniform wind, 3 bands vs 1, max rel error " << uniform_error);
    CHECK(uniform_error < 1e-12);

    // No wind, no force.
    CHECK(basis.modal_forces(Eigen::MatrixX3d::Zero(bands, 3)).isZero(0.0));
  }
}

TEST_CASE("WindBasis load operator: nodal loads sum to the total drag, projections are shapes^T G",
          "[windbasis]") {
  const Skeleton skeleton = branched_tree();
  const BeamModel model(skeleton, kWood);
  const Modes modes = dense_modes(model, 5);
  const Foliage foliage = Foliage::of(skeleton, kLeafAreaIndex);
  for (const bool normal : {false, true}) {
    const int bands = 3;
    const WindBasisSettings settings = make_settings(normal, bands, kLeafAreaIndex);
    const Eigen::MatrixXd G = WindBasis::load_operator(skeleton, settings);
    REQUIRE(G.rows() == 6 * skeleton.size());
    REQUIRE(G.cols() == 3 * bands);
    const Eigen::Vector3d v(6.0, -2.0, 0.5);
    const Eigen::VectorXd F =
        G * WindBasis::squared_wind(Eigen::MatrixX3d(v.transpose().replicate(bands, 1)));
    Eigen::Vector3d total = Eigen::Vector3d::Zero();
    for (int node = 0; node < skeleton.size(); ++node) total += F.segment<3>(6 * node);
    // Closed form: sum_e A_e L_e |v| v, A_e = 1/2 rho (C_Db D_e P_e + C_Df lambda_e I).
    Eigen::Vector3d expected = Eigen::Vector3d::Zero();
    for (std::size_t e = 0; e < skeleton.elements().size(); ++e) {
      const auto [a, b] = skeleton.elements()[e];
      const Eigen::Vector3d d = skeleton.node(b).position - skeleton.node(a).position;
      const Eigen::Vector3d axis = d.normalized();
      Eigen::Vector3d wood = v.norm() * v;
      if (normal) wood -= axis * axis.dot(wood);
      expected +=
          0.5 * WindBasisSettings::kAirDensity * d.norm() *
          (WindBasisSettings::kCylinderDragCoefficient * (skeleton.node(a).radius + skeleton.node(b).radius) *
               wood +
           WindBasisSettings::kFoliageDragCoefficient * foliage.leaf_area_per_metre[e] * v.norm() * v);
    }
    INFO("branch_normal_drag " << normal);
    CHECK((total - expected).norm() < 1e-12 * expected.norm());
    // The projections are the free rows of G against the shapes.
    Eigen::MatrixXd free(model.dof_count(), 3 * bands);
    for (int node = 0; node < skeleton.size(); ++node)
      for (int j = 0; j < 6; ++j)
        if (model.free_dof_of(node, j) >= 0) free.row(model.free_dof_of(node, j)) = G.row(6 * node + j);
    const WindBasis basis = WindBasis::compute(skeleton, model, modes.vectors, settings);
    CHECK(relative_error(basis.projection_matrix(), free.transpose() * modes.vectors) < 1e-14);
  }
  CHECK_THROWS_WITH(
      WindBasis::load_operator(Skeleton::from_nodes({{-1, {0, 0, 0}, 0.1}}), WindBasisSettings{}),
      Catch::Matchers::Contains("WindBasis:"));
}

TEST_CASE("WindBasis scaled(s) matches the basis of the scaled skeleton", "[windbasis]") {
  const double s = 1.3;
  const int m = 8;
  const Skeleton small = branched_tree();
  const Skeleton big = small.transformed(Eigen::Matrix3d::Identity(), Eigen::Vector3d::Zero(), s);
  const BeamModel small_model(small, kWood);
  const BeamModel big_model(big, kWood);
  const Modes small_modes = dense_modes(small_model, m + 1);
  const Modes big_modes = dense_modes(big_model, m);

  // The comparison per mode needs simple eigenvalues.
  double gap = std::numeric_limits<double>::infinity();
  for (int i = 0; i < m; ++i) gap = std::min(gap, small_modes.omega(i + 1) / small_modes.omega(i) - 1.0);
  INFO("smallest relative gap between the lowest " << m + 1 << " frequencies " << gap);
  REQUIRE(gap > 1e-3);

  const double omega_error = relative_error(big_modes.omega, small_modes.omega.head(m) / s);
  INFO("frequencies omega_big vs omega / s, max rel error " << omega_error);
  CHECK(omega_error < 1e-9);

  for (const bool normal : {false, true}) {
    // Leaves too: lambda_e scales as s like D_e, so the similarity law holds with foliage.
    const WindBasisSettings settings = make_settings(normal, 3, kLeafAreaIndex);
    const WindBasis scaled =
        WindBasis::compute(small, small_model, small_modes.vectors.leftCols(m), settings).scaled(s);
    const WindBasis direct = WindBasis::compute(big, big_model, big_modes.vectors, settings);

    // Align each direct mode's sign with the scaled shape s^-5/2 D phi.
    Eigen::MatrixXd aligned = direct.projection_matrix();
    double shape_error = 0.0;
    for (int i = 0; i < m; ++i) {
      Eigen::VectorXd expected = small_modes.vectors.col(i) * std::pow(s, -2.5);
      for (Eigen::Index dof = 0; dof < expected.size(); ++dof) {
        if (dof % 6 < 3) expected(dof) *= s;
      }
      const double sign = big_modes.vectors.col(i).dot(expected) < 0.0 ? -1.0 : 1.0;
      aligned.col(i) *= sign;
      shape_error = std::max(shape_error, relative_error(sign * big_modes.vectors.col(i), expected));
    }
    const double p_error = relative_error(scaled.projection_matrix(), aligned);
    const double x_error = relative_error(scaled.sample_points(), direct.sample_points());
    INFO("branch_normal_drag " << normal);
    INFO("shapes s^-5/2 D phi vs the big tree modes, max rel error " << shape_error);
    INFO("scaled(s) projection vs compute on the scaled skeleton, max rel error " << p_error);
    INFO("sample points, max rel error " << x_error);
    CHECK(shape_error < 1e-7);
    CHECK(p_error < 1e-8);
    CHECK(x_error < 1e-12);
    CHECK(scaled.settings().samples == 3);
    CHECK(scaled.settings().branch_normal_drag == normal);
  }
}

TEST_CASE("WindBasis from_values round-trips and validates", "[windbasis]") {
  const Skeleton skeleton = branched_tree();
  const BeamModel model(skeleton, kWood);
  const Modes modes = dense_modes(model, 4);
  const WindBasis basis = WindBasis::compute(skeleton, model, modes.vectors, make_settings(true, 2));
  const WindBasis copy =
      WindBasis::from_values(basis.projection_matrix(), basis.sample_points(), basis.settings());
  CHECK(copy.projection_matrix() == basis.projection_matrix());
  CHECK(copy.sample_points() == basis.sample_points());
  CHECK(copy.settings().branch_normal_drag);
  CHECK(copy.projection(1, 3) == basis.projection_matrix().block<3, 1>(3, 3));
}

TEST_CASE("WindBasis rejects bad arguments", "[windbasis]") {
  const Skeleton skeleton = branched_tree();
  const BeamModel model(skeleton, kWood);
  const Modes modes = dense_modes(model, 3);
  const WindBasis basis = WindBasis::compute(skeleton, model, modes.vectors, make_settings(false, 2));

  using Catch::Matchers::Contains;
  WindBasisSettings bad = make_settings(false, 0);
  CHECK_THROWS_WITH(bad.validate(), Contains("WindBasisSettings:") && Contains("samples"));
  for (const char* field :
       {"air_density", "branch_drag_coefficient", "leaf_area_index", "leaf_drag_coefficient"}) {
    for (const double value :
         {-1.0, std::numeric_limits<double>::quiet_NaN(), std::numeric_limits<double>::infinity()}) {
      bad = make_settings(false, 1);
      const std::string name = field;
      double& target = name == "air_density"               ? bad.air_density
                       : name == "branch_drag_coefficient" ? bad.branch_drag_coefficient
                       : name == "leaf_area_index"         ? bad.leaf_area_index
                                                           : bad.leaf_drag_coefficient;
      target = value;
      INFO(field << " = " << value);
      CHECK_THROWS_WITH(bad.validate(), Contains("WindBasisSettings:") && Contains(field));
    }
  }
  CHECK_NOTHROW(make_settings(false, 1, kLeafAreaIndex).validate());
  bad = make_settings(false, 1);
  bad.air_density = -1.0;
  CHECK_THROWS_WITH(WindBasis::compute(skeleton, model, modes.vectors, bad), Contains("WindBasisSettings:"));

  // Shapes with the wrong number of rows, non-finite shapes, a model of another skeleton.
  CHECK_THROWS_WITH(WindBasis::compute(skeleton, model, modes.vectors.topRows(model.dof_count() - 6),
                                       make_settings(false, 1)),
                    Contains("WindBasis:") && Contains("rows"));
  Eigen::MatrixXd nan_shapes = modes.vectors;
  nan_shapes(5, 1) = std::numeric_limits<double>::quiet_NaN();
  CHECK_THROWS_WITH(WindBasis::compute(skeleton, model, nan_shapes, make_settings(false, 1)),
                    Contains("WindBasis:"));
  const Skeleton cantilever = vertical_cantilever();
  CHECK_THROWS_WITH(WindBasis::compute(cantilever, model, modes.vectors, make_settings(false, 1)),
                    Contains("WindBasis:"));

  // from_values with inconsistent sizes or values.
  CHECK_THROWS_WITH(
      WindBasis::from_values(basis.projection_matrix(), basis.sample_points(), make_settings(false, 3)),
      Contains("WindBasis:"));
  CHECK_THROWS_WITH(WindBasis::from_values(basis.projection_matrix().topRows(3), basis.sample_points(),
                                           make_settings(false, 2)),
                    Contains("WindBasis:"));
  Eigen::MatrixX3d nan_points = basis.sample_points();
  nan_points(0, 0) = std::numeric_limits<double>::infinity();
  CHECK_THROWS_WITH(WindBasis::from_values(basis.projection_matrix(), nan_points, make_settings(false, 2)),
                    Contains("WindBasis:"));
  CHECK_THROWS_WITH(
      WindBasis::from_values(basis.projection_matrix(), basis.sample_points(), make_settings(false, 0)),
      Contains("WindBasisSettings:"));

  // Wind with the wrong number of samples, bad scales, indices out of range.
  CHECK_THROWS_WITH(basis.modal_forces(Eigen::MatrixX3d::Zero(1, 3)), Contains("WindBasis:"));
  for (const double s :
       {0.0, -1.3, std::numeric_limits<double>::quiet_NaN(), std::numeric_limits<double>::infinity()}) {
    CHECK_THROWS_WITH(basis.scaled(s), Contains("WindBasis:") && Contains("scale"));
  }
  CHECK_THROWS_AS(basis.projection(2, 0), std::out_of_range);
  CHECK_THROWS_AS(basis.projection(0, 3), std::out_of_range);
  CHECK_THROWS_AS(basis.projection(-1, 0), std::out_of_range);
}
