#include "trees/Foliage.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <cmath>
#include <stdexcept>

namespace fw::trees {

std::vector<bool> leaf_bearing_elements(const Skeleton& skeleton) {
  const auto& pairs = skeleton.elements();
  const std::size_t n = std::size_t(skeleton.size());
  // The main stem continues into the thickest child at each fork (ties: the lowest index); every other
  // child starts a branch one order higher.
  std::vector<int> main_child(n, -1), child_count(n, 0);
  for (const auto& [parent, child] : pairs) {
    ++child_count[std::size_t(parent)];
    int& best = main_child[std::size_t(parent)];
    if (best < 0 || skeleton.node(child).radius > skeleton.node(best).radius ||
        (skeleton.node(child).radius == skeleton.node(best).radius && child < best)) {
      best = child;
    }
  }
  // elements() is breadth-first: a parent's order is known before its children's.
  std::vector<int> order(n, 0);
  for (const auto& [parent, child] : pairs) {
    order[std::size_t(child)] =
        order[std::size_t(parent)] + (main_child[std::size_t(parent)] == child ? 0 : 1);
  }
  std::vector<bool> bearing(pairs.size(), false);
  bool any_branch = false;
  for (std::size_t e = 0; e < pairs.size(); ++e) {
    bearing[e] = order[std::size_t(pairs[e].second)] >= 1;
    any_branch = any_branch || bearing[e];
  }
  if (!any_branch) {  // an unbranched pole: its terminal element carries the leaves
    for (std::size_t e = 0; e < pairs.size(); ++e)
      bearing[e] = child_count[std::size_t(pairs[e].second)] == 0;
  }
  return bearing;
}

double convex_hull_area(std::vector<Eigen::Vector2d> p) {
  // Andrew's monotone chain, then the shoelace formula.
  auto less = [](const Eigen::Vector2d& a, const Eigen::Vector2d& b) {
    return a.x() < b.x() || (a.x() == b.x() && a.y() < b.y());
  };
  std::sort(p.begin(), p.end(), less);
  p.erase(std::unique(p.begin(), p.end()), p.end());
  if (p.size() < 3) return 0.0;
  auto cross = [](const Eigen::Vector2d& o, const Eigen::Vector2d& a, const Eigen::Vector2d& b) {
    return (a.x() - o.x()) * (b.y() - o.y()) - (a.y() - o.y()) * (b.x() - o.x());
  };
  std::vector<Eigen::Vector2d> hull(2 * p.size());
  std::size_t k = 0;
  for (std::size_t i = 0; i < p.size(); ++i) {  // lower chain
    while (k >= 2 && cross(hull[k - 2], hull[k - 1], p[i]) <= 0.0) --k;
    hull[k++] = p[i];
  }
  for (std::size_t i = p.size() - 1, lower = k + 1; i-- > 0;) {  // upper chain
    while (k >= lower && cross(hull[k - 2], hull[k - 1], p[i]) <= 0.0) --k;
    hull[k++] = p[i];
  }
  hull.resize(k - 1);  // the last point repeats the first
  double twice = 0.0;
  for (std::size_t i = 0; i < hull.size(); ++i) {
    const auto& a = hull[i];
    const auto& b = hull[(i + 1) % hull.size()];
    twice += a.x() * b.y() - a.y() * b.x();
  }
  return 0.5 * std::abs(twice);
}

Foliage Foliage::of(const Skeleton& skeleton, double leaf_area_index) {
  if (!std::isfinite(leaf_area_index) || leaf_area_index < 0.0) {
    throw std::invalid_argument(
        fmt::format("Foliage: leaf area index must be finite and >= 0, got {}", leaf_area_index));
  }
  const auto& pairs = skeleton.elements();
  Foliage foliage;
  foliage.leaf_bearing = leaf_bearing_elements(skeleton);
  foliage.leaf_area_per_metre.assign(pairs.size(), 0.0);
  std::vector<Eigen::Vector2d> crown;
  for (std::size_t e = 0; e < pairs.size(); ++e) {
    if (!foliage.leaf_bearing[e]) continue;
    const Eigen::Vector3d& a = skeleton.node(pairs[e].first).position;
    const Eigen::Vector3d& b = skeleton.node(pairs[e].second).position;
    crown.push_back(a.head<2>());
    crown.push_back(b.head<2>());
    foliage.leaf_bearing_length += (b - a).norm();
  }
  foliage.crown_projected_area = convex_hull_area(std::move(crown));
  foliage.leaf_area = leaf_area_index * foliage.crown_projected_area;
  if (foliage.leaf_area > 0.0 && foliage.leaf_bearing_length > 0.0) {
    const double per_metre = foliage.leaf_area / foliage.leaf_bearing_length;
    for (std::size_t e = 0; e < pairs.size(); ++e) {
      if (foliage.leaf_bearing[e]) foliage.leaf_area_per_metre[e] = per_metre;
    }
  } else {
    foliage.leaf_area = 0.0;  // nowhere to put leaves
  }
  return foliage;
}

}  // namespace fw::trees
