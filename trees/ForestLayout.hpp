// Where the trees of a stand stand: positions, yaws and scales for a region of ground, reproducible from a
// seed.
//
//   fw::trees::StandSpec stand;
//   stand.species = 0;
//   stand.min = {60, 20};  stand.max = {260, 220};    // m, horizontal region (x east, y north)
//   stand.layout = fw::trees::StandLayout::poisson;    // or grid
//   stand.spacing = 6.0;                               // m
//   stand.scale_min = 0.85;  stand.scale_max = 1.15;
//   stand.seed = 11;
//   std::vector<fw::trees::PlacedTree> trees = fw::trees::place_stand(stand);
//
// Layouts:
//   poisson: Poisson-disk sampling (Bridson's dart throwing around active samples, 30 tries each): no two
//            trees closer than `spacing`, and no gap much larger than 2 * spacing, as in a natural stand.
//   grid:    rows and columns `spacing` apart, centred in the region (a plantation).
// Every tree gets a yaw uniform in [0, 2 pi) and a scale uniform in [scale_min, scale_max], so that a stand
// of one species does not look cloned. The same spec gives the same trees on any platform: raw
// std::mt19937_64 bits mapped to [0, 1) by unit_interval (trees/LSystem.hpp), never the standard library's
// distributions.
#pragma once

#include <Eigen/Core>

#include <cstdint>
#include <vector>

namespace fw::trees {

enum class StandLayout { poisson, grid };

struct StandSpec {
  int species = 0;                                ///< index into the forest's species
  Eigen::Vector2d min = Eigen::Vector2d::Zero();  ///< m, south-west corner of the region
  Eigen::Vector2d max = Eigen::Vector2d::Zero();  ///< m, north-east corner
  StandLayout layout = StandLayout::poisson;
  double spacing = 5.0;  ///< m, minimum (poisson) or exact (grid) distance between neighbours, > 0
  double scale_min = 1.0;
  double scale_max = 1.0;
  std::uint64_t seed = 0;

  /// The region's area, m^2: the ground a stand's density counts per (trees/StandDensity.hpp).
  double ground_area() const { return (max - min).prod(); }

  /// Throws std::invalid_argument("StandSpec: ...") for an empty or inverted region, spacing <= 0,
  /// 0 < scale_min <= scale_max violated, non-finite values, or a region needing more than kMaxTrees trees.
  void validate() const;
};

struct PlacedTree {
  int species = 0;
  Eigen::Vector2d position = Eigen::Vector2d::Zero();  ///< m, ground position of the root
  double yaw_rad = 0.0;                                ///< counter-clockwise about +z
  double scale = 1.0;                                  ///< uniform scale of the species' skeleton
};

/// Most trees one stand may hold (a guard against a spacing typed in the wrong unit).
inline constexpr int kMaxTreesPerStand = 1'000'000;

/// The trees of one stand, in a deterministic order. See the header comment.
std::vector<PlacedTree> place_stand(const StandSpec& stand);

}  // namespace fw::trees
