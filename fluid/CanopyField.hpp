// The trees' drag on the wind: frontal area density a(x) (1/m) and drag density k(x) (1/m) per cell of the
// wind grid, rasterised from line elements in world coordinates that each carry a frontal area and a drag
// area per metre. This class knows nothing of trees or leaves: trees/CanopyDrag.hpp turns a forest instance
// (wood and foliage, with the drag convention of trees/WindBasis.hpp) into elements.
//
//   fw::fluid::CanopyField canopy(spec);
//   auto r = fw::trees::ForestCanopy(forest).add(canopy, k);          // instance k of a trees::Forest
//   if (r.dropped_area > 0) ...                                        // parts outside the domain
//   wind.set_canopy(canopy.drag_density());                            // host::WindGrid, du/dt = -k |u| u
//   vtk.add("canopy_density", canopy.frontal_area_density());
//
// The drag convention (docs/design.md, "Coupling"): an area A (m^2) with drag coefficient C_D in wind u feels
// F = 1/2 rho_air C_D A |u| u. An element carries frontal area alpha (m^2 per metre of element) and drag
// area beta = sum over its parts of C_D x area (m^2/m), both constant along it. The element is clipped
// exactly at every cell boundary it crosses; a piece of length l in cell c adds
//   a_c += alpha l / h^3      and      k_c += 1/2 beta l / h^3,
// so that the air in cell c (mass rho_air h^3, slowed at du/dt = -k |u| u by the wind kernels) loses the
// force rho_air k_c |u| u h^3 = sum over pieces 1/2 rho_air beta l |u| u: exactly the drag the trees'
// elements in that cell receive. Parts outside the domain are dropped and reported (CanopyTreeReport).
// Sums are kept in double; the float fields are converted on request (float32: ~6e-8 relative rounding).
#pragma once

#include <array>
#include <span>
#include <vector>

#include "fluid/GridSpec.hpp"

namespace fw::fluid {

/// One line element in world coordinates (m) from `start` to `end`, with constant areas per metre.
struct CanopyElement {
  std::array<double, 3> start{}, end{};
  double frontal_area_per_metre = 0.0;  ///< alpha, m^2/m, >= 0 (e.g. D + leaf area per metre)
  double drag_area_per_metre = 0.0;     ///< beta = sum of C_D x area per metre, m^2/m, >= 0
};

/// What one add_elements (or trees::ForestCanopy::add) put on the grid, m^2.
struct CanopyTreeReport {
  double frontal_area = 0.0;       ///< sum of alpha L over the elements
  double drag_area = 0.0;          ///< sum of beta L over the elements (C_D x area)
  double dropped_area = 0.0;       ///< the part of frontal_area outside the domain
  double dropped_drag_area = 0.0;  ///< the part of drag_area outside the domain
  bool outside = false;            ///< nothing of the tree landed in the domain
  /// Filled by callers that know what the elements are (trees::ForestCanopy::add); add_elements leaves them
  /// 0.
  double woody_area = 0.0;            ///< sum of D x L over the elements
  double leaf_area = 0.0;             ///< one-sided leaf area, LAI x crown_projected_area
  double crown_projected_area = 0.0;  ///< horizontal convex hull of the leaf-bearing elements
};

/// The canopy over a horizontal rectangle: the grid columns whose centres lie in it, and the frontal area
/// in them. frontal_area / ground_area is the rectangle's frontal area index (m^2 per m^2 of ground): a
/// integrated up each column, averaged over the columns.
struct CanopyColumns {
  int columns = 0;            ///< columns whose centre (x, y) lies in the rectangle, edges included
  double ground_area = 0.0;   ///< columns x h^2, m^2
  double frontal_area = 0.0;  ///< sum over their cells of a h^3 (whatever element put it there), m^2
};

/// The cells of a grid a CanopyField stores: [first, first + count) along x, y and z.
struct CellBox {
  std::array<int, 3> first{0, 0, 0}, count{0, 0, 0};
  /// Every cell of `spec`.
  static CellBox whole(const GridSpec& spec) { return {{0, 0, 0}, {spec.nx, spec.ny, spec.nz}}; }
  /// The cells of `spec` within one cell of the box from `low` to `high` (m, world), clamped to the grid:
  /// every cell a segment inside it crosses. Empty (a zero count) when the box is empty (low > high on an
  /// axis) or lies outside the grid.
  static CellBox around(const GridSpec& spec, const std::array<double, 3>& low,
                        const std::array<double, 3>& high);
  /// Whether the two boxes share a cell.
  bool overlaps(const CellBox& other) const;
  std::size_t cell_count() const {
    return std::size_t(count[0]) * std::size_t(count[1]) * std::size_t(count[2]);
  }
};

class CanopyField {
 public:
  /// All cells empty. Throws std::invalid_argument("CanopyField: ...") for an invalid spec.
  explicit CanopyField(const GridSpec& spec) : CanopyField(spec, CellBox::whole(spec)) {}
  /// Stores the cells of `box` only (memory that follows the trees, not the grid: what `forestwind check`
  /// rasterises on), which must hold every cell inside the domain that an added element crosses
  /// (std::logic_error otherwise); the other cells are empty. Every figure below is the whole-grid field's,
  /// bit for bit. Throws std::invalid_argument for an invalid spec or a box that is not inside it.
  CanopyField(const GridSpec& spec, const CellBox& box);

  /// Adds one tree (or any set of elements). Throws std::invalid_argument("CanopyField: ...") for no
  /// elements, or an element with a non-finite position or an area per metre that is negative or not
  /// finite; nothing is added then.
  CanopyTreeReport add_elements(std::span<const CanopyElement> elements);

  const GridSpec& spec() const { return spec_; }
  /// k = 1/2 sum beta l / h^3 per cell of the whole grid (header comment), 1/m, x-fastest like GridSpec:
  /// what host::WindGrid::set_canopy takes.
  std::vector<float> drag_density() const { return to_float(drag_); }
  /// drag_density() of one cell of the box (std::out_of_range for a cell outside it), the same float.
  float drag_density_at(int i, int j, int k) const;
  /// a per cell of the whole grid, 1/m (the ParaView field `canopy_density`).
  std::vector<float> frontal_area_density() const { return to_float(area_); }
  /// The cells whose frontal area density is above 0 in float (those frontal_area_density() holds).
  std::size_t occupied_cells() const;

  /// Frontal area of every tree added, inside the domain or not, m^2.
  double total_frontal_area() const { return total_area_; }
  /// The part of total_frontal_area() that fell outside the domain, m^2.
  double dropped_frontal_area() const { return dropped_area_; }
  /// Sum over cells of a h^3 (double precision), m^2: total_frontal_area() - dropped_frontal_area().
  double frontal_area_in_domain() const;
  /// Sum over cells of k h^3 (double precision), m^2: half the drag area (C_D x area) inside the domain,
  /// so that rho_air |u| u times it is the force a uniform wind u loses to the canopy.
  double drag_in_domain() const;
  /// The columns whose centres lie in [min, max] (world x and y, m, edges included) and the frontal area in
  /// them; none (all zero) when the rectangle holds no column centre.
  CanopyColumns columns_in(const std::array<double, 2>& min, const std::array<double, 2>& max) const;
  int tree_count() const { return trees_; }
  /// Trees of which nothing landed in the domain.
  int trees_outside() const { return trees_outside_; }

 private:
  struct Split {
    double frontal_inside = 0.0, frontal_outside = 0.0, drag_outside = 0.0;  // m^2
  };
  // Adds the element's areas to the cells it crosses; says how much landed outside the domain.
  Split rasterise(const CanopyElement& e);
  // The whole grid's field from the box's values v (zero outside the box).
  std::vector<float> to_float(const std::vector<double>& v) const;
  // The index in the box's arrays of the grid's cell (i, j, k), which lies in the box.
  std::size_t box_index(int i, int j, int k) const;

  GridSpec spec_;
  CellBox box_;
  std::vector<double> area_, drag_;  // per cell of the box: m^2 / h^3 = 1/m
  double total_area_ = 0.0, dropped_area_ = 0.0;
  int trees_ = 0, trees_outside_ = 0;
};

}  // namespace fw::fluid
