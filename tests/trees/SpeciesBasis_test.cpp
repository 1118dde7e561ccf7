#include "trees/SpeciesBasis.hpp"

#include <catch2/catch.hpp>

#include <Eigen/Geometry>

#include <cmath>
#include <stdexcept>
#include <vector>

#include "trees/BeamModel.hpp"

using fw::trees::BeamModel;
using fw::trees::ModalBasis;
using fw::trees::Skeleton;
using fw::trees::SkeletonNode;
using fw::trees::SpeciesBasis;
using fw::trees::SpeciesSettings;
using fw::trees::WindBasis;

namespace {

// A trunk with two inclined branches and a horizontal one, 25 nodes.
Skeleton small_tree() {
  std::vector<SkeletonNode> nodes{{-1, {0.0, 0.0, 0.0}, 0.12}};
  auto chain = [&](int from, const Eigen::Vector3d& step, int count, double radius) {
    int parent = from;
    for (int k = 1; k <= count; ++k) {
      nodes.push_back({parent, nodes[std::size_t(from)].position + step * k, radius * (1.0 - 0.08 * k)});
      parent = int(nodes.size()) - 1;
    }
    return parent;
  };
  const int top = chain(0, {0.02, 0.01, 0.6}, 10, 0.11);
  chain(4, {0.35, 0.1, 0.25}, 5, 0.05);
  chain(7, {-0.2, 0.3, 0.2}, 5, 0.04);
  chain(top - 2, {0.0, -0.4, 0.0}, 4, 0.03);
  return Skeleton::from_nodes(std::move(nodes));
}

SpeciesSettings settings_with(int modes, int samples) {
  SpeciesSettings settings;
  settings.modal.mode_count = modes;
  settings.wind.samples = samples;
  return settings;
}

}  // namespace

TEST_CASE("SpeciesBasis: parts agree with computing each one directly") {
  const Skeleton tree = small_tree();
  const SpeciesSettings settings = settings_with(8, 2);
  const SpeciesBasis species = SpeciesBasis::compute(tree, settings);
  const BeamModel model(tree, settings.material);
  const ModalBasis modes = ModalBasis::compute(model, settings.modal);
  const WindBasis wind = WindBasis::compute(tree, model, modes.shapes(), settings.wind);
  CHECK(species.modes().omega() == modes.omega());
  CHECK(species.modes().shapes() == modes.shapes());
  CHECK(species.wind().projection_matrix() == wind.projection_matrix());
  CHECK(species.timings().modes > 0.0);

  // node_shapes rows are the nodal translations of every mode.
  REQUIRE(species.node_shapes().rows() == 3 * tree.size());
  REQUIRE(species.node_shapes().cols() == 8);
  for (int mode = 0; mode < 8; ++mode) {
    const Eigen::MatrixX3d u = modes.node_displacements(model, mode);
    for (int node = 0; node < tree.size(); ++node) {
      for (int axis = 0; axis < 3; ++axis)
        CHECK(species.node_shapes()(3 * node + axis, mode) == u(node, axis));
    }
  }
}

TEST_CASE("SpeciesBasis: a scaled species matches the species computed from the scaled skeleton") {
  const Skeleton tree = small_tree();
  const SpeciesSettings settings = settings_with(6, 3);
  const SpeciesBasis base = SpeciesBasis::compute(tree, settings);
  const double s = 1.25;
  const SpeciesBasis scaled = base.scaled(s);
  const SpeciesBasis recomputed = SpeciesBasis::compute(
      tree.transformed(Eigen::Matrix3d::Identity(), Eigen::Vector3d::Zero(), s), settings);
  for (int i = 0; i < 6; ++i) {
    // Tolerance: 1e-9 relative (two Lanczos solves).
    CHECK(scaled.modes().omega()(i) == Approx(recomputed.modes().omega()(i)).epsilon(1e-9));
    // Mode and projection carry the same sign, so align the whole mode by its shape.
    const double sign =
        scaled.modes().shapes().col(i).dot(recomputed.modes().shapes().col(i)) < 0.0 ? -1.0 : 1.0;
    const Eigen::VectorXd p_scaled = sign * scaled.wind().projection_matrix().col(i);
    const Eigen::VectorXd p_fresh = recomputed.wind().projection_matrix().col(i);
    // Tolerance: 1e-6 of the largest component (eigenvector precision).
    CHECK((p_scaled - p_fresh).cwiseAbs().maxCoeff() < 1e-6 * p_fresh.cwiseAbs().maxCoeff());
    const Eigen::VectorXd u_scaled = sign * scaled.node_shapes().col(i);
    const Eigen::VectorXd u_fresh = recomputed.node_shapes().col(i);
    CHECK((u_scaled - u_fresh).cwiseAbs().maxCoeff() < 1e-6 * u_fresh.cwiseAbs().maxCoeff());
  }
  // Sample points scale about the origin; tolerance 1e-12 m.
  CHECK((scaled.wind().sample_points() - recomputed.wind().sample_points()).cwiseAbs().maxCoeff() < 1e-12);
  CHECK(scaled.skeleton().height() == Approx(s * tree.height()).epsilon(1e-12));
}

TEST_CASE("SpeciesBasis: another leaf area index keeps the modes and gives the wind basis of that foliage") {
  const Skeleton tree = small_tree();
  SpeciesSettings settings = settings_with(6, 2);
  settings.wind.leaf_area_index = 2.0;
  const SpeciesBasis base = SpeciesBasis::compute(tree, settings);
  const SpeciesBasis leafier = base.with_leaf_area_index(5.0);
  CHECK(leafier.settings().wind.leaf_area_index == 5.0);
  CHECK(base.settings().wind.leaf_area_index == 2.0);
  // Foliage adds drag, neither mass nor stiffness: the very same modes and strong-wind correction.
  CHECK(leafier.modes().omega() == base.modes().omega());
  CHECK(leafier.modes().shapes() == base.modes().shapes());
  CHECK(leafier.node_shapes() == base.node_shapes());
  CHECK(leafier.strong_wind().mode_count() == base.strong_wind().mode_count());
  // The wind basis is the one WindBasis computes with the new foliage on the same modes, bit for bit.
  settings.wind.leaf_area_index = 5.0;
  const BeamModel model(tree, settings.material);
  const WindBasis wind = WindBasis::compute(tree, model, base.modes().shapes(), settings.wind);
  CHECK(leafier.wind().projection_matrix() == wind.projection_matrix());
  CHECK(leafier.wind().sample_points() == wind.sample_points());  // drag-weighted: they move with the foliage
  CHECK_FALSE(leafier.wind().projection_matrix() == base.wind().projection_matrix());
  CHECK_THROWS_AS(base.with_leaf_area_index(-1.0), std::invalid_argument);
}

TEST_CASE("SpeciesBasis: parts that do not fit together are rejected") {
  const Skeleton tree = small_tree();
  const SpeciesBasis species = SpeciesBasis::compute(tree, settings_with(5, 1));
  const Skeleton other = Skeleton::from_nodes({{-1, {0.0, 0.0, 0.0}, 0.1}, {0, {0.0, 0.0, 1.0}, 0.1}});
  CHECK_THROWS_WITH(SpeciesBasis::from_parts(other, species.settings(), species.modes(), species.wind()),
                    Catch::Contains("SpeciesBasis: the modes have"));
  CHECK_THROWS_WITH(SpeciesBasis::from_parts(tree, settings_with(5, 2), species.modes(), species.wind()),
                    Catch::Contains("SpeciesBasis: the wind basis has 1 samples"));
}
