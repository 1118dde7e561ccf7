// Where a tree's leaves are and how much of them (docs/design.md, "Coupling"): the one definition of the
// leaf-bearing rule and of the foliage distribution, used by the wind basis (trees/WindBasis: leaves bend the
// tree) and by the canopy rasterisation (trees/CanopyDrag: leaves slow the air), so both sides see the same
// leaf area on the same elements.
//
//   auto foliage = fw::trees::Foliage::of(skeleton, 3.0);        // LAI 3
//   foliage.leaf_area;                                           // m^2, one-sided
//   foliage.leaf_area_per_metre[e];                              // lambda_e of element e, m^2/m
//
// Leaf-bearing rule: the main stem starts at the root and continues, at every fork, into the thickest child
// (ties: the lowest node index); every other child starts a branch one order higher. Elements of branch
// order >= 1 bear leaves. An unbranched pole (no element off the main stem) bears its leaves on its terminal
// element.
//
// Distribution: the tree carries one-sided leaf area A_leaf = LAI x A_crown, with A_crown the area of the
// convex hull, in the horizontal plane, of the end points of the leaf-bearing elements. A_leaf is shared
// among the leaf-bearing elements per metre of their length: lambda_e = A_leaf / (sum of their lengths),
// constant along each, 0 on the other elements. Foliage density so follows the density of twigs, and leaves
// sit only where the crown's branches are. A crown with no horizontal extent (a vertical pole) has
// A_crown = 0, hence no leaves.
//
// Similarity: for skeleton.transformed(R, x, s) (R about +z) A_crown and A_leaf scale as s^2 and lambda_e
// as s, like the diameters D_e; so the wind basis' similarity law p -> s^1/2 p holds with foliage too.
// Units: m, m^2, m^2/m.
#pragma once

#include <vector>

#include "trees/Skeleton.hpp"

namespace fw::trees {

/// Leaf-bearing flag per element of `skeleton`, in skeleton.elements() order (rule above). A single-node
/// skeleton has no elements and gives an empty vector.
std::vector<bool> leaf_bearing_elements(const Skeleton& skeleton);

/// Area of the convex hull of points in the plane, m^2 (0 for fewer than three non-collinear points).
double convex_hull_area(std::vector<Eigen::Vector2d> points);

struct Foliage {
  std::vector<bool> leaf_bearing;           ///< per element, skeleton.elements() order
  std::vector<double> leaf_area_per_metre;  ///< lambda_e per element, m^2/m, 0 where not leaf-bearing
  double crown_projected_area = 0.0;        ///< A_crown, m^2
  double leaf_area = 0.0;                   ///< A_leaf = LAI x A_crown, m^2 (one-sided)
  double leaf_bearing_length = 0.0;         ///< sum of the leaf-bearing elements' lengths, m

  /// The foliage of a tree with the given leaf area index (one-sided leaf area per crown hull area,
  /// dimensionless; 0 = no leaves). Throws std::invalid_argument("Foliage: ...") unless it is finite and
  /// >= 0.
  static Foliage of(const Skeleton& skeleton, double leaf_area_index);
};

}  // namespace fw::trees
