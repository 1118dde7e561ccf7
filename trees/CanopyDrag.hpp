// The trees' side of the two-way coupling (docs/design.md, "Coupling"): a forest instance rasterised into the
// canopy field with the same drag convention, foliage and element diameters as its wind basis, so that the
// force the air loses in a cell equals the force applied to the tree's elements in that cell.
//
//   fw::fluid::CanopyField canopy(spec);
//   const fw::trees::ForestCanopy trees(forest);
//   for (int k = 0; k < forest.instance_count(); ++k) trees.add(canopy, k);
//   wind.set_canopy(canopy.drag_density());     // host::WindGrid: u <- u / (1 + dt k |u|)
//
// Convention (trees/WindBasis.hpp): the drag on an area A in wind u is F = 1/2 rho_air C_D A |u| u. Element
// e of the world skeleton (species skeleton transformed by the instance's rotation, position and scale)
// becomes one fluid::CanopyElement with
//   frontal area per metre  alpha_e = D_e + lambda_e                (m^2/m)
//   drag area per metre     beta_e  = C_Db D_e + C_Df lambda_e      (m^2/m)
// with D_e = r_a + r_b (constant along the element, as in the stiffness and the wind basis), lambda_e the
// element's one-sided leaf area per metre (trees/Foliage.hpp: the crown hull scales as s^2, lambda_e as s,
// consistent with the basis' similarity law p -> s^1/2 p), and C_Db, C_Df,
// LAI from the species' settings().wind. The canopy field then holds a = sum alpha l / h^3 (woody plus
// one-sided leaf area density, 1/m) and k = 1/2 sum beta l / h^3 (1/m), so the air in a cell loses
// rho_air k |u| u h^3 = sum over the pieces in it of 1/2 rho_air beta_e l |u| u, which is the load
// A_e |u| u per metre that the wind basis integrates (without branch_normal_drag; with it the balance holds
// for the foliage and for wind normal to the branches only). rho_air is not stored: the wind kernels
// decelerate per unit mass.
#pragma once

#include <vector>

#include "fluid/CanopyField.hpp"
#include "trees/Forest.hpp"
#include "trees/Skeleton.hpp"
#include "trees/WindBasis.hpp"

namespace fw::trees {

/// The canopy elements of a skeleton (already in world coordinates) under the wind settings' drag
/// coefficients and leaf area index (header comment), one per element in skeleton.elements() order.
/// Throws std::invalid_argument("CanopyDrag: ...") for invalid settings or a skeleton without elements.
std::vector<fluid::CanopyElement> canopy_elements(const Skeleton& world_skeleton,
                                                  const WindBasisSettings& settings);

/// A forest's trees as canopy elements. Each species' elements are computed once, in its own frame, and each
/// instance's are theirs carried by its similarity: ends at x + s R p, D_e and lambda_e times s, the woody,
/// leaf and crown areas times s^2 (Foliage is similar under a scale and a turn about +z). Per instance, a
/// convex hull of its crown was over half of planning 100,000 trees (docs/gis.md).
class ForestCanopy {
 public:
  /// Keeps a reference to `forest`, which must outlive it. Throws std::invalid_argument("CanopyDrag: ...")
  /// for a species with invalid drag settings or without elements.
  explicit ForestCanopy(const Forest& forest);

  /// Instance k's elements, one per element of its species' skeleton.elements(), world coordinates. Throws
  /// std::invalid_argument("CanopyDrag: ...") for an index out of range.
  std::vector<fluid::CanopyElement> elements(int instance) const;
  /// Rasterises instance k into the canopy field (canopy.add_elements of elements(k)) with the report's
  /// woody_area, leaf_area and crown_projected_area filled in (m^2). Throws as elements().
  fluid::CanopyTreeReport add(fluid::CanopyField& canopy, int instance) const;

 private:
  struct SpeciesElements {
    std::vector<fluid::CanopyElement> elements;                            // species frame, scale 1
    double woody_area = 0.0, leaf_area = 0.0, crown_projected_area = 0.0;  // m^2 at scale 1
  };
  const Forest* forest_;
  std::vector<SpeciesElements> species_;
};

/// The world box of instance k's skeleton nodes (m): where add_to_canopy puts its drag, within a cell of it.
Eigen::AlignedBox3d instance_reach(const Forest& forest, int instance);
/// The cells instance k's drag can reach (fluid::CellBox::around its instance_reach).
fluid::CellBox instance_cells(const fluid::GridSpec& spec, const Forest& forest, int instance);
/// fluid::CellBox::around a box in metres.
fluid::CellBox cells_around(const fluid::GridSpec& spec, const Eigen::AlignedBox3d& reach);

}  // namespace fw::trees
