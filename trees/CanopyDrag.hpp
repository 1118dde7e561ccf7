// The trees' side of the two-way coupling (docs/design.md, "Coupling"): a forest instance rasterised into the
// canopy field with the same drag convention, foliage and element diameters as its wind basis, so that the
// force the air loses in a cell equals the force applied to the tree's elements in that cell.
//
//   fw::fluid::CanopyField canopy(spec);
//   for (int k = 0; k < forest.instance_count(); ++k) fw::trees::add_to_canopy(canopy, forest, k);
//   wind.set_canopy(canopy.drag_density());     // host::WindGrid: u <- u / (1 + dt k |u|)
//
// Convention (trees/WindBasis.hpp): the drag on an area A in wind u is F = 1/2 rho_air C_D A |u| u. Element
// e of the world skeleton (species skeleton transformed by the instance's rotation, position and scale)
// becomes one fluid::CanopyElement with
//   frontal area per metre  alpha_e = D_e + lambda_e                (m^2/m)
//   drag area per metre     beta_e  = C_Db D_e + C_Df lambda_e      (m^2/m)
// with D_e = r_a + r_b (constant along the element, as in the stiffness and the wind basis), lambda_e the
// element's one-sided leaf area per metre (trees/Foliage.hpp, computed on the world skeleton: the crown hull
// scales as s^2, lambda_e as s, consistent with the basis' similarity law p -> s^1/2 p), and C_Db, C_Df,
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

/// Rasterises instance k of the forest (world skeleton = species skeleton transformed by the instance's
/// rotation, position, scale) into the canopy field with the species' settings().wind coefficients. The
/// report's woody_area, leaf_area and crown_projected_area are filled in (m^2). Throws
/// std::invalid_argument("CanopyDrag: ...") for an instance index out of range.
fluid::CanopyTreeReport add_to_canopy(fluid::CanopyField& canopy, const Forest& forest, int instance);
/// The elements add_to_canopy adds for instance k, the same values: canopy.add_elements of them is
/// add_to_canopy's field, bit for bit. Throws as add_to_canopy.
std::vector<fluid::CanopyElement> instance_canopy_elements(const Forest& forest, int instance);

/// The world box of instance k's skeleton nodes (m): where add_to_canopy puts its drag, within a cell of it.
Eigen::AlignedBox3d instance_reach(const Forest& forest, int instance);
/// The cells instance k's drag can reach (fluid::CellBox::around its instance_reach).
fluid::CellBox instance_cells(const fluid::GridSpec& spec, const Forest& forest, int instance);
/// fluid::CellBox::around a box in metres.
fluid::CellBox cells_around(const fluid::GridSpec& spec, const Eigen::AlignedBox3d& reach);

}  // namespace fw::trees
