// trees/StemLoads: the stem's section moments are the statics of a cantilever, the modal maps give the FEM's
// static moments in a steady wind, and a leaning pole's weight gives its analytic moment.
#include "trees/StemLoads.hpp"

#include <catch2/catch.hpp>

#include <algorithm>
#include <cmath>
#include <numbers>
#include <vector>

#include "tests/support/SmallSpecies.hpp"
#include "trees/StaticDeflection.hpp"
#include "trees/TreeGenerator.hpp"
#include "trees/WindBasis.hpp"

namespace {

using fw::trees::BeamModel;
using fw::trees::Material;
using fw::trees::Skeleton;
using fw::trees::SkeletonNode;
using fw::trees::StemLoads;

const Material kWood{1.0e10, 3.85e9, 900.0};

// A vertical pole of `elements` equal elements, length L, radius r, its root at the origin.
Skeleton pole(int elements, double length, double radius) {
  std::vector<SkeletonNode> nodes;
  for (int i = 0; i <= elements; ++i)
    nodes.push_back({i - 1, Eigen::Vector3d(0.0, 0.0, length * i / elements), radius});
  return Skeleton::from_nodes(std::move(nodes));
}

// The node-major translational rows (3 n) of a free-DOF vector or of a 6 n node-major load.
Eigen::VectorXd translational_rows(const Eigen::VectorXd& loads, int nodes) {
  Eigen::VectorXd out(3 * nodes);
  for (int k = 0; k < nodes; ++k) out.segment<3>(3 * k) = loads.segment<3>(6 * k);
  return out;
}

// The wood's wind load on every node, 6 n node-major (N, N m): the drag of trees/WindBasis in the wind v.
Eigen::VectorXd wind_loads(const Skeleton& skeleton, const fw::trees::WindBasisSettings& drag,
                           const Eigen::Vector3d& v) {
  const Eigen::MatrixXd G = fw::trees::WindBasis::load_operator(skeleton, drag);
  const Eigen::MatrixX3d bands = Eigen::MatrixX3d::Constant(G.cols() / 3, 3, 0.0).rowwise() + v.transpose();
  return G * fw::trees::WindBasis::squared_wind(bands);
}

}  // namespace

TEST_CASE("StemLoads: the stem follows the thickest child from the root to the top of the trunk", "[trees]") {
  const Skeleton tree = fw::test::asymmetric_skeleton();  // trunk 0-1-2-3-4-9; side branches thinner
  CHECK(fw::trees::stem_path(tree) == std::vector<int>{0, 1, 2, 3, 4, 9});
}

TEST_CASE(
    "StemLoads: a stem of more than 15 sections keeps 15, evenly along it, the root first and the top "
    "out",
    "[trees]") {
  using fw::trees::kMaxStemSections;
  using fw::trees::stem_section_indices;
  // Up to 15 sections (16 nodes), every node but the top.
  const Eigen::VectorXd short_stem = Eigen::VectorXd::LinSpaced(16, 0.0, 15.0);
  CHECK(stem_section_indices(short_stem) ==
        std::vector<int>{0, 1, 2, 3, 4, 5, 6, 7, 8, 9, 10, 11, 12, 13, 14});
  // 60 equal elements: every 4th node, exactly at k L / 15.
  const Eigen::VectorXd even = Eigen::VectorXd::LinSpaced(61, 0.0, 30.0);
  const std::vector<int> every_fourth = stem_section_indices(even);
  REQUIRE(int(every_fourth.size()) == kMaxStemSections);
  for (int k = 0; k < kMaxStemSections; ++k) CHECK(every_fourth[std::size_t(k)] == 4 * k);
  // Nodes crowded near the base (lengths growing as i^2): the nearest node to each target, repeats once, and
  // never the top, even when a target lies nearest to it.
  Eigen::VectorXd crowded(40);
  for (int i = 0; i < 40; ++i) crowded(i) = double(i) * i;
  const std::vector<int> picked = stem_section_indices(crowded);
  const double length = crowded(39);
  CHECK(picked.front() == 0);
  CHECK(picked.back() < 39);
  CHECK(std::is_sorted(picked.begin(), picked.end()));
  CHECK(std::adjacent_find(picked.begin(), picked.end()) == picked.end());
  for (int k = 1; k < kMaxStemSections; ++k) {
    const double target = length * k / kMaxStemSections;
    int nearest = 0;
    for (int i = 1; i < 40; ++i)
      if (std::abs(crowded(i) - target) < std::abs(crowded(nearest) - target)) nearest = i;
    INFO("target " << target);
    CHECK(std::find(picked.begin(), picked.end(), std::min(nearest, 38)) != picked.end());
  }
  CHECK_THROWS_AS(stem_section_indices(Eigen::VectorXd::Zero(1)), std::invalid_argument);
}

TEST_CASE("StemLoads: along_stem carries the sections' values to every stem node, linear between them",
          "[trees]") {
  // A 40-element pole keeps 15 sections (every node nearest k 40 / 15 elements up): values 0, 1, 2, ...
  // at them are the distance along the pole in section spacings, the last's above the last section.
  constexpr double kLength = 10.0;
  const Skeleton stick = pole(40, kLength, 0.1);
  const fw::trees::BeamModel model(stick, kWood);
  fw::trees::ModalSettings modal;
  modal.mode_count = 2;
  const StemLoads stem = StemLoads::compute(stick, model, fw::trees::ModalBasis::compute(model, modal));
  REQUIRE(stem.section_count() == fw::trees::kMaxStemSections);
  std::vector<float> values;
  for (int j = 0; j < stem.section_count(); ++j) values.push_back(float(j));
  const std::vector<float> along = stem.along_stem(values);
  REQUIRE(along.size() == stem.profile().size());
  const std::vector<int>& at = stem.section_indices();
  for (std::size_t i = 0; i < along.size(); ++i) {
    INFO("stem node " << i);
    const auto above = std::upper_bound(at.begin(), at.end(), int(i));
    if (above == at.end()) {
      CHECK(along[i] == float(at.size() - 1));  // above the last section: its value
      continue;
    }
    const int j = int(above - at.begin()) - 1;  // the section at or below node i
    const double t =
        double(int(i) - at[std::size_t(j)]) / double(*above - at[std::size_t(j)]);  // equal elements
    CHECK(along[i] == Approx(j + t).margin(1e-6));
  }
  CHECK_THROWS_AS(stem.along_stem(std::vector<float>{1.0f}), std::invalid_argument);
}

TEST_CASE("StemLoads: a uniformly loaded cantilever gives M = w (L - x)^2 / 2 at every section", "[trees]") {
  constexpr double kLength = 10.0, kRadius = 0.15, kSpeed = 20.0;
  const Skeleton stick = pole(16, kLength, kRadius);
  fw::trees::WindBasisSettings drag;
  drag.leaf_area_index = 0.0;
  // w = 1/2 rho C_D D v^2 per metre, D = 2 r (trees/WindBasis.hpp's wood drag).
  const double w = 0.5 * drag.air_density * drag.branch_drag_coefficient * 2.0 * kRadius * kSpeed * kSpeed;
  const Eigen::VectorXd F = translational_rows(wind_loads(stick, drag, {kSpeed, 0.0, 0.0}), stick.size());
  const std::vector<int> path = fw::trees::stem_path(stick);
  const std::vector<int> sections(path.begin(), path.end() - 1);
  const Eigen::MatrixXd M = fw::trees::section_moments_of_forces(stick, sections, F);
  for (std::size_t j = 0; j < sections.size(); ++j) {
    const double z = stick.node(sections[j]).position.z();
    const double expected = w * (kLength - z) * (kLength - z) / 2.0;
    INFO("section at z = " << z);
    // The wind along +x bends the pole about +y: M_y = sum (z_k - z) F_x. The consistent loads of a uniform
    // load are w L_e / 2 at each end of an element, whose lever arms the trapezoid rule sums exactly: only
    // rounding remains (1e-12 of the root's moment).
    CHECK(M(3 * j + 1) == Approx(expected).margin(1e-12 * w * kLength * kLength));
    CHECK(std::abs(M(3 * j)) < 1e-12 * w * kLength * kLength);
  }
}

TEST_CASE("StemLoads: a leaning pole's weight gives mu g theta (L - z)^2 / 2 at every section", "[trees]") {
  constexpr double kLength = 8.0, kRadius = 0.1, kLean = 0.05;  // rad
  const Skeleton stick = pole(12, kLength, kRadius);
  const double mu = kWood.density * std::numbers::pi * kRadius * kRadius;  // kg/m
  const Eigen::VectorXd masses = fw::trees::lumped_node_masses(stick, kWood.density);
  CHECK(masses.sum() == Approx(mu * kLength).epsilon(1e-12));
  // A rigid lean by theta about the root, toward +x: u_x = theta z.
  Eigen::VectorXd u = Eigen::VectorXd::Zero(3 * stick.size());
  for (int k = 0; k < stick.size(); ++k) u(3 * k) = kLean * stick.node(k).position.z();
  const std::vector<int> path = fw::trees::stem_path(stick);
  const std::vector<int> sections(path.begin(), path.end() - 1);
  const Eigen::MatrixXd M = fw::trees::section_moments_of_weight(stick, sections, masses, u);
  for (std::size_t j = 0; j < sections.size(); ++j) {
    const double z = stick.node(sections[j]).position.z();
    // The weight leaning toward +x turns the pole about -y (right-hand rule: r x (0, 0, -mg) with r along
    // +x is +y... r x F = (r_y F_z - 0, 0 - r_x F_z, 0) = (0, m g r_x, 0)): +y, as the wind along +x.
    const double expected = mu * fw::trees::kGravity * kLean * (kLength - z) * (kLength - z) / 2.0;
    INFO("section at z = " << z);
    // Lumped masses: the trapezoid rule of a linear lever arm, exact to rounding.
    CHECK(M(3 * j + 1) == Approx(expected).margin(1e-12 * mu * kLength * kLength));
    CHECK(M(3 * j) == Approx(0.0).margin(1e-12 * mu * kLength * kLength));
  }
}

TEST_CASE("StemLoads: the modal section moments in a steady wind match the FEM's static solution",
          "[trees]") {
  // A generated conifer (a few hundred nodes) with 24 modes; a steady 15 m/s wind. The reference is the
  // statics of the full FEM's elastic forces K u (StaticDeflection: every DOF, no truncation). The modal
  // static state q_i = f_i / omega_i^2 (the run's equilibrium) gives K Phi q = M Phi Phi^T F, the load's
  // mass-weighted projection on the kept modes, whose moments differ from the load's by what the higher
  // modes carry.
  fw::trees::GeneratorSettings g;
  g.preset = "conifer";
  g.height = 12.0;
  g.seed = 3;
  g.iterations = 4;
  g.max_element_length = 0.6;
  const Skeleton tree = fw::trees::generate_tree(g);
  fw::trees::SpeciesSettings settings;
  settings.material = kWood;
  settings.modal.mode_count = 24;
  settings.wind.samples = 1;
  settings.wind.leaf_area_index = 0.0;
  const BeamModel model(tree, kWood);
  const auto modes = fw::trees::ModalBasis::compute(model, settings.modal);
  const StemLoads stem = StemLoads::compute(tree, model, modes, /*gravity=*/0.0);

  const Eigen::Vector3d wind(15.0, 4.0, 0.0);
  const Eigen::VectorXd loads = wind_loads(tree, settings.wind, wind);
  Eigen::VectorXd free_loads = Eigen::VectorXd::Zero(model.dof_count());
  for (int node = 0; node < tree.size(); ++node)
    for (int local = 0; local < 6; ++local)
      if (const int dof = model.free_dof_of(node, local); dof >= 0) free_loads(dof) = loads(6 * node + local);
  const Eigen::VectorXd q =
      (modes.shapes().transpose() * free_loads).cwiseQuotient(modes.omega().cwiseAbs2());

  // The FEM: StaticDeflection solves K u = F on every DOF, so its elastic forces K u are the load F itself
  // and its section moments are the statics of F's translational rows. The modal state is the same bend:
  // the top of the stem moves as the FEM's within 2% (measured 0.02%).
  const Eigen::MatrixX3d u = fw::trees::static_deflection(tree, model, settings.wind, wind);
  const int top = stem.profile().back().node;
  Eigen::Vector3d modal_top = Eigen::Vector3d::Zero();
  for (int axis = 0; axis < 3; ++axis)
    modal_top(axis) = modes.shapes().row(model.free_dof_of(top, axis)).dot(q);
  CHECK((modal_top - u.row(top).transpose()).norm() < 0.02 * u.row(top).norm());
  const Eigen::VectorXd F = translational_rows(loads, tree.size());
  const std::vector<fw::trees::StemSection> sections = stem.sections();
  std::vector<int> nodes;
  for (const auto& s : sections) nodes.push_back(s.node);
  const Eigen::MatrixXd reference = fw::trees::section_moments_of_forces(tree, nodes, F);
  const Eigen::VectorXd modal = stem.bending_moments(q);

  // The base moment: the low modes carry almost all of a smooth load's moment (measured 0.8% short with 24
  // modes); 2% leaves room for rounding of another solver's modes. Higher up the moments are smaller and
  // the truncation's error is absolute: within 2% of the base moment at every section (measured 0.8%, at
  // the base).
  const double base = reference.col(0).segment<3>(0).norm();
  const Eigen::Vector3d axis0 =
      (tree.node(stem.profile()[1].node).position - tree.node(stem.profile()[0].node).position).normalized();
  const Eigen::Vector3d m0 = reference.col(0).segment<3>(0);
  const double base_bending = (m0 - m0.dot(axis0) * axis0).norm();
  CHECK(modal(0) == Approx(base_bending).epsilon(0.02));
  double worst = 0.0;
  for (std::size_t j = 0; j < sections.size(); ++j) {
    const Eigen::Vector3d t =
        (tree.node(stem.profile()[j + 1].node).position - tree.node(stem.profile()[j].node).position)
            .normalized();
    const Eigen::Vector3d mj = reference.col(0).segment<3>(3 * Eigen::Index(j));
    worst = std::max(worst, std::abs(modal(Eigen::Index(j)) - (mj - mj.dot(t) * t).norm()) / base);
  }
  CHECK(worst < 0.02);
  // The root's turning moment is the horizontal part of the base moment.
  CHECK(stem.root_moment(q) == Approx(std::hypot(m0.x(), m0.y())).epsilon(0.02));
}

TEST_CASE("StemLoads: scaled(s) gives the moments of the tree grown by s for its own modal state",
          "[trees]") {
  const Skeleton tree = fw::test::asymmetric_skeleton();
  const BeamModel model(tree, kWood);
  fw::trees::ModalSettings settings;
  settings.mode_count = 6;
  const auto modes = fw::trees::ModalBasis::compute(model, settings);
  const StemLoads stem = StemLoads::compute(tree, model, modes);

  constexpr double s = 1.7;
  const Skeleton grown = tree.transformed(Eigen::Matrix3d::Identity(), Eigen::Vector3d::Zero(), s);
  const BeamModel grown_model(grown, kWood);
  const auto grown_modes = modes.scaled(s);  // the same mode signs as the source
  const StemLoads direct = StemLoads::compute(grown, grown_model, grown_modes);
  const StemLoads similar = stem.scaled(s);
  Eigen::VectorXd q(6);
  q << 0.3, -0.2, 0.1, 0.05, -0.02, 0.01;
  // Similarity is exact algebra; only rounding of the two assemblies differs.
  CHECK((similar.bending_moments(q) - direct.bending_moments(q)).norm() <
        1e-9 * direct.bending_moments(q).norm());
  CHECK(similar.root_moment(q) == Approx(direct.root_moment(q)).epsilon(1e-9));
  CHECK(similar.stem_volume() == Approx(s * s * s * stem.stem_volume()).epsilon(1e-12));
  CHECK(similar.breast_height_diameter() == Approx(direct.breast_height_diameter()).epsilon(1e-12));
}

TEST_CASE("StemLoads: the stem's volume and diameter at breast height are a pole's", "[trees]") {
  const Skeleton stick = pole(10, 5.0, 0.2);
  const BeamModel model(stick, kWood);
  fw::trees::ModalSettings settings;
  settings.mode_count = 4;
  const StemLoads stem = StemLoads::compute(stick, model, fw::trees::ModalBasis::compute(model, settings));
  CHECK(stem.section_count() == 10);
  CHECK(stem.height() == Approx(5.0));
  CHECK(stem.stem_volume() == Approx(std::numbers::pi * 0.04 * 5.0).epsilon(1e-12));
  CHECK(stem.breast_height_diameter() == Approx(0.4).epsilon(1e-12));
}
