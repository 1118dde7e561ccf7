#include "trees/Skeleton.hpp"

#include <catch2/catch.hpp>

#include <Eigen/Geometry>

#include <cmath>
#include <limits>
#include <stdexcept>
#include <string>
#include <vector>

using fw::trees::Skeleton;
using fw::trees::SkeletonError;
using fw::trees::SkeletonNode;

namespace {

// A small Y-shaped tree: a trunk 0-1-2 and two branches from node 2, listed with children before parents.
std::vector<SkeletonNode> y_tree() {
  return {
      {3, {1.0, 0.0, 4.0}, 0.05},   // 0: left tip, parent 3
      {-1, {0.0, 0.0, 0.0}, 0.30},  // 1: root
      {1, {0.0, 0.0, 2.0}, 0.20},   // 2: trunk
      {2, {0.0, 0.0, 3.0}, 0.10},   // 3: fork
      {3, {-1.0, 0.5, 3.5}, 0.05},  // 4: right tip
  };
}

// The SkeletonError that from_nodes throws; fails the test when it does not throw.
SkeletonError error_of(std::vector<SkeletonNode> nodes) {
  try {
    Skeleton::from_nodes(std::move(nodes));
  } catch (const SkeletonError& error) {
    return error;
  }
  FAIL("from_nodes did not throw");
  return SkeletonError(-1, SkeletonError::Field::nodes, "", "");
}

double element_length(const Skeleton& skeleton, std::pair<int, int> element) {
  return (skeleton.node(element.second).position - skeleton.node(element.first).position).norm();
}

}  // namespace

TEST_CASE("Skeleton: topology accessors", "[trees][skeleton]") {
  const auto skeleton = Skeleton::from_nodes(y_tree());
  REQUIRE(skeleton.size() == 5);
  CHECK(skeleton.root() == 1);
  CHECK(skeleton.node(3).parent == 2);
  CHECK(skeleton.node(4).radius == 0.05);

  const auto fork_children = skeleton.children(3);
  REQUIRE(fork_children.size() == 2);
  CHECK(fork_children[0] == 0);
  CHECK(fork_children[1] == 4);
  CHECK(skeleton.children(0).empty());
  CHECK(skeleton.children(1).size() == 1);
  CHECK_THROWS_AS(skeleton.children(5), std::out_of_range);

  CHECK(skeleton.topological_order() == std::vector<int>{1, 2, 3, 0, 4});
  const auto& elements = skeleton.elements();
  REQUIRE(elements.size() == 4);
  CHECK(elements == std::vector<std::pair<int, int>>{{1, 2}, {2, 3}, {3, 0}, {3, 4}});
  for (std::size_t k = 0; k < elements.size(); ++k)
    CHECK(elements[k].second == skeleton.topological_order()[k + 1]);
}

TEST_CASE("Skeleton: elements list parents before children", "[trees][skeleton]") {
  // A chain listed backwards plus a side branch: every element's parent node is the root or was reached.
  std::vector<SkeletonNode> nodes;
  const int n = 30;
  for (int i = 0; i < n; ++i) nodes.push_back({i == n - 1 ? -1 : i + 1, {0.0, 0.0, double(n - 1 - i)}, 0.1});
  nodes.push_back({10, {1.0, 0.0, 19.0}, 0.05});
  const auto skeleton = Skeleton::from_nodes(nodes);
  std::vector<char> reached(std::size_t(skeleton.size()), 0);
  reached[std::size_t(skeleton.root())] = 1;
  for (auto [parent, child] : skeleton.elements()) {
    CHECK(reached[std::size_t(parent)]);
    CHECK(skeleton.node(child).parent == parent);
    reached[std::size_t(child)] = 1;
  }
  CHECK(skeleton.elements().size() == std::size_t(n));
}

TEST_CASE("Skeleton: height and bounding box", "[trees][skeleton]") {
  auto nodes = y_tree();
  for (auto& node : nodes) node.position.z() += 100.0;  // the root stands at z = 100
  const auto skeleton = Skeleton::from_nodes(nodes);
  CHECK(skeleton.height() == Approx(4.0));
  const auto box = skeleton.bounding_box();
  CHECK(box.min().isApprox(Eigen::Vector3d(-1.0, 0.0, 100.0)));
  CHECK(box.max().isApprox(Eigen::Vector3d(1.0, 0.5, 104.0)));
}

TEST_CASE("Skeleton: a single root node is a valid skeleton without elements", "[trees][skeleton]") {
  const auto skeleton = Skeleton::from_nodes({{-1, {1.0, 2.0, 3.0}, 0.1}});
  CHECK(skeleton.size() == 1);
  CHECK(skeleton.elements().empty());
  CHECK(skeleton.height() == 0.0);
}

TEST_CASE("Skeleton: transformed scales lengths and radii", "[trees][skeleton]") {
  const auto skeleton = Skeleton::from_nodes(y_tree());
  const double scale = 2.5;
  const Eigen::Vector3d shift(10.0, -4.0, 1.0);
  const auto big = skeleton.transformed(Eigen::Matrix3d::Identity(), shift, scale);
  REQUIRE(big.size() == skeleton.size());
  CHECK(big.elements() == skeleton.elements());
  for (int i = 0; i < skeleton.size(); ++i) {
    CHECK(big.node(i).radius == Approx(scale * skeleton.node(i).radius));
    CHECK(big.node(i).position.isApprox(shift + scale * skeleton.node(i).position));
  }
  for (const auto& element : skeleton.elements())
    CHECK(element_length(big, element) == Approx(scale * element_length(skeleton, element)));
  CHECK(big.height() == Approx(scale * skeleton.height()));
}

TEST_CASE("Skeleton: rotation keeps lengths and radii", "[trees][skeleton]") {
  const auto skeleton = Skeleton::from_nodes(y_tree());
  const Eigen::Matrix3d rotation =
      Eigen::AngleAxisd(0.7, Eigen::Vector3d(1.0, 2.0, -0.5).normalized()).toRotationMatrix();
  const auto turned = skeleton.transformed(rotation, Eigen::Vector3d(3.0, 4.0, 5.0), 1.0);
  for (const auto& element : skeleton.elements())
    CHECK(element_length(turned, element) == Approx(element_length(skeleton, element)).epsilon(1e-12));
  for (int i = 0; i < skeleton.size(); ++i) CHECK(turned.node(i).radius == skeleton.node(i).radius);
  // The root moves to the translation (it is at the origin).
  CHECK((turned.node(turned.root()).position - Eigen::Vector3d(3.0, 4.0, 5.0)).norm() < 1e-12);
}

TEST_CASE("Skeleton: transformed rejects a bad scale or a non-rotation", "[trees][skeleton]") {
  const auto skeleton = Skeleton::from_nodes(y_tree());
  const Eigen::Vector3d zero = Eigen::Vector3d::Zero();
  CHECK_THROWS_AS(skeleton.transformed(Eigen::Matrix3d::Identity(), zero, 0.0), std::invalid_argument);
  CHECK_THROWS_AS(skeleton.transformed(Eigen::Matrix3d::Identity(), zero, -1.0), std::invalid_argument);
  CHECK_THROWS_AS(skeleton.transformed(Eigen::Matrix3d::Identity(), zero, std::nan("")),
                  std::invalid_argument);
  CHECK_THROWS_AS(skeleton.transformed(2.0 * Eigen::Matrix3d::Identity(), zero, 1.0), std::invalid_argument);
  Eigen::Matrix3d mirror = Eigen::Matrix3d::Identity();
  mirror(0, 0) = -1.0;
  CHECK_THROWS_AS(skeleton.transformed(mirror, zero, 1.0), std::invalid_argument);
}

TEST_CASE("Skeleton: validation names the offending node", "[trees][skeleton]") {
  using Field = SkeletonError::Field;

  SECTION("empty") {
    const auto error = error_of({});
    CHECK(error.node() == -1);
    CHECK(std::string(error.what()).find("at least one node") != std::string::npos);
  }
  SECTION("parent out of range") {
    auto nodes = y_tree();
    nodes[4].parent = 5;
    const auto error = error_of(nodes);
    CHECK(error.node() == 4);
    CHECK(error.field() == Field::parent);
    CHECK(std::string(error.what()) ==
          "Skeleton: node 4: parent: expected -1 (root) or an existing node in 0..4, got 5");
    nodes[4].parent = -3;
    CHECK(error_of(nodes).node() == 4);
  }
  SECTION("self-parent") {
    auto nodes = y_tree();
    nodes[2].parent = 2;
    const auto error = error_of(nodes);
    CHECK(error.node() == 2);
    CHECK(error.field() == Field::parent);
  }
  SECTION("two roots") {
    auto nodes = y_tree();
    nodes[3].parent = -1;
    const auto error = error_of(nodes);
    CHECK(error.node() == 3);
    CHECK(error.field() == Field::parent);
    CHECK(std::string(error.what()).find("node 1 is already the root") != std::string::npos);
  }
  SECTION("no root") {
    auto nodes = y_tree();
    nodes[1].parent = 3;  // root -> fork: cycle 1 -> 3 -> 2 -> 1
    const auto error = error_of(nodes);
    CHECK(error.node() == 1);
    CHECK(error.field() == Field::parent);
    CHECK(std::string(error.what()).find("found none") != std::string::npos);
    CHECK(std::string(error.what()).find("1 -> 3 -> 2 -> 1") != std::string::npos);
  }
  SECTION("cycle beside the root") {
    std::vector<SkeletonNode> nodes = {{-1, {0, 0, 0}, 0.1}, {0, {0, 0, 1}, 0.1},
                                       {4, {0, 1, 1}, 0.1},  // 2 -> 4 -> 3 -> 2, with tip 5 hanging off it
                                       {2, {0, 2, 1}, 0.1},  {3, {0, 3, 1}, 0.1},
                                       {3, {0, 4, 1}, 0.1}};
    const auto error = error_of(nodes);
    CHECK(error.node() == 2);
    CHECK(error.field() == Field::parent);
    CHECK(error.got() == "4");
    CHECK(std::string(error.what()).find("2 -> 4 -> 3 -> 2") != std::string::npos);
  }
  SECTION("zero-length element") {
    auto nodes = y_tree();
    nodes[4].position = nodes[3].position + Eigen::Vector3d(0.0, 0.0, 5e-10);
    const auto error = error_of(nodes);
    CHECK(error.node() == 4);
    CHECK(error.field() == Field::position);
    CHECK(std::string(error.what()).find("zero-length") != std::string::npos);
    nodes[4].position = nodes[3].position + Eigen::Vector3d(0.0, 0.0, 2e-9);  // short but not zero
    CHECK_NOTHROW(Skeleton::from_nodes(nodes));
  }
  SECTION("radius") {
    auto nodes = y_tree();
    nodes[0].radius = 0.0;
    CHECK(error_of(nodes).field() == Field::radius);
    nodes[0].radius = -0.1;
    CHECK(error_of(nodes).node() == 0);
    nodes[0].radius = std::numeric_limits<double>::infinity();
    CHECK(error_of(nodes).field() == Field::radius);
  }
  SECTION("non-finite position") {
    auto nodes = y_tree();
    nodes[3].position.y() = std::nan("");
    const auto error = error_of(nodes);
    CHECK(error.node() == 3);
    CHECK(error.field() == Field::position);
  }
  SECTION("is a std::invalid_argument") {
    auto nodes = y_tree();
    nodes[0].parent = 0;
    CHECK_THROWS_AS(Skeleton::from_nodes(nodes), std::invalid_argument);
  }
}
