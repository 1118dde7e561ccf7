// The leaves of one species, generated on its leaf-bearing elements (docs/leaves.md, "A leaf" and
// "Generation"): as many as the foliage's one-sided leaf area holds leaves of the species' size (times
// LeafSettings::fraction), each anchored on an element, deterministic from LeafSettings::seed.
//
//   const auto foliage = fw::trees::Foliage::of(skeleton, 3.0);
//   fw::trees::SpeciesLeaves leaves = fw::trees::SpeciesLeaves::generate(skeleton, foliage, settings);
//   leaves.count();                          // N = round(fraction x foliage.leaf_area / settings.area)
//   leaves.leaf(k).anchor;                   // m, skeleton frame
//
// Shapes and units: every vector is in the species' skeleton frame (a tree at scale 1), m; directions unit.
#pragma once

#include <Eigen/Core>
#include <array>
#include <limits>
#include <vector>

#include "trees/Foliage.hpp"
#include "trees/LeafSettings.hpp"
#include "trees/Skeleton.hpp"

namespace fw::trees {

struct RestLeaf {
  int element = 0;          ///< index into skeleton.elements()
  double along = 0.0;       ///< t in [0, 1] from the element's parent node to its child node
  Eigen::Vector3d anchor;   ///< the petiole's point on the element, m
  Eigen::Vector3d petiole;  ///< unit, anchor -> blade centre
  Eigen::Vector3d hinge;    ///< unit, the flutter axis (the element's direction, perpendicular to petiole)
  Eigen::Vector3d normal;   ///< unit, the blade's normal at rest (n.z >= 0)
  double strength = 0.0;    ///< petiole strength S, N
  std::array<double, 3> phase{};      ///< phi_H, phi_V, phi_R of the stochastic model, rad
  std::array<double, 3> frequency{};  ///< f_H, f_V, f_R, Hz (the species' frequency +-20%)
  Eigen::Vector3d tumble_axis;        ///< unit, horizontal: the axis the blade turns about in flight
};

class SpeciesLeaves {
 public:
  SpeciesLeaves() = default;  ///< no leaves

  /// The most leaves a species may have: count() is an int.
  static constexpr double kMaxCount = std::numeric_limits<int>::max();

  /// Throws std::invalid_argument("SpeciesLeaves: ...") when the settings are invalid
  /// (LeafSettings::validate), the foliage does not belong to the skeleton (element count), or
  /// planned_count is above kMaxCount (or not a number): a caller that can name the key checks first.
  static SpeciesLeaves generate(const Skeleton& skeleton, const Foliage& foliage,
                                const LeafSettings& settings);
  /// The leaves generate() makes, counted but not drawn: count(), the settings and foliage_leaf_count() as
  /// generate()'s, leaves() empty. What a plan for `check` holds (host::PlanFor): a tree may carry up to
  /// 2^31 leaves, which would take minutes and hundreds of gigabytes to draw. Throws as generate().
  static SpeciesLeaves counted(const Skeleton& skeleton, const Foliage& foliage,
                               const LeafSettings& settings);
  /// The count generate() makes, before rounding: fraction x foliage.leaf_area / area; 0 without leaves.
  /// May be huge or infinite for a foliage no tree has: what generate() refuses.
  static double planned_count(const Foliage& foliage, const LeafSettings& settings);

  const LeafSettings& settings() const { return settings_; }
  /// The leaves generate() makes (of a counted() species too, whose leaves() are empty).
  int count() const { return count_; }
  const RestLeaf& leaf(int k) const { return leaves_.at(std::size_t(k)); }
  const std::vector<RestLeaf>& leaves() const { return leaves_; }

  double side() const;   ///< l = sqrt(a), m
  double lever() const;  ///< r = l_p + l / 2 from the anchor to the blade's centre, m
  double mass() const;   ///< m = sigma a, kg
  /// Expected count before rounding and thinning: foliage.leaf_area / settings.area (the real leaves).
  double foliage_leaf_count() const { return foliage_leaf_count_; }

 private:
  LeafSettings settings_;
  std::vector<RestLeaf> leaves_;
  int count_ = 0;
  double foliage_leaf_count_ = 0.0;
};

}  // namespace fw::trees
