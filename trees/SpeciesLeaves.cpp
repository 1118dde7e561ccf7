#include "trees/SpeciesLeaves.hpp"

#include <fmt/format.h>

#include <Eigen/Geometry>
#include <algorithm>
#include <cmath>
#include <numbers>
#include <random>
#include <stdexcept>

#include "trees/LSystem.hpp"  // unit_interval: the portable mapping of 64 random bits onto [0, 1)

namespace fw::trees {
namespace {

constexpr double kPi = std::numbers::pi;
constexpr double kMaxTiltRad = 45.0 * kPi / 180.0;   // petiole tilt up, [0, 45] degrees
constexpr double kMaxTwistRad = 30.0 * kPi / 180.0;  // blade twist about the petiole, [-30, 30] degrees
constexpr double kFrequencyJitter = 0.2;             // per-leaf +-20% about leaves.frequency
constexpr double kVerticalElementTolerance = 1e-12;  // |projection of +z| below this: a vertical element

// The one random stream of a species: std::mt19937_64 bits through unit_interval, never a standard library
// distribution (their outputs differ between implementations).
class Draws {
 public:
  explicit Draws(std::uint64_t seed) : engine_(seed) {}
  double uniform() { return unit_interval(engine_()); }
  double uniform(double lo, double hi) { return lo + (hi - lo) * uniform(); }
  /// A standard normal number by Box-Muller from two uniform draws (1 - u lies in (0, 1], so the log is
  /// finite).
  double normal() {
    const double radius = std::sqrt(-2.0 * std::log(1.0 - uniform()));
    return radius * std::cos(2.0 * kPi * uniform());
  }

 private:
  std::mt19937_64 engine_;
};

// Cumulative lengths of the leaf-bearing elements, so that a leaf picks one with probability proportional
// to its length (the foliage's area per metre is the same on all of them).
struct BearingElements {
  std::vector<int> element;
  std::vector<double> cumulative_length;

  BearingElements(const Skeleton& skeleton, const Foliage& foliage) {
    const auto& pairs = skeleton.elements();
    double total = 0.0;
    for (std::size_t e = 0; e < pairs.size(); ++e) {
      if (!foliage.leaf_bearing[e]) continue;
      total += (skeleton.node(pairs[e].second).position - skeleton.node(pairs[e].first).position).norm();
      element.push_back(int(e));
      cumulative_length.push_back(total);
    }
  }
  double total() const { return cumulative_length.empty() ? 0.0 : cumulative_length.back(); }
  int pick(double u) const {
    const auto it = std::upper_bound(cumulative_length.begin(), cumulative_length.end(), u * total());
    return element[std::size_t(
        std::min<std::ptrdiff_t>(it - cumulative_length.begin(), std::ptrdiff_t(element.size()) - 1))];
  }
};

Eigen::Vector3d rotate(const Eigen::Vector3d& v, const Eigen::Vector3d& axis, double angle) {
  return Eigen::AngleAxisd(angle, axis) * v;
}

// The petiole: perpendicular to the element d at azimuth phi in [-pi, pi) about it, measured from the
// plane's highest direction (+z made perpendicular to d), then turned about d towards that direction by the
// tilt, stopping there. Turning about d keeps it perpendicular to the element; on a vertical element the
// plane has no highest direction and the petiole stays horizontal.
Eigen::Vector3d petiole_direction(const Eigen::Vector3d& d, double phi, double tilt) {
  const Eigen::Vector3d up = Eigen::Vector3d::UnitZ() - d.z() * d;
  const bool vertical = up.norm() < kVerticalElementTolerance;
  const Eigen::Vector3d e1 =
      vertical ? Eigen::Vector3d(d.unitOrthogonal()) : Eigen::Vector3d(up.normalized());
  const Eigen::Vector3d e2 = d.cross(e1);
  const double azimuth = vertical ? phi : phi - std::copysign(std::min(tilt, std::abs(phi)), phi);
  return (std::cos(azimuth) * e1 + std::sin(azimuth) * e2).normalized();
}

// One leaf from 14 draws, in this order: element, t, azimuth, tilt, twist, strength (2), phases (3),
// frequencies (3), tumble axis azimuth.
RestLeaf draw_leaf(const Skeleton& skeleton, const BearingElements& bearing, const LeafSettings& settings,
                   Draws& draws) {
  RestLeaf leaf;
  leaf.element = bearing.pick(draws.uniform());
  leaf.along = draws.uniform();
  const auto [parent, child] = skeleton.elements()[std::size_t(leaf.element)];
  const Eigen::Vector3d a = skeleton.node(parent).position, b = skeleton.node(child).position;
  const Eigen::Vector3d d = (b - a).normalized();
  leaf.anchor = a + leaf.along * (b - a);

  const double phi = draws.uniform(-kPi, kPi);
  const double tilt = draws.uniform(0.0, kMaxTiltRad);
  leaf.petiole = petiole_direction(d, phi, tilt);
  leaf.hinge = (d - d.dot(leaf.petiole) * leaf.petiole).normalized();
  leaf.normal =
      rotate(leaf.petiole.cross(leaf.hinge), leaf.petiole, draws.uniform(-kMaxTwistRad, kMaxTwistRad));
  if (leaf.normal.z() < 0.0) leaf.normal = -leaf.normal;

  // Log-normal: median petiole_strength, log-standard deviation strength_spread.
  leaf.strength = settings.petiole_strength * std::exp(settings.strength_spread * draws.normal());
  for (double& phase : leaf.phase) phase = draws.uniform(0.0, 2.0 * kPi);
  for (double& f : leaf.frequency)
    f = settings.frequency * (1.0 + draws.uniform(-kFrequencyJitter, kFrequencyJitter));
  const double psi = draws.uniform(0.0, 2.0 * kPi);
  leaf.tumble_axis = Eigen::Vector3d(std::cos(psi), std::sin(psi), 0.0);
  return leaf;
}

}  // namespace

SpeciesLeaves SpeciesLeaves::generate(const Skeleton& skeleton, const Foliage& foliage,
                                      const LeafSettings& settings) {
  SpeciesLeaves out = counted(skeleton, foliage, settings);
  if (out.count_ == 0) return out;
  const BearingElements bearing(skeleton, foliage);
  Draws draws(settings.seed);
  out.leaves_.reserve(std::size_t(out.count_));
  for (int k = 0; k < out.count_; ++k) out.leaves_.push_back(draw_leaf(skeleton, bearing, settings, draws));
  return out;
}

SpeciesLeaves SpeciesLeaves::counted(const Skeleton& skeleton, const Foliage& foliage,
                                     const LeafSettings& settings) {
  try {
    settings.validate();
  } catch (const std::invalid_argument& e) {
    throw std::invalid_argument(fmt::format("SpeciesLeaves: {}", e.what()));
  }
  if (foliage.leaf_bearing.size() != skeleton.elements().size()) {
    throw std::invalid_argument(fmt::format("SpeciesLeaves: the foliage has {} elements, the skeleton {}",
                                            foliage.leaf_bearing.size(), skeleton.elements().size()));
  }
  SpeciesLeaves out;
  out.settings_ = settings;
  const BearingElements bearing(skeleton, foliage);
  if (!settings.has_leaves() || foliage.leaf_area <= 0.0 || bearing.total() <= 0.0) return out;

  const double planned = planned_count(foliage, settings);
  if (!(planned <= kMaxCount))  // NaN too: llround of a count past long long would be undefined
    throw std::invalid_argument(fmt::format(
        "SpeciesLeaves: {:.3g} leaves, more than the {:.0f} a species holds", planned, kMaxCount));
  out.foliage_leaf_count_ = foliage.leaf_area / settings.area;
  out.count_ = int(std::llround(planned));
  return out;
}

double SpeciesLeaves::planned_count(const Foliage& foliage, const LeafSettings& settings) {
  if (!settings.has_leaves() || !(foliage.leaf_area > 0.0)) return 0.0;
  return settings.fraction * (foliage.leaf_area / settings.area);
}

double SpeciesLeaves::side() const {
  return std::sqrt(settings_.area);
}

double SpeciesLeaves::lever() const {
  return (kPetioleLengthPerSide + 0.5) * side();
}

double SpeciesLeaves::mass() const {
  return settings_.mass_per_area * settings_.area;
}

}  // namespace fw::trees
