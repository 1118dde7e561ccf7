#include "trees/SpringBranches.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <cmath>
#include <numbers>
#include <stdexcept>

#include "kernels/shared_types.h"

namespace fw::trees {

std::vector<double> spring_phases(int tree_id, int count) {
  std::vector<double> phases(std::size_t(std::max(count, 0)));
  const double turn = 2.0 * std::numbers::pi / double(1u << FW_PHASE_BITS);
  for (int j = 0; j < count; ++j)
    phases[std::size_t(j)] = turn * double(fw_phase_bits(fw_uint(tree_id), fw_uint(j)));
  return phases;
}

std::vector<Eigen::Vector3d> spring_angles(const BranchElements& elements, const SpringSettings& settings,
                                           double scale, const std::vector<Eigen::Vector3d>& loads,
                                           const std::vector<double>& phases, double time) {
  const int n = elements.size();
  if (int(loads.size()) != n || int(phases.size()) != n)
    throw std::invalid_argument(
        fmt::format("spring_angles: {} loads and {} phases for {} entries", loads.size(), phases.size(), n));
  const double largest = settings.max_angle_deg * std::numbers::pi / 180.0;
  const double omega = 2.0 * std::numbers::pi * settings.sway_frequency_hz;
  std::vector<Eigen::Vector3d> angles(std::size_t(n), Eigen::Vector3d::Zero());
  for (int j = 1; j < n; ++j) {
    const BranchElement& e = elements[j];
    const Eigen::Vector3d axis = e.rest / e.length;
    const Eigen::Vector3d& F = loads[std::size_t(j)];
    const Eigen::Vector3d normal = F - F.dot(axis) * axis;
    const double load = normal.norm();
    if (load == 0.0) continue;
    // Deflection over length, both at scale s: P / (s k) / (s L).
    const double bend = load / (scale * e.spring_stiffness) / (scale * e.length);
    const double steady = std::min(std::atan(bend), largest);
    const double amplitude = settings.sway_amplitude * steady / largest;
    const double swayed = bend * (1.0 + amplitude * std::sin(omega * time + phases[std::size_t(j)]));
    const double theta = std::clamp(std::atan(swayed), -largest, largest);
    angles[std::size_t(j)] = theta * axis.cross(normal / load);
  }
  return angles;
}

}  // namespace fw::trees
