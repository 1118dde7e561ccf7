#include "trees/BranchElements.hpp"

#include <stdexcept>

#include "trees/BeamElement.hpp"
#include "trees/Skeleton.hpp"

namespace fw::trees {
namespace {

// C(e) L / 2: the compliance of half an element, rad / (N m).
Eigen::Matrix3d half_compliance(const Material& material, const BeamSection& section,
                                const Eigen::Vector3d& axis, double length) {
  const Eigen::Matrix3d along = axis * axis.transpose();
  const Eigen::Matrix3d bending =
      (Eigen::Matrix3d::Identity() - along) / (material.youngs_modulus * section.second_moment);
  const Eigen::Matrix3d torsion = along / (material.shear_modulus * section.polar_moment);
  return 0.5 * length * (bending + torsion);
}

}  // namespace

BranchElements BranchElements::of(const Skeleton& skeleton, const Material& material,
                                  const WindBasisSettings& drag) {
  material.validate();
  if (skeleton.size() < 2) throw std::invalid_argument("BranchElements: the skeleton has no elements");
  const ElementDrag element_drag = ElementDrag::of(skeleton, drag);  // validates the drag settings
  const std::vector<int>& order = skeleton.topological_order();
  const int n = skeleton.size();

  std::vector<int> entry_of(std::size_t(n), -1);
  for (int j = 0; j < n; ++j) entry_of[std::size_t(order[std::size_t(j)])] = j;

  BranchElements table;
  table.normal_drag_ = drag.branch_normal_drag;
  table.entries_.resize(std::size_t(n));
  table.entries_[0].node = order[0];
  const double half_rho = 0.5 * drag.air_density;
  std::vector<BeamSection> sections(static_cast<std::size_t>(n));
  for (int j = 1; j < n; ++j) {
    // Element j - 1 of the skeleton ends at order[j] (Skeleton::elements()).
    const int e = j - 1;
    const auto [parent, child] = skeleton.elements()[std::size_t(e)];
    BranchElement& entry = table.entries_[std::size_t(j)];
    const SkeletonNode& a = skeleton.node(parent);
    const SkeletonNode& b = skeleton.node(child);
    entry.node = child;
    entry.parent_node = parent;
    entry.parent_entry = entry_of[std::size_t(parent)];
    entry.rest = b.position - a.position;
    entry.centre = 0.5 * (a.position + b.position);
    entry.length = entry.rest.norm();
    const BeamSection section = BeamSection::circle(0.5 * (a.radius + b.radius));
    sections[std::size_t(j)] = section;
    entry.mass = material.density * section.area * entry.length;
    entry.axial_inertia = material.density * section.polar_moment * entry.length;
    entry.branch_drag = half_rho * drag.branch_drag_coefficient * element_drag.diameter[std::size_t(e)];
    entry.leaf_drag =
        half_rho * drag.leaf_drag_coefficient * element_drag.foliage.leaf_area_per_metre[std::size_t(e)];
    const double diameter = element_drag.diameter[std::size_t(e)];
    const double d2 = diameter * diameter;
    entry.spring_stiffness =
        material.youngs_modulus * d2 * d2 / (4.0 * entry.length * entry.length * entry.length);
  }

  // The continuing child of every node: its thickest, the first (in table order) on a tie.
  std::vector<int> continuing(std::size_t(n), -1);
  for (int j = 1; j < n; ++j) {
    const int p = table.entries_[std::size_t(j)].parent_entry;
    int& best = continuing[std::size_t(p)];
    if (best < 0 || sections[std::size_t(j)].area > sections[std::size_t(best)].area) best = j;
  }
  for (int j = 1; j < n; ++j) {
    BranchElement& entry = table.entries_[std::size_t(j)];
    Eigen::Matrix3d compliance =
        half_compliance(material, sections[std::size_t(j)], entry.rest / entry.length, entry.length);
    const int p = entry.parent_entry;
    if (p > 0 && continuing[std::size_t(p)] == j) {
      const BranchElement& parent = table.entries_[std::size_t(p)];
      compliance +=
          half_compliance(material, sections[std::size_t(p)], parent.rest / parent.length, parent.length);
    }
    entry.joint_stiffness = compliance.inverse();
  }
  return table;
}

Eigen::Vector3d BranchElements::load(int entry, const Eigen::Vector3d& wind) const {
  const BranchElement& e = (*this)[entry];
  const double speed = wind.norm();
  Eigen::Vector3d wood = wind;
  if (normal_drag_ && e.length > 0.0) {
    const Eigen::Vector3d axis = e.rest / e.length;
    wood -= axis.dot(wind) * axis;
  }
  return e.length * speed * (e.branch_drag * wood + e.leaf_drag * wind);
}

std::vector<FwBranch> BranchElements::pack() const {
  std::vector<FwBranch> packed(entries_.size());
  for (std::size_t j = 0; j < entries_.size(); ++j) {
    const BranchElement& e = entries_[j];
    FwBranch& b = packed[j];
    b.node = e.node;
    b.parent_node = e.parent_node;
    b.parent_entry = e.parent_entry;
    for (int axis = 0; axis < 3; ++axis) {
      b.rest[axis] = float(e.rest[axis]);
      b.centre[axis] = float(e.centre[axis]);
    }
    b.length = float(e.length);
    b.mass = float(e.mass);
    b.axial_inertia = float(e.axial_inertia);
    const Eigen::Matrix3d& K = e.joint_stiffness;
    const double stiffness[6] = {K(0, 0), K(1, 1), K(2, 2), K(0, 1), K(0, 2), K(1, 2)};
    for (int i = 0; i < 6; ++i) b.stiffness[i] = float(stiffness[i]);
    b.branch_drag = float(e.branch_drag);
    b.leaf_drag = float(e.leaf_drag);
    b.spring = float(e.spring_stiffness);
  }
  return packed;
}

}  // namespace fw::trees
