#include "trees/BranchStemLoads.hpp"

#include <fmt/format.h>

#include <cmath>
#include <stdexcept>

#include "trees/BranchPose.hpp"
#include "trees/StemLoads.hpp"

namespace fw::trees {

BranchStem BranchStem::of(const Skeleton& skeleton) {
  BranchStem stem;
  stem.path_ = stem_path(skeleton);
  const int n = skeleton.size();
  const std::vector<int>& order = skeleton.topological_order();
  std::vector<int> entry_of(std::size_t(n), -1), section_of(std::size_t(n), -1);
  for (int j = 0; j < n; ++j) entry_of[std::size_t(order[std::size_t(j)])] = j;
  const std::vector<int> sections = stem_section_indices(stem_arc_length(skeleton, stem.path_));
  for (std::size_t j = 0; j < sections.size(); ++j) {
    const std::size_t i = std::size_t(sections[j]);
    const int node = stem.path_[i];
    section_of[std::size_t(node)] = int(j);
    stem.section_nodes_.push_back(node);
    stem.section_entries_.push_back(entry_of[std::size_t(node)]);
    stem.axes_.push_back(
        (skeleton.node(stem.path_[i + 1]).position - skeleton.node(node).position).normalized());
  }
  // The deepest section node among each node and its ancestors, parents first.
  std::vector<int> deepest(std::size_t(n), -1);
  stem.joint_sections_.assign(std::size_t(n), -1);
  stem.element_sections_.assign(std::size_t(n), -1);
  for (int j = 0; j < n; ++j) {
    const int node = order[std::size_t(j)], parent = skeleton.node(node).parent;
    const int own = section_of[std::size_t(node)];
    deepest[std::size_t(node)] = own >= 0 ? own : (parent >= 0 ? deepest[std::size_t(parent)] : -1);
    if (parent < 0) continue;
    stem.joint_sections_[std::size_t(j)] = section_of[std::size_t(parent)];
    stem.element_sections_[std::size_t(j)] = deepest[std::size_t(parent)];
  }
  return stem;
}

Eigen::Vector3d joint_moment(const BranchElement& e, TreeDynamics model, double scale,
                             const Eigen::Vector3d& theta) {
  const double s3 = scale * scale * scale;
  switch (model) {
    case TreeDynamics::rigid_bodies:
      return s3 * (e.joint_stiffness * theta);
    case TreeDynamics::springs: {
      const double angle = theta.norm();
      if (angle == 0.0) return Eigen::Vector3d::Zero();
      return (s3 * e.spring_stiffness * e.length * e.length * std::tan(angle) / angle) * theta;
    }
    case TreeDynamics::modal:
      break;
  }
  throw std::invalid_argument("joint_moment: a modal tree has no joints");
}

BranchStemMoments branch_stem_moments(const Skeleton& skeleton, const BranchElements& elements,
                                      const BranchStem& stem, TreeDynamics model, double scale,
                                      const std::vector<Eigen::Vector3d>& angles, double gravity) {
  const int n = elements.size(), J = stem.section_count();
  if (skeleton.size() != n || int(stem.joint_sections().size()) != n || int(angles.size()) != n)
    throw std::invalid_argument(
        fmt::format("branch_stem_moments: {} angles, a table of {} entries, a skeleton of {} nodes and a "
                    "stem of {} entries",
                    angles.size(), n, skeleton.size(), stem.joint_sections().size()));
  if (model == TreeDynamics::modal) throw std::invalid_argument("branch_stem_moments: a modal tree");
  BranchStemMoments out;
  out.elastic = Eigen::Matrix3Xd::Zero(3, J);
  for (int j = 1; j < n; ++j)
    if (const int section = stem.joint_sections()[std::size_t(j)]; section >= 0)
      out.elastic.col(section) += joint_moment(elements[j], model, scale, angles[std::size_t(j)]);

  // The modal model's weight moment (StemLoads) on the pose's displacements, with the lumped node masses.
  const double s3 = scale * scale * scale;
  Eigen::VectorXd masses = Eigen::VectorXd::Zero(n);
  for (int j = 1; j < n; ++j) {
    const BranchElement& e = elements[j];
    masses(e.node) += 0.5 * s3 * e.mass;
    masses(e.parent_node) += 0.5 * s3 * e.mass;
  }
  const Eigen::MatrixX3d u = branch_displacements(elements, scale, angles);
  Eigen::MatrixXd displacements(3 * n, 1);
  for (int k = 0; k < n; ++k) displacements.middleRows(3 * k, 3) = u.row(k).transpose();
  const Eigen::MatrixXd weight =
      section_moments_of_weight(skeleton, stem.section_nodes(), masses, displacements, gravity);
  out.weight = Eigen::Map<const Eigen::Matrix3Xd>(weight.data(), 3, J);

  out.bending.resize(J);
  for (int j = 0; j < J; ++j) {
    const Eigen::Vector3d moment = out.elastic.col(j) + out.weight.col(j);
    const Eigen::Vector3d& t = stem.axes()[std::size_t(j)];
    out.bending(j) = (moment - moment.dot(t) * t).norm();
  }
  out.root = (out.elastic.col(0) + out.weight.col(0)).head<2>().norm();
  return out;
}

TreeLoad branch_tree_load(const BranchStemMoments& moments, const CriticalMoments& critical, double scale) {
  if (std::size_t(moments.bending.size()) != critical.breaking.size())
    throw std::invalid_argument(fmt::format("branch_tree_load: {} sections against {} critical moments",
                                            moments.bending.size(), critical.breaking.size()));
  const double strength_scale = scale * scale * scale;  // d^3 and the stem's volume
  TreeLoad load;
  load.utilisation = moments.bending;
  for (Eigen::Index j = 0; j < load.utilisation.size(); ++j)
    load.utilisation(j) /= critical.breaking[std::size_t(j)] * strength_scale;
  load.root_moment = moments.root;
  load.overturning = load.root_moment / (critical.overturning * strength_scale);
  return load;
}

}  // namespace fw::trees
