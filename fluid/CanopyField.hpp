// The trees' drag on the wind: frontal area density a(x) (1/m) and drag density k(x) = sum_j Cd_j a_j (1/m)
// per cell of the wind grid, rasterised from tree skeletons in world coordinates.
//
//   fw::fluid::CanopyField canopy(spec);
//   auto world = skeleton.transformed(yaw, position, scale);           // a trees::Skeleton, metres
//   auto r = canopy.add_tree(world, 1.2, 3.5, 0.2);                    // Cd branch, LAI, Cd leaf
//   if (r.dropped_area > 0) ...                                        // parts outside the domain
//   wind.set_canopy(canopy.drag_density());                            // host::WindGrid, F = -k |u| u
//   vtk.add("canopy_density", canopy.frontal_area_density());
//
// Woody area: element e (a truncated cone from node radius r0 to r1, length L) has frontal area
// D x L = 2 (r0 + r1) / 2 x L, the projected area seen across its axis. The element is clipped exactly at
// every cell boundary it crosses; each piece adds its own mean diameter times its length, divided by h^3,
// to the cell it lies in. Parts outside the domain are dropped and reported (CanopyTreeReport).
//
// Leaves (the rule chosen here): a tree carries one-sided leaf area A_leaf = LAI x A_crown, where A_crown is
// the area of the convex hull, in the horizontal plane, of the end points of its leaf-bearing elements.
// Leaf-bearing elements are all elements off the main stem (branch order >= 1; the stem follows the
// thickest child at each fork), or, for an unbranched pole, its terminal element. A_leaf is shared among
// the leaf-bearing elements in proportion to their length and, within each, to the clipped length in each
// cell: foliage density follows the density of twigs, and leaves land only in cells the crown's branches
// touch. A crown with no horizontal extent (a vertical pole) gets A_crown = 0, hence no leaves.
//
// Leaf area counts as frontal area (a = one-sided leaf area density, the usual canopy-flow convention), so
// a = (woody + leaf area in the cell) / h^3 and k = (Cd_branch woody + Cd_leaf leaf area) / h^3.
// Sums are kept in double; the float fields are converted on request.
#pragma once

#include <array>
#include <cstddef>
#include <span>
#include <utility>
#include <vector>

#include "fluid/GridSpec.hpp"

namespace fw::fluid {

/// One skeleton element in world coordinates (m): a truncated cone from `start` to `end`.
struct CanopyElement {
  std::array<double, 3> start{}, end{};
  double start_radius = 0.0, end_radius = 0.0;  // m, >= 0
  bool leaf_bearing = false;                    // carries a share of the tree's leaf area
};

/// What one add_tree / add_elements put on the grid, m^2.
struct CanopyTreeReport {
  double woody_area = 0.0;            // sum of D x L over all elements
  double leaf_area = 0.0;             // LAI x crown_projected_area
  double crown_projected_area = 0.0;  // horizontal convex hull of the leaf-bearing elements
  double dropped_area = 0.0;          // the part of woody + leaf area outside the domain
  bool outside = false;               // nothing of the tree landed in the domain
};

class CanopyField {
 public:
  /// All cells empty. Throws std::invalid_argument("CanopyField: ...") for an invalid spec.
  explicit CanopyField(const GridSpec& spec);

  /// Adds one tree from a skeleton already in world coordinates (a trees::Skeleton, e.g.
  /// skeleton.transformed(R, position, scale)); a template only so that fluid/ does not depend on trees/.
  /// Throws std::invalid_argument("CanopyField: ...") for an empty skeleton, or a negative or non-finite
  /// drag coefficient or leaf area index.
  template <class Skeleton>
  CanopyTreeReport add_tree(const Skeleton& world_skeleton, double branch_drag_coefficient,
                            double leaf_area_index, double leaf_drag_coefficient) {
    return add_elements(elements_of(world_skeleton), branch_drag_coefficient, leaf_area_index,
                        leaf_drag_coefficient);
  }

  /// The same for a tree given as elements (the skeleton's, or any other source).
  CanopyTreeReport add_elements(std::span<const CanopyElement> elements, double branch_drag_coefficient,
                                double leaf_area_index, double leaf_drag_coefficient);

  /// The elements of a skeleton with the leaf-bearing rule applied (see the header comment).
  template <class Skeleton>
  static std::vector<CanopyElement> elements_of(const Skeleton& skeleton);

  const GridSpec& spec() const { return spec_; }
  /// k = sum_j Cd_j a_j per cell, 1/m, x-fastest like GridSpec: what host::WindGrid::set_canopy takes.
  std::vector<float> drag_density() const { return to_float(drag_); }
  /// a per cell, 1/m (the ParaView field `canopy_density`).
  std::vector<float> frontal_area_density() const { return to_float(area_); }

  /// Woody plus leaf area of every tree added, inside the domain or not, m^2.
  double total_frontal_area() const { return total_area_; }
  /// The part of total_frontal_area() that fell outside the domain, m^2.
  double dropped_frontal_area() const { return dropped_area_; }
  /// Sum over cells of a h^3 (double precision), m^2: total_frontal_area() - dropped_frontal_area().
  double frontal_area_in_domain() const;
  int tree_count() const { return trees_; }
  /// Trees of which nothing landed in the domain.
  int trees_outside() const { return trees_outside_; }

 private:
  // Adds the element's area to the cells it crosses (area per metre of element runs linearly from a0 at its
  // start to a1 at its end; m^2/m), and cd times it to the drag. Returns {area inside, area outside}, m^2.
  std::pair<double, double> rasterise(const CanopyElement& e, double a0, double a1, double cd);
  static std::vector<float> to_float(const std::vector<double>& v);

  GridSpec spec_;
  std::vector<double> area_, drag_;  // per cell: m^2 / h^3 = 1/m
  double total_area_ = 0.0, dropped_area_ = 0.0;
  int trees_ = 0, trees_outside_ = 0;
};

template <class Skeleton>
std::vector<CanopyElement> CanopyField::elements_of(const Skeleton& skeleton) {
  const auto& nodes = skeleton.nodes();
  const auto& pairs = skeleton.elements();
  const std::size_t n = nodes.size();
  // The main stem continues into the thickest child at each fork (ties: the lowest index); every other
  // child starts a branch one order higher.
  std::vector<int> main_child(n, -1), child_count(n, 0);
  for (const auto& [parent, child] : pairs) {
    ++child_count[std::size_t(parent)];
    int& best = main_child[std::size_t(parent)];
    if (best < 0 || nodes[std::size_t(child)].radius > nodes[std::size_t(best)].radius) best = child;
  }
  std::vector<int> order(n, 0);  // pairs are breadth-first: a parent's order is known before its children
  for (const auto& [parent, child] : pairs)
    order[std::size_t(child)] =
        order[std::size_t(parent)] + (main_child[std::size_t(parent)] == child ? 0 : 1);

  std::vector<CanopyElement> out;
  out.reserve(pairs.size());
  bool any_branch = false;
  for (const auto& [parent, child] : pairs) {
    const auto& a = nodes[std::size_t(parent)];
    const auto& b = nodes[std::size_t(child)];
    CanopyElement e;
    e.start = {a.position.x(), a.position.y(), a.position.z()};
    e.end = {b.position.x(), b.position.y(), b.position.z()};
    e.start_radius = a.radius;
    e.end_radius = b.radius;
    e.leaf_bearing = order[std::size_t(child)] >= 1;
    any_branch = any_branch || e.leaf_bearing;
    out.push_back(e);
  }
  if (!any_branch)  // an unbranched pole: its top element carries the leaves
    for (std::size_t m = 0; m < pairs.size(); ++m)
      out[m].leaf_bearing = child_count[std::size_t(pairs[m].second)] == 0;
  return out;
}

}  // namespace fw::fluid
