// How a failed tree falls (docs/damage.md, "What follows a failure"): the part above the break, or the
// whole uprooted tree, topples downwind about its pivot as a rigid rod and then lies on the ground. Frames
// draw it there; it takes no load meanwhile. kernels/tree_fall.cl moves the nodes on the device; this is the
// model and its CPU reference.
//
//   auto geometry = fw::trees::FallGeometry::of(forest.species_of(k));
//   fw::trees::FallPose pose = fw::trees::fall_pose(record, geometry, scale, time);   // a TreeDamageRecord
//   Eigen::MatrixX3d u = fw::trees::fall_displacements(forest, k, pose);        // world frame, m
//
// The fall: a rigid rod of length L pivoting on the ground, theta'' = (3 g / (2 L)) sin(theta) from
// theta = kFallStartAngle at rest (a tree bent by the storm at the moment it fails), integrated until it
// lies flat (theta = pi/2), where it stays. A 20 m tree takes about 3.6 s. The direction is the wind's at
// its top when it failed, horizontal (+x when that wind had no horizontal part). A broken top comes down
// as it turns, by the break's height times 1 - cos(theta), so that it lies on the ground beside its stump.
// Left out: the root plate's rotation before failure, the trunk sliding or bouncing, and a falling tree
// striking its neighbours (they neither feel it nor stop it); on a slope the tree turns to horizontal, not
// to the ground's slope.
#pragma once

#include <Eigen/Core>

#include <vector>

#include "trees/Forest.hpp"
#include "trees/TreeDamage.hpp"

namespace fw::trees {

/// The angle a failing tree leans at when it starts to fall, rad.
inline constexpr double kFallStartAngle = 0.1;
/// The step of the fall's integration, s (RK4: the angle to 1e-9 rad).
inline constexpr double kFallStep = 1e-3;

/// The angle (rad, from upright, kFallStartAngle to pi/2) of a rod of length `length` (m, > 0) `elapsed`
/// seconds after it started to fall (0 before).
double fall_angle(double elapsed, double length);
/// The time a rod of `length` takes to lie flat, s.
double fall_duration(double length);

/// A falling tree's pose: the node it turns about, the angle, the direction and the drop.
struct FallPose {
  int pivot = 0;                                         ///< node within the tree
  double angle = 0.0;                                    ///< rad from upright
  Eigen::Vector2d direction = Eigen::Vector2d::UnitX();  ///< horizontal unit vector it falls toward
  double drop = 0.0;                                     ///< m
};

/// What a species' fall needs to know of it, at scale 1.
struct FallGeometry {
  double height = 0.0;             ///< m, the skeleton's
  int root = 0;                    ///< the root node
  std::vector<int> section_nodes;  ///< the stem sections' nodes (StemLoads::sections())
  static FallGeometry of(const SpeciesBasis& species);
};

/// The pose at `time` of a tree of scale `scale` of the species `geometry` with the failure `record` (broken
/// or overturned; std::invalid_argument for a standing tree).
FallPose fall_pose(const TreeDamageRecord& record, const FallGeometry& geometry, double scale, double time);

/// Each node's preorder index and the index past its subtree (2 n ints): node k lies above node b when
/// tour(b) < tour(k) < end(b).
std::vector<int> skeleton_tour(const Skeleton& skeleton);

/// The displacement of every node of instance k (world frame, m; n x 3) in the pose: the nodes above the
/// pivot turned and dropped, the others at rest.
Eigen::MatrixX3d fall_displacements(const Forest& forest, int instance, const FallPose& pose);

}  // namespace fw::trees
