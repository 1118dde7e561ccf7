// A tree skeleton: a rooted tree of nodes, each with a position and a radius. An element joins a node to its
// parent; it is what the FEM beam model turns into one 3D frame element.
//
//   std::vector<fw::trees::SkeletonNode> nodes = {
//       {-1, {0.0, 0.0, 0.0}, 0.20},   // node 0: the root, at the base of the trunk
//       {0, {0.0, 0.0, 2.0}, 0.15},    // node 1: its parent is node 0
//       {1, {1.0, 0.0, 3.0}, 0.05}};   // node 2: a branch tip
//   auto skeleton = fw::trees::Skeleton::from_nodes(std::move(nodes));   // validates, throws on errors
//   for (auto [parent, child] : skeleton.elements()) { ... }              // parents before children
//   auto big = skeleton.transformed(Eigen::Matrix3d::Identity(), {10.0, 5.0, 0.0}, 1.2);
//
// Units: positions and radii in metres, in the world frame (x east, y north, z up).
// Indices: nodes are numbered 0..size()-1; parent is a node index, -1 for the root. Exactly one root.
//
// Validation (from_nodes) throws SkeletonError, a std::invalid_argument whose what() reads
// "Skeleton: node I: FIELD: what was expected, got VALUE". It carries the node index and the field so that
// readers of files (TreeFile, QsmImport) can translate it into "FILE:LINE: ..." without repeating the checks.
#pragma once

#include <Eigen/Core>
#include <Eigen/Geometry>

#include <span>
#include <stdexcept>
#include <string>
#include <utility>
#include <vector>

namespace fw::trees {

struct SkeletonNode {
  int parent = -1;                                     ///< parent node index, -1 for the root
  Eigen::Vector3d position = Eigen::Vector3d::Zero();  ///< m, world frame
  double radius = 0.0;                                 ///< m, > 0
};

/// A validation error of Skeleton::from_nodes that names the offending node and field.
class SkeletonError : public std::invalid_argument {
 public:
  enum class Field { nodes, parent, position, radius };

  /// node: the offending node index (-1 when the error concerns the whole list, e.g. an empty one).
  /// expected: "expected ..." text; got: the offending value as text.
  SkeletonError(int node, Field field, std::string expected, std::string got);

  int node() const { return node_; }
  Field field() const { return field_; }
  const std::string& expected() const { return expected_; }
  const std::string& got() const { return got_; }

  /// "parent", "position", "radius" or "nodes".
  static const char* field_name(Field field);

 private:
  int node_;
  Field field_;
  std::string expected_;
  std::string got_;
};

class Skeleton {
 public:
  /// Smallest distance between a node and its parent, m; closer is a zero-length element.
  static constexpr double kMinElementLength = 1e-9;

  /// Validates and builds a skeleton. Throws SkeletonError (a std::invalid_argument) naming the node index
  /// for: an empty list, a non-finite position, a radius <= 0 or non-finite, a parent outside -1..n-1, a
  /// node that is its own parent, no root or more than one root (parent -1), a cycle (a parent chain that
  /// never reaches the root), or a zero-length element (a node within kMinElementLength of its parent).
  static Skeleton from_nodes(std::vector<SkeletonNode> nodes);

  Skeleton() = default;  ///< empty; only useful as a placeholder to assign to

  /// Number of nodes n.
  int size() const { return int(nodes_.size()); }
  const SkeletonNode& node(int i) const { return nodes_.at(std::size_t(i)); }
  const std::vector<SkeletonNode>& nodes() const { return nodes_; }
  /// Index of the root node (its parent is -1).
  int root() const { return root_; }
  /// Children of node i, in increasing index order (precomputed).
  std::span<const int> children(int i) const;

  /// The n-1 elements as (parent, child) node index pairs, breadth-first from the root, so that every
  /// element's parent node appears as a child of an earlier element (or is the root). Element k ends at
  /// node topological_order()[k + 1].
  const std::vector<std::pair<int, int>>& elements() const { return elements_; }
  /// All n node indices, breadth-first from the root: the root first, every parent before its children.
  const std::vector<int>& topological_order() const { return order_; }

  /// Largest node z minus the root's z, m (>= 0 when no node lies below the root).
  double height() const;
  /// Axis-aligned box of the node positions (radii not included), m.
  Eigen::AlignedBox3d bounding_box() const;

  /// A copy with every position p mapped to translation + scale * rotation * p and every radius r to
  /// scale * r; the topology is unchanged. rotation must be a proper rotation (orthonormal within 1e-6,
  /// determinant +1) and scale finite and > 0, otherwise std::invalid_argument. Lengths scale by `scale`.
  Skeleton transformed(const Eigen::Matrix3d& rotation, const Eigen::Vector3d& translation,
                       double scale) const;

 private:
  std::vector<SkeletonNode> nodes_;
  int root_ = -1;
  std::vector<int> child_offsets_;  // children of i: child_list_[child_offsets_[i] .. child_offsets_[i+1])
  std::vector<int> child_list_;
  std::vector<int> order_;
  std::vector<std::pair<int, int>> elements_;
};

}  // namespace fw::trees
