#include "trees/Skeleton.hpp"

#include <fmt/format.h>

#include <Eigen/LU>

#include <algorithm>
#include <cmath>
#include <limits>

namespace fw::trees {

namespace {

std::string message(int node, SkeletonError::Field field, const std::string& expected,
                    const std::string& got) {
  if (node < 0) return fmt::format("Skeleton: {}, got {}", expected, got);
  return fmt::format("Skeleton: node {}: {}: {}, got {}", node, SkeletonError::field_name(field), expected,
                     got);
}

std::string point(const Eigen::Vector3d& p) {
  return fmt::format("({:g}, {:g}, {:g})", p.x(), p.y(), p.z());
}

// The nodes of the cycle that node `start`'s parent chain runs into, starting at its smallest index.
// Requires that the chain never reaches -1.
std::vector<int> find_cycle(const std::vector<SkeletonNode>& nodes, int start) {
  std::vector<int> step(nodes.size(), -1);
  int node = start;
  for (int k = 0; step[std::size_t(node)] < 0; ++k) {
    step[std::size_t(node)] = k;
    node = nodes[std::size_t(node)].parent;
  }
  // `node` is the first node seen twice: it lies on the cycle.
  std::vector<int> cycle{node};
  for (int next = nodes[std::size_t(node)].parent; next != node; next = nodes[std::size_t(next)].parent)
    cycle.push_back(next);
  std::rotate(cycle.begin(), std::min_element(cycle.begin(), cycle.end()), cycle.end());
  return cycle;
}

std::string describe_cycle(const std::vector<int>& cycle) {
  constexpr std::size_t kShown = 8;
  std::string text;
  for (std::size_t k = 0; k < std::min(cycle.size(), kShown); ++k) text += fmt::format("{} -> ", cycle[k]);
  if (cycle.size() > kShown) text += "... -> ";
  text += fmt::format("{}", cycle.front());
  return text;
}

}  // namespace

SkeletonError::SkeletonError(int node, Field field, std::string expected, std::string got)
    : std::invalid_argument(message(node, field, expected, got)),
      node_(node),
      field_(field),
      expected_(std::move(expected)),
      got_(std::move(got)) {}

const char* SkeletonError::field_name(Field field) {
  switch (field) {
    case Field::nodes:
      return "nodes";
    case Field::parent:
      return "parent";
    case Field::position:
      return "position";
    case Field::radius:
      return "radius";
  }
  return "?";
}

Skeleton Skeleton::from_nodes(std::vector<SkeletonNode> nodes) {
  using Field = SkeletonError::Field;
  if (nodes.empty()) throw SkeletonError(-1, Field::nodes, "expected at least one node", "none");
  if (nodes.size() > std::size_t(std::numeric_limits<int>::max() - 1))
    throw SkeletonError(-1, Field::nodes, "expected fewer nodes", fmt::format("{}", nodes.size()));
  const int n = int(nodes.size());

  // Per-node checks, in index order.
  int root = -1;
  for (int i = 0; i < n; ++i) {
    const SkeletonNode& node = nodes[std::size_t(i)];
    if (!node.position.allFinite())
      throw SkeletonError(i, Field::position, "expected finite coordinates in metres", point(node.position));
    if (!std::isfinite(node.radius) || node.radius <= 0.0)
      throw SkeletonError(i, Field::radius, "expected a positive radius in metres",
                          fmt::format("{:g}", node.radius));
    if (node.parent < -1 || node.parent >= n)
      throw SkeletonError(i, Field::parent,
                          fmt::format("expected -1 (root) or an existing node in 0..{}", n - 1),
                          fmt::format("{}", node.parent));
    if (node.parent == i)
      throw SkeletonError(i, Field::parent, "expected a parent other than the node itself",
                          fmt::format("{}", node.parent));
    if (node.parent == -1) {
      if (root >= 0)
        throw SkeletonError(
            i, Field::parent,
            fmt::format("expected exactly one root (parent -1), but node {} is already the root", root),
            "-1");
      root = i;
    }
  }

  Skeleton skeleton;
  skeleton.nodes_ = std::move(nodes);
  skeleton.root_ = root;
  const auto& all = skeleton.nodes_;

  // Children in compressed rows, in increasing index order.
  skeleton.child_offsets_.assign(std::size_t(n) + 1, 0);
  for (const SkeletonNode& node : all)
    if (node.parent >= 0) ++skeleton.child_offsets_[std::size_t(node.parent) + 1];
  for (int i = 0; i < n; ++i)
    skeleton.child_offsets_[std::size_t(i) + 1] += skeleton.child_offsets_[std::size_t(i)];
  skeleton.child_list_.resize(std::size_t(skeleton.child_offsets_[std::size_t(n)]));
  {
    std::vector<int> fill(skeleton.child_offsets_.begin(), skeleton.child_offsets_.end() - 1);
    for (int i = 0; i < n; ++i) {
      const int parent = all[std::size_t(i)].parent;
      if (parent >= 0) skeleton.child_list_[std::size_t(fill[std::size_t(parent)]++)] = i;
    }
  }

  // Breadth-first from the root; whatever it does not reach hangs off a cycle.
  if (root >= 0) {
    skeleton.order_.reserve(std::size_t(n));
    skeleton.order_.push_back(root);
    for (std::size_t k = 0; k < skeleton.order_.size(); ++k)
      for (int child : skeleton.children(skeleton.order_[k])) skeleton.order_.push_back(child);
  }
  if (int(skeleton.order_.size()) != n) {
    std::vector<char> reached(std::size_t(n), 0);
    for (int i : skeleton.order_) reached[std::size_t(i)] = 1;
    const int start = int(std::find(reached.begin(), reached.end(), 0) - reached.begin());
    const auto cycle = find_cycle(all, start);
    const int culprit = cycle.front();
    const std::string expected =
        root < 0
            ? fmt::format("expected exactly one root (parent -1), found none; nodes {} form a cycle",
                          describe_cycle(cycle))
            : fmt::format("expected a parent chain that reaches the root node {}, but nodes {} form a cycle",
                          root, describe_cycle(cycle));
    throw SkeletonError(culprit, Field::parent, expected,
                        fmt::format("{}", all[std::size_t(culprit)].parent));
  }

  // Elements, parents before children; none may have zero length.
  skeleton.elements_.reserve(std::size_t(n) - 1);
  for (std::size_t k = 1; k < skeleton.order_.size(); ++k) {
    const int child = skeleton.order_[k];
    const int parent = all[std::size_t(child)].parent;
    const Eigen::Vector3d& p = all[std::size_t(parent)].position;
    const Eigen::Vector3d& c = all[std::size_t(child)].position;
    if ((c - p).norm() <= kMinElementLength)
      throw SkeletonError(child, Field::position,
                          fmt::format("expected a position more than {:g} m from its parent node {} at {} "
                                      "(a zero-length element)",
                                      kMinElementLength, parent, point(p)),
                          point(c));
    skeleton.elements_.emplace_back(parent, child);
  }
  return skeleton;
}

std::span<const int> Skeleton::children(int i) const {
  if (i < 0 || i >= size())
    throw std::out_of_range(fmt::format("Skeleton::children: node {} outside 0..{}", i, size() - 1));
  const auto begin = std::size_t(child_offsets_[std::size_t(i)]);
  const auto end = std::size_t(child_offsets_[std::size_t(i) + 1]);
  return std::span<const int>(child_list_.data() + begin, end - begin);
}

double Skeleton::height() const {
  if (nodes_.empty()) return 0.0;
  double top = -std::numeric_limits<double>::infinity();
  for (const SkeletonNode& node : nodes_) top = std::max(top, node.position.z());
  return top - nodes_[std::size_t(root_)].position.z();
}

Eigen::AlignedBox3d Skeleton::bounding_box() const {
  Eigen::AlignedBox3d box;  // empty
  for (const SkeletonNode& node : nodes_) box.extend(node.position);
  return box;
}

Skeleton Skeleton::transformed(const Eigen::Matrix3d& rotation, const Eigen::Vector3d& translation,
                               double scale) const {
  if (!std::isfinite(scale) || scale <= 0.0)
    throw std::invalid_argument(
        fmt::format("Skeleton::transformed: expected a finite scale > 0, got {:g}", scale));
  if (!rotation.allFinite() || !translation.allFinite())
    throw std::invalid_argument("Skeleton::transformed: expected a finite rotation and translation");
  const double orthogonality =
      (rotation.transpose() * rotation - Eigen::Matrix3d::Identity()).cwiseAbs().maxCoeff();
  if (orthogonality > 1e-6 || rotation.determinant() <= 0.0)
    throw std::invalid_argument(
        fmt::format("Skeleton::transformed: expected a proper rotation (R^T R = I within 1e-6, det R = +1), "
                    "got |R^T R - I| "
                    "= {:g}, det R = {:g}",
                    orthogonality, rotation.determinant()));
  std::vector<SkeletonNode> nodes = nodes_;
  for (SkeletonNode& node : nodes) {
    node.position = translation + scale * (rotation * node.position);
    node.radius *= scale;
  }
  return from_nodes(std::move(nodes));
}

}  // namespace fw::trees
