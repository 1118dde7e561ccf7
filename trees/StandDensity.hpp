// How densely a stand's trees stand, in the figures foresters and canopy-flow studies give (docs/trees.md,
// "Stand density"), and the crown leaf area index that gives a stand the leaf area index a file asks for.
//
//   fw::trees::StandDensity density;                 // filled by the planner
//   (host/app/plan/CouplingPlan.cpp) density.ground_area = stand.ground_area();       // m^2, the stand's
//   region density.leaf_area = ...;                         // m^2, one-sided, of the stand's trees' whole
//   crowns density.leaf_area_index();                       // m^2 of leaf per m^2 of ground
//   density.forest_like();                           // within the range of measured forests
//   double crown = fw::trees::crown_leaf_area_index(4.0, stand.ground_area(), crown_area, placed);
//
// LAI = the one-sided leaf area of the stand's trees (every crown whole, also where it hangs over the
// region's edge) per m^2 of the stand's region. FAI = the canopy's frontal area (wood and leaves of whatever
// tree stands there) in the grid columns whose centres lie in the region, per m^2 of those columns' ground:
// the frontal area density a (1/m) integrated up each column and averaged over the columns.
#pragma once

#include <span>

#include "trees/ForestLayout.hpp"

namespace fw::trees {

struct StandDensity {
  /// The leaf area index of forests as measured in the field, about 0.3 to 12 (m^2/m^2). Asner, Scurlock &
  /// Hicke (2003, Global Ecology and Biogeography 12: 191-205) gathered 1008 field estimates from 15 biomes;
  /// their biome means run from 1.3 +- 0.9 (deserts) to 8.7 +- 4.3 (tree plantations), so one standard
  /// deviation past the lowest and the highest mean is about 0.4 and 13. A stand outside the range is not a
  /// forest a forester would recognise, and `forestwind check` warns.
  static constexpr double kForestLeafAreaIndexLow = 0.3;
  static constexpr double kForestLeafAreaIndexHigh = 12.0;
  /// The largest leaf area index a stand may be given (forest.stands[].leaf_area_index): 18, the largest
  /// value of the same synthesis left after its outlier analysis. A larger figure is no forest but a slip
  /// (a leaf area per tree instead of per m^2 of ground, say).
  static constexpr double kMaxLeafAreaIndex = 18.0;

  int trees = 0;
  double ground_area = 0.0;          ///< m^2, the stand's region
  double leaf_area = 0.0;            ///< m^2, one-sided, of the stand's trees (whole crowns)
  int columns = 0;                   ///< grid columns whose centre lies in the region
  double column_ground_area = 0.0;   ///< m^2, those columns' (columns x h^2)
  double column_frontal_area = 0.0;  ///< m^2, the canopy's frontal area (wood and leaves) in those columns

  /// LAI, m^2 of leaf per m^2 of ground: leaf_area / ground_area.
  double leaf_area_index() const { return ground_area > 0.0 ? leaf_area / ground_area : 0.0; }
  /// FAI, m^2 of frontal area per m^2 of ground: column_frontal_area / column_ground_area (0 without a
  /// column).
  double frontal_area_index() const {
    return column_ground_area > 0.0 ? column_frontal_area / column_ground_area : 0.0;
  }
  /// Whether the LAI lies in [kForestLeafAreaIndexLow, kForestLeafAreaIndexHigh].
  bool forest_like() const;
};

/// The crown leaf area index (trees/Foliage.hpp: one-sided leaf area per crown hull area) at which trees of a
/// species whose crown hull at scale 1 is `crown_area` (m^2), placed as `trees`, give the stand the leaf area
/// index `stand_lai` on `ground_area` (m^2): stand_lai ground_area / (crown_area sum of s^2), since a tree
/// scaled by s has s^2 the crown hull. Throws std::invalid_argument("StandDensity: ...") unless stand_lai is
/// in (0, StandDensity::kMaxLeafAreaIndex] and ground_area > 0, for no trees, and for a crown without
/// horizontal extent (crown_area 0: a pole carries no leaves).
double crown_leaf_area_index(double stand_lai, double ground_area, double crown_area,
                             std::span<const PlacedTree> trees);

}  // namespace fw::trees
