#include "trees/StemLoads.hpp"

#include <fmt/format.h>

#include <cmath>
#include <numbers>
#include <stdexcept>

namespace fw::trees {

namespace {

constexpr int kAxes = 3;
constexpr int kPlane = 2;  // bending components per section: e1, e2

// x cross each column of a 3 x c block.
Eigen::MatrixXd cross_columns(const Eigen::Vector3d& x, const Eigen::MatrixXd& block) {
  Eigen::MatrixXd out(kAxes, block.cols());
  for (Eigen::Index c = 0; c < block.cols(); ++c) out.col(c) = x.cross(Eigen::Vector3d(block.col(c)));
  return out;
}

// Each node's total of `own` (rows 3k..3k+2 node k's) over its subtree, itself included: children before
// parents, in reverse breadth-first order.
Eigen::MatrixXd subtree_totals(const Skeleton& skeleton, const Eigen::MatrixXd& own) {
  Eigen::MatrixXd total = own;
  const std::vector<int>& order = skeleton.topological_order();
  for (auto it = order.rbegin(); it != order.rend(); ++it) {
    const int parent = skeleton.node(*it).parent;
    if (parent >= 0) total.middleRows(kAxes * parent, kAxes) += total.middleRows(kAxes * *it, kAxes);
  }
  return total;
}

void require_finite(const char* what, const Eigen::MatrixXd& values) {
  if (!values.allFinite())
    throw std::invalid_argument(fmt::format("StemLoads: {} holds a non-finite value", what));
}

// The unit normal pair (e1, e2) of the plane normal to the stem's axis t: e1 horizontal unless t is within
// a degree of horizontal-free (vertical t has every horizontal e1; take t x z, else t x x).
Eigen::Matrix<double, 2, 3> bending_plane(const Eigen::Vector3d& t) {
  Eigen::Vector3d e1 = t.cross(Eigen::Vector3d::UnitZ());
  if (e1.norm() < 1e-6) e1 = t.cross(Eigen::Vector3d::UnitX());
  e1.normalize();
  Eigen::Matrix<double, 2, 3> plane;
  plane.row(0) = e1.transpose();
  plane.row(1) = t.cross(e1).normalized().transpose();
  return plane;
}

}  // namespace

std::vector<int> stem_path(const Skeleton& skeleton) {
  std::vector<int> path{skeleton.root()};
  Eigen::Vector3d direction = Eigen::Vector3d::UnitZ();
  for (int node = skeleton.root(); !skeleton.children(node).empty();) {
    int best = -1;
    double best_radius = 0.0, best_turn = 0.0;
    for (const int child : skeleton.children(node)) {
      const double radius = skeleton.node(child).radius;
      const double turn =
          (skeleton.node(child).position - skeleton.node(node).position).normalized().dot(direction);
      if (best < 0 || radius > best_radius || (radius == best_radius && turn > best_turn)) {
        best = child;
        best_radius = radius;
        best_turn = turn;
      }
    }
    direction = (skeleton.node(best).position - skeleton.node(node).position).normalized();
    path.push_back(best);
    node = best;
  }
  if (path.size() < 2) throw std::invalid_argument("StemLoads: the skeleton's root has no child");
  return path;
}

Eigen::VectorXd stem_arc_length(const Skeleton& skeleton, const std::vector<int>& path) {
  Eigen::VectorXd along = Eigen::VectorXd::Zero(Eigen::Index(path.size()));
  for (std::size_t i = 1; i < path.size(); ++i)
    along(Eigen::Index(i)) = along(Eigen::Index(i) - 1) +
                             (skeleton.node(path[i]).position - skeleton.node(path[i - 1]).position).norm();
  return along;
}

std::vector<int> stem_section_indices(const Eigen::VectorXd& arc_length) {
  const int nodes = int(arc_length.size());
  if (nodes < 2) throw std::invalid_argument("StemLoads: a stem needs at least 2 nodes");
  std::vector<int> indices;
  if (nodes - 1 <= kMaxStemSections) {
    for (int i = 0; i + 1 < nodes; ++i) indices.push_back(i);
    return indices;
  }
  const double length = arc_length(nodes - 1);
  int node = 0;
  for (int k = 0; k < kMaxStemSections; ++k) {
    const double target = length * k / kMaxStemSections;
    // The nodes' distances increase: walk on while the next node is nearer the target.
    while (node + 1 < nodes && std::abs(arc_length(node + 1) - target) < std::abs(arc_length(node) - target))
      ++node;
    const int section = std::min(node, nodes - 2);  // the top bends nothing
    if (indices.empty() || section > indices.back()) indices.push_back(section);
  }
  return indices;
}

Eigen::VectorXd lumped_node_masses(const Skeleton& skeleton, double density) {
  Eigen::VectorXd masses = Eigen::VectorXd::Zero(skeleton.size());
  for (const auto& [a, b] : skeleton.elements()) {
    const double radius = 0.5 * (skeleton.node(a).radius + skeleton.node(b).radius);
    const double length = (skeleton.node(b).position - skeleton.node(a).position).norm();
    const double half = 0.5 * density * std::numbers::pi * radius * radius * length;
    masses(a) += half;
    masses(b) += half;
  }
  return masses;
}

Eigen::MatrixXd section_moments_of_forces(const Skeleton& skeleton, const std::vector<int>& sections,
                                          const Eigen::MatrixXd& forces) {
  const int n = skeleton.size();
  if (forces.rows() != kAxes * n)
    throw std::invalid_argument(
        fmt::format("StemLoads: forces have {} rows, expected 3 x {}", forces.rows(), n));
  Eigen::MatrixXd own_moments(forces.rows(), forces.cols());
  for (int k = 0; k < n; ++k)
    own_moments.middleRows(kAxes * k, kAxes) =
        cross_columns(skeleton.node(k).position, forces.middleRows(kAxes * k, kAxes));
  const Eigen::MatrixXd force_totals = subtree_totals(skeleton, forces);
  const Eigen::MatrixXd moment_totals = subtree_totals(skeleton, own_moments);

  Eigen::MatrixXd moments(kAxes * Eigen::Index(sections.size()), forces.cols());
  for (std::size_t j = 0; j < sections.size(); ++j) {
    const int node = sections[j];
    const Eigen::Vector3d& x = skeleton.node(node).position;
    // The descendants' sums: the subtree's less the node's own (whose lever arm is zero anyway).
    const Eigen::MatrixXd above_forces =
        force_totals.middleRows(kAxes * node, kAxes) - forces.middleRows(kAxes * node, kAxes);
    const Eigen::MatrixXd above_moments =
        moment_totals.middleRows(kAxes * node, kAxes) - own_moments.middleRows(kAxes * node, kAxes);
    moments.middleRows(kAxes * Eigen::Index(j), kAxes) = above_moments - cross_columns(x, above_forces);
  }
  return moments;
}

Eigen::MatrixXd section_moments_of_weight(const Skeleton& skeleton, const std::vector<int>& sections,
                                          const Eigen::VectorXd& masses, const Eigen::MatrixXd& displacements,
                                          double gravity) {
  const int n = skeleton.size();
  if (masses.size() != n || displacements.rows() != kAxes * n)
    throw std::invalid_argument("StemLoads: masses or displacements do not fit the skeleton");
  Eigen::MatrixXd weighted(displacements.rows(), displacements.cols());
  Eigen::MatrixXd mass_rows = Eigen::MatrixXd::Zero(kAxes * n, 1);  // the mass on the first row of each node
  for (int k = 0; k < n; ++k) {
    weighted.middleRows(kAxes * k, kAxes) = masses(k) * displacements.middleRows(kAxes * k, kAxes);
    mass_rows(kAxes * k) = masses(k);
  }
  const Eigen::MatrixXd weighted_totals = subtree_totals(skeleton, weighted);
  const Eigen::MatrixXd mass_totals = subtree_totals(skeleton, mass_rows);

  Eigen::MatrixXd moments =
      Eigen::MatrixXd::Zero(kAxes * Eigen::Index(sections.size()), displacements.cols());
  for (std::size_t j = 0; j < sections.size(); ++j) {
    const int node = sections[j];
    const double mass_above = mass_totals(kAxes * node) - masses(node);
    // a = sum over the descendants of m_k (u_k - u_j); (a) x (0, 0, -g) = (-g a_y, g a_x, 0).
    const Eigen::MatrixXd a = weighted_totals.middleRows(kAxes * node, kAxes) -
                              weighted.middleRows(kAxes * node, kAxes) -
                              mass_above * displacements.middleRows(kAxes * node, kAxes);
    moments.row(kAxes * Eigen::Index(j)) = -gravity * a.row(1);
    moments.row(kAxes * Eigen::Index(j) + 1) = gravity * a.row(0);
  }
  return moments;
}

StemLoads StemLoads::compute(const Skeleton& skeleton, const BeamModel& model, const ModalBasis& modes,
                             double gravity) {
  if (model.node_count() != skeleton.size() || modes.dof_count() != model.dof_count())
    throw std::invalid_argument("StemLoads: the modes do not fit the model or the skeleton");
  const std::vector<int> path = stem_path(skeleton);
  const Eigen::VectorXd arc_length = stem_arc_length(skeleton, path);
  const std::vector<int> section_indices = stem_section_indices(arc_length);
  std::vector<int> sections;
  for (const int i : section_indices) sections.push_back(path[std::size_t(i)]);
  const int n = skeleton.size(), m = modes.mode_count();

  // The translational rows, node-major, of K Phi (the elastic forces per unit q) and of Phi.
  const Eigen::MatrixXd elastic_forces = model.stiffness() * modes.shapes();
  Eigen::MatrixXd forces = Eigen::MatrixXd::Zero(kAxes * n, m), shapes = Eigen::MatrixXd::Zero(kAxes * n, m);
  for (int k = 0; k < n; ++k) {
    for (int axis = 0; axis < kAxes; ++axis) {
      if (const int dof = model.free_dof_of(k, axis); dof >= 0) {
        forces.row(kAxes * k + axis) = elastic_forces.row(dof);
        shapes.row(kAxes * k + axis) = modes.shapes().row(dof);
      }
    }
  }
  const Eigen::MatrixXd elastic = section_moments_of_forces(skeleton, sections, forces);
  const Eigen::MatrixXd weight = section_moments_of_weight(
      skeleton, sections, lumped_node_masses(skeleton, model.material().density), shapes, gravity);

  StemLoads loads;
  const Eigen::Index J = Eigen::Index(sections.size());
  loads.elastic_.resize(kPlane * J, m);
  loads.weight_.resize(kPlane * J, m);
  for (Eigen::Index j = 0; j < J; ++j) {
    const std::size_t i = std::size_t(section_indices[std::size_t(j)]);
    const Eigen::Vector3d axis =
        (skeleton.node(path[i + 1]).position - skeleton.node(path[i]).position).normalized();
    const Eigen::Matrix<double, 2, 3> plane = bending_plane(axis);
    loads.elastic_.middleRows(kPlane * j, kPlane) = plane * elastic.middleRows(kAxes * j, kAxes);
    loads.weight_.middleRows(kPlane * j, kPlane) = plane * weight.middleRows(kAxes * j, kAxes);
  }
  loads.root_elastic_ = elastic.topRows(kPlane);  // the root is section 0; x and y are its horizontal part
  loads.root_weight_ = weight.topRows(kPlane);

  const Eigen::Vector3d& root = skeleton.node(skeleton.root()).position;
  loads.arc_length_ = arc_length;
  loads.section_indices_ = section_indices;
  for (const int node : path)
    loads.profile_.push_back(
        {node, skeleton.node(node).position.z() - root.z(), 2.0 * skeleton.node(node).radius});
  return loads;
}

StemLoads StemLoads::from_values(std::vector<StemSection> profile, Eigen::VectorXd arc_length,
                                 std::vector<int> section_indices, Eigen::MatrixXd elastic,
                                 Eigen::MatrixXd weight, Eigen::MatrixXd root_elastic,
                                 Eigen::MatrixXd root_weight) {
  const Eigen::Index J = Eigen::Index(section_indices.size());
  for (std::size_t j = 0; j < section_indices.size(); ++j) {
    const int i = section_indices[j];
    if ((j == 0 && i != 0) || (j > 0 && i <= section_indices[j - 1]) || i + 1 >= int(profile.size()))
      throw std::invalid_argument(fmt::format(
          "StemLoads: section {} at stem node {} of {}: sections increase from the root, below the top", j, i,
          profile.size()));
  }
  if (J < 1 || arc_length.size() != Eigen::Index(profile.size()) || elastic.rows() != kPlane * J ||
      weight.rows() != elastic.rows() || weight.cols() != elastic.cols() || root_elastic.rows() != kPlane ||
      root_weight.rows() != kPlane || root_elastic.cols() != elastic.cols() ||
      root_weight.cols() != elastic.cols()) {
    throw std::invalid_argument(fmt::format(
        "StemLoads: {} stem nodes, {} sections, maps {} x {} and {} x {}, root maps {} x {}: sizes that do "
        "not fit",
        profile.size(), J, elastic.rows(), elastic.cols(), weight.rows(), weight.cols(), root_elastic.rows(),
        root_elastic.cols()));
  }
  require_finite("the elastic map", elastic);
  require_finite("the weight map", weight);
  require_finite("the root's maps", root_elastic);
  require_finite("the root's maps", root_weight);
  require_finite("the stem's lengths", arc_length);
  for (const StemSection& section : profile)
    if (!std::isfinite(section.height) || !(section.diameter > 0.0) || !std::isfinite(section.diameter))
      throw std::invalid_argument("StemLoads: a stem node's height or diameter is not finite and positive");
  StemLoads loads;
  loads.profile_ = std::move(profile);
  loads.arc_length_ = std::move(arc_length);
  loads.section_indices_ = std::move(section_indices);
  loads.elastic_ = std::move(elastic);
  loads.weight_ = std::move(weight);
  loads.root_elastic_ = std::move(root_elastic);
  loads.root_weight_ = std::move(root_weight);
  return loads;
}

std::vector<StemSection> StemLoads::sections() const {
  std::vector<StemSection> sections;
  for (const int i : section_indices_) sections.push_back(profile_[std::size_t(i)]);
  return sections;
}

std::vector<float> StemLoads::along_stem(std::span<const float> at_sections) const {
  if (int(at_sections.size()) != section_count())
    throw std::invalid_argument(
        fmt::format("StemLoads: {} values for {} sections", at_sections.size(), section_count()));
  std::vector<float> nodes(profile_.size(), 0.0f);
  std::size_t j = 0;  // the section at or below node i
  for (std::size_t i = 0; i < profile_.size(); ++i) {
    while (j + 1 < section_indices_.size() && std::size_t(section_indices_[j + 1]) <= i) ++j;
    if (j + 1 == section_indices_.size()) {
      nodes[i] = at_sections[j];
      continue;
    }
    const double below = arc_length_(section_indices_[j]), above = arc_length_(section_indices_[j + 1]);
    const double t = (arc_length_(Eigen::Index(i)) - below) / (above - below);
    nodes[i] = float((1.0 - t) * at_sections[j] + t * at_sections[j + 1]);
  }
  return nodes;
}

Eigen::VectorXd StemLoads::bending_moments(const Eigen::VectorXd& q) const {
  const Eigen::VectorXd planar = (elastic_ + weight_) * q;
  Eigen::VectorXd moments(section_count());
  for (int j = 0; j < section_count(); ++j)
    moments(j) = std::hypot(planar(kPlane * j), planar(kPlane * j + 1));
  return moments;
}

double StemLoads::root_moment(const Eigen::VectorXd& q) const {
  const Eigen::Vector2d horizontal = (root_elastic_ + root_weight_) * q;
  return horizontal.norm();
}

double StemLoads::diameter_at(double height) const {
  if (profile_.empty()) return 0.0;
  if (height <= profile_.front().height) return profile_.front().diameter;
  for (std::size_t i = 1; i < profile_.size(); ++i) {
    const StemSection& below = profile_[i - 1];
    const StemSection& above = profile_[i];
    if (above.height >= height && above.height > below.height) {
      const double f = (height - below.height) / (above.height - below.height);
      return below.diameter + f * (above.diameter - below.diameter);
    }
  }
  return profile_.back().diameter;
}

double StemLoads::stem_volume() const {
  double volume = 0.0;
  for (std::size_t i = 1; i < profile_.size(); ++i) {
    const double a = 0.5 * profile_[i - 1].diameter, b = 0.5 * profile_[i].diameter;
    const double length = arc_length_(Eigen::Index(i)) - arc_length_(Eigen::Index(i) - 1);
    volume += std::numbers::pi * length * (a * a + a * b + b * b) / 3.0;
  }
  return volume;
}

StemLoads StemLoads::scaled(double s) const {
  if (!std::isfinite(s) || !(s > 0.0))
    throw std::invalid_argument(fmt::format("StemLoads: the scale must be finite and positive, got {}", s));
  StemLoads loads = *this;
  for (StemSection& section : loads.profile_) {
    section.height *= s;
    section.diameter *= s;
  }
  loads.arc_length_ *= s;
  const double elastic_scale = std::sqrt(s), weight_scale = s * std::sqrt(s);
  loads.elastic_ *= elastic_scale;
  loads.root_elastic_ *= elastic_scale;
  loads.weight_ *= weight_scale;
  loads.root_weight_ *= weight_scale;
  return loads;
}

}  // namespace fw::trees
