#include "trees/BranchPose.hpp"

#include <fmt/format.h>

#include <stdexcept>

namespace fw::trees {

Eigen::Matrix3d rotation_of(const Eigen::Vector3d& theta) {
  const double angle = theta.norm();
  if (angle == 0.0) return Eigen::Matrix3d::Identity();
  return Eigen::AngleAxisd(angle, theta / angle).toRotationMatrix();
}

Eigen::MatrixX3d branch_displacements(const BranchElements& elements, double scale,
                                      const std::vector<Eigen::Vector3d>& angles) {
  const int n = elements.size();
  if (int(angles.size()) != n)
    throw std::invalid_argument(
        fmt::format("branch_displacements: {} angles for {} entries", angles.size(), n));
  std::vector<Eigen::Matrix3d> turn(std::size_t(n), Eigen::Matrix3d::Identity());
  Eigen::MatrixX3d u = Eigen::MatrixX3d::Zero(n, 3);
  for (int j = 1; j < n; ++j) {
    const BranchElement& e = elements[j];
    turn[std::size_t(j)] = turn[std::size_t(e.parent_entry)] * rotation_of(angles[std::size_t(j)]);
    const Eigen::Vector3d rest = scale * e.rest;
    u.row(e.node) =
        u.row(e.parent_node) + ((turn[std::size_t(j)] - Eigen::Matrix3d::Identity()) * rest).transpose();
  }
  return u;
}

}  // namespace fw::trees
