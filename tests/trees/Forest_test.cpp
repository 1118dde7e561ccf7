// trees::Forest: validation of species and instances, flat offsets, and the packing for the device.
#include <catch2/catch.hpp>

#include <cmath>
#include <limits>
#include <string>

#include "tests/support/SmallSpecies.hpp"
#include "trees/Forest.hpp"

using namespace fw;

namespace {

trees::SpeciesBasis small_species(int modes, int samples) {
  trees::SpeciesSettings settings;
  settings.modal.mode_count = modes;
  settings.modal.damping = trees::Damping::modal_ratio(0.04);
  settings.wind.samples = samples;
  return trees::SpeciesBasis::compute(test::asymmetric_skeleton(), settings);
}

template <typename F>
std::string error_of(F&& make) {
  try {
    make();
  } catch (const std::invalid_argument& e) {
    return e.what();
  }
  return "(no exception)";
}

}  // namespace

TEST_CASE("Forest: flat offsets follow the instances' species", "[forest]") {
  std::vector<trees::SpeciesBasis> species = {small_species(6, 2), small_species(8, 3)};
  std::vector<trees::TreeInstance> trees = {
      {1, {1, 2, 0}, 0.3, 1.2}, {0, {5, 2, 0}, -1.0, 0.8}, {1, {9, 4, 1}, 2.0, 1.0}};
  const trees::Forest forest(species, trees);
  REQUIRE(forest.instance_count() == 3);
  CHECK(forest.mode_offset(0) == 0);
  CHECK(forest.mode_offset(1) == 8);
  CHECK(forest.mode_offset(2) == 14);
  CHECK(forest.total_modes() == 22);
  CHECK(forest.node_offset(2) == 22);
  CHECK(forest.total_nodes() == 33);
  CHECK(forest.sample_offset(1) == 3);
  CHECK(forest.sample_offset(2) == 5);
  CHECK(forest.total_samples() == 8);
}

TEST_CASE("Forest: pack lays out species and instances as kernels/shared_types.h documents", "[forest]") {
  std::vector<trees::SpeciesBasis> species = {small_species(6, 2), small_species(8, 3)};
  std::vector<trees::TreeInstance> trees = {{1, {1, 2, 0.5}, 0.3, 1.2}, {0, {5, 2, 0}, -1.0, 0.8}};
  const trees::Forest forest(species, trees);
  const trees::ForestPacking p = forest.pack();

  REQUIRE(p.species.size() == 2);
  REQUIRE(p.instances.size() == 2);
  CHECK(p.total_modes == 14);
  CHECK(p.total_nodes == 22);
  CHECK(p.total_samples == 5);
  CHECK(p.node_shapes.size() == std::size_t(33 * 6 + 33 * 8));
  CHECK(p.projections.size() == std::size_t(6 * 6 + 8 * 9));
  CHECK(p.sample_points.size() == std::size_t(3 * (2 + 3)));
  CHECK(p.omega.size() == 14);
  CHECK(p.damping_ratios.size() == 14);

  const FwSpecies& s1 = p.species[1];
  CHECK(s1.node_count == 11);
  CHECK(s1.mode_count == 8);
  CHECK(s1.sample_count == 3);
  CHECK(s1.shape_offset == 33 * 6);
  CHECK(s1.projection_offset == 6 * 6);
  CHECK(s1.sample_point_offset == 6);
  CHECK(s1.modal_offset == 6);

  const trees::SpeciesBasis& sp = species[1];
  // Node shapes and projections: mode-major.
  for (int r = 0; r < 33; ++r)
    for (int i = 0; i < 8; ++i)
      CHECK(p.node_shapes[std::size_t(s1.shape_offset + i * 33 + r)] == float(sp.node_shapes()(r, i)));
  for (int i = 0; i < 8; ++i)
    for (int r = 0; r < 9; ++r)
      CHECK(p.projections[std::size_t(s1.projection_offset + i * 9 + r)] ==
            float(sp.wind().projection_matrix()(r, i)));
  for (int s = 0; s < 3; ++s)
    for (int a = 0; a < 3; ++a)
      CHECK(p.sample_points[std::size_t(s1.sample_point_offset + 3 * s + a)] ==
            float(sp.wind().sample_points()(s, a)));
  for (int i = 0; i < 8; ++i) {
    CHECK(p.omega[std::size_t(6 + i)] == float(sp.modes().omega()(i)));
    CHECK(p.damping_ratios[std::size_t(6 + i)] == Approx(0.04).epsilon(1e-6));
  }

  const FwTreeInstance& t = p.instances[0];
  CHECK(t.species == 1);
  CHECK(t.mode_offset == 0);
  CHECK(t.node_offset == 0);
  CHECK(t.sample_offset == 0);
  CHECK(t.position[2] == 0.5f);
  CHECK(t.cos_yaw == float(std::cos(0.3)));
  CHECK(t.sin_yaw == float(std::sin(0.3)));
  CHECK(t.scale == 1.2f);
  CHECK(p.instances[1].mode_offset == 8);
  CHECK(p.instances[1].node_offset == 11);
  CHECK(p.instances[1].sample_offset == 3);

  REQUIRE(p.mode_instance.size() == 14);
  REQUIRE(p.node_instance.size() == 22);
  CHECK(p.mode_instance[7] == 0);
  CHECK(p.mode_instance[8] == 1);
  CHECK(p.node_instance[10] == 0);
  CHECK(p.node_instance[11] == 1);
}

TEST_CASE("Forest: rotation turns counter-clockwise about +z", "[forest]") {
  const trees::Forest forest({small_species(6, 1)}, {{0, {0, 0, 0}, M_PI / 2, 1.0}});
  const Eigen::Vector3d east(1, 0, 0);
  CHECK((forest.rotation(0) * east - Eigen::Vector3d(0, 1, 0)).norm() < 1e-15);
  CHECK(std::abs(forest.rotation(0).determinant() - 1.0) < 1e-15);
}

TEST_CASE("Forest: an empty forest has no flat entries", "[forest]") {
  const trees::Forest forest({small_species(6, 1)}, {});
  CHECK(forest.total_modes() == 0);
  CHECK(forest.total_nodes() == 0);
  const auto p = forest.pack();
  CHECK(p.instances.empty());
  CHECK(p.species.size() == 1);
  CHECK(trees::Forest().total_samples() == 0);
}

TEST_CASE("Forest: bad instances throw invalid_argument naming the class and the instance", "[forest]") {
  std::vector<trees::SpeciesBasis> species = {small_species(6, 1)};
  const double nan = std::numeric_limits<double>::quiet_NaN();
  const double inf = std::numeric_limits<double>::infinity();
  auto with = [&](trees::TreeInstance bad) {
    return error_of([&] { trees::Forest(species, {{0, {0, 0, 0}, 0.0, 1.0}, bad}); });
  };
  CHECK(with({1, {0, 0, 0}, 0.0, 1.0}) == "Forest: instance 1: species index must be 0..0, got 1");
  CHECK(with({-1, {0, 0, 0}, 0.0, 1.0}) == "Forest: instance 1: species index must be 0..0, got -1");
  CHECK(with({0, {0, 0, 0}, 0.0, 0.0}) == "Forest: instance 1: scale must be finite and > 0, got 0");
  CHECK(with({0, {0, 0, 0}, 0.0, -2.0}) == "Forest: instance 1: scale must be finite and > 0, got -2");
  CHECK(with({0, {0, 0, 0}, 0.0, inf}).find("scale must be finite") != std::string::npos);
  CHECK(with({0, {0, 0, 0}, 0.0, nan}).find("scale must be finite") != std::string::npos);
  CHECK(with({0, {0, nan, 0}, 0.0, 1.0}).find("Forest: instance 1: position must be finite") == 0);
  CHECK(with({0, {0, 0, 0}, inf, 1.0}).find("Forest: instance 1: yaw must be finite") == 0);
  CHECK(error_of([] { trees::Forest({}, {{0, {0, 0, 0}, 0.0, 1.0}}); }).find("Forest: instance 0") == 0);
}

TEST_CASE("Forest: a species with more wind samples than the kernels hold is rejected", "[forest]") {
  auto many = small_species(6, FW_MAX_TREE_SAMPLES + 1);
  CHECK(error_of([&] { trees::Forest({many}, {}); }) ==
        "Forest: species 0: wind samples must be 1..16, got 17");
}
