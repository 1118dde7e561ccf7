#include "trees/BeamModel.hpp"

#include <stdexcept>
#include <vector>

#include <fmt/format.h>

#include "trees/BeamElement.hpp"
#include "trees/Skeleton.hpp"

namespace fw::trees {

BeamModel::BeamModel(const Skeleton& skeleton, const Material& material) {
  if (skeleton.size() < 2) {
    throw std::invalid_argument(
        fmt::format("BeamModel: the skeleton needs at least 2 nodes (one element), got {}", skeleton.size()));
  }
  material.validate();
  material_ = material;

  node_count_ = skeleton.size();
  root_ = skeleton.root();
  dof_count_ = 6 * (node_count_ - 1);

  const auto& elements = skeleton.elements();
  std::vector<Eigen::Triplet<double>> k_entries;
  std::vector<Eigen::Triplet<double>> m_entries;
  k_entries.reserve(elements.size() * 144);
  m_entries.reserve(elements.size() * 144);

  for (const auto& [parent, child] : elements) {
    const SkeletonNode& a = skeleton.node(parent);
    const SkeletonNode& b = skeleton.node(child);
    const BeamSection section = BeamSection::circle(0.5 * (a.radius + b.radius));
    const Matrix12d k = global_stiffness(material, section, a.position, b.position);
    const Matrix12d m = global_mass(material, section, a.position, b.position);

    int dof[12];
    for (int local = 0; local < 6; ++local) {
      dof[local] = free_dof_of(parent, local);
      dof[6 + local] = free_dof_of(child, local);
    }
    // Every entry of the free-free part is stored, zeros included, so that K and M share one pattern that
    // depends only on the topology.
    for (int i = 0; i < 12; ++i) {
      if (dof[i] < 0) continue;
      for (int j = 0; j < 12; ++j) {
        if (dof[j] < 0) continue;
        k_entries.emplace_back(dof[i], dof[j], k(i, j));
        m_entries.emplace_back(dof[i], dof[j], m(i, j));
      }
    }
  }

  stiffness_.resize(dof_count_, dof_count_);
  mass_.resize(dof_count_, dof_count_);
  stiffness_.setFromTriplets(k_entries.begin(), k_entries.end());
  mass_.setFromTriplets(m_entries.begin(), m_entries.end());
  stiffness_.makeCompressed();
  mass_.makeCompressed();
}

int BeamModel::free_dof_of(int node, int local) const {
  if (node < 0 || node >= node_count_) {
    throw std::out_of_range(fmt::format("BeamModel: node {} outside 0..{}", node, node_count_ - 1));
  }
  if (local < 0 || local > 5) {
    throw std::out_of_range(fmt::format("BeamModel: local DOF {} outside 0..5", local));
  }
  return free_dof_index(root_, node, local);
}

}  // namespace fw::trees
