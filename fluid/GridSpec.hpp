// The wind grid's size, cell size, placement and boundary conditions, validated before anything is
// allocated.
//
//   fw::fluid::GridSpec spec;
//   spec.nx = 128; spec.ny = 128; spec.nz = 64; spec.h = 1.0;
//   spec.boundary[FW_FACE_WEST] = BoundaryType::inflow;
//   spec.validate();                                   // throws std::invalid_argument("GridSpec: ...")
//
// Cells are cubic (size h, metres). Face velocities live on a MAC grid, see kernels/shared_types.h.
#pragma once

#include <array>
#include <cstddef>
#include <cstdint>
#include <limits>
#include <string>

#include "kernels/shared_types.h"

namespace fw::fluid {

enum class BoundaryType : int {
  inflow = FW_BC_INFLOW,
  outflow = FW_BC_OUTFLOW,
  slip = FW_BC_SLIP,
  no_slip = FW_BC_NO_SLIP,
  periodic = FW_BC_PERIODIC,
};

/// "inflow", "outflow", "slip", "no_slip" or "periodic".
std::string to_string(BoundaryType type);
/// "west", "east", "south", "north", "ground", "top" for FW_FACE_*.
std::string face_name(int face);

struct GridSpec {
  /// The most faces (nx + 1)(ny + 1)(nz + 1) a grid may have: the kernels index face arrays with 32-bit ints.
  static constexpr std::int64_t kMaxFaces = std::numeric_limits<std::int32_t>::max();

  int nx = 0, ny = 0, nz = 0;             // cells along x, y, z
  double h = 0.0;                         // cell size, m
  std::array<double, 3> origin{0, 0, 0};  // minimum corner of the domain, m
  /// For a rank's block of the domain (docs/parallel.md): the domain's cell index of this grid's cell
  /// (0, 0) along x and y, so that a face or cell centre lies at origin + h (index + block_offset + ...),
  /// the same float a whole grid computes. {0, 0} for a whole grid.
  std::array<int, 2> block_offset{0, 0};
  /// For a rank's block whose x or y axis is periodic in the domain but cut between blocks: the domain's
  /// cells along it, by which positions wrap as a whole grid wraps them (so a back-trace rounds alike). 0
  /// elsewhere, and for a whole grid.
  std::array<int, 2> block_period{0, 0};
  /// For a rank's block: the domain's cells along x and y, the lattice a point sample clamps to (so that a
  /// block samples a point as the whole grid does). {0, 0} for a whole grid, whose own nx, ny they are.
  std::array<int, 2> block_domain{0, 0};
  std::array<BoundaryType, 6> boundary{BoundaryType::slip, BoundaryType::slip, BoundaryType::slip,
                                       BoundaryType::slip, BoundaryType::slip, BoundaryType::slip};

  /// Throws std::invalid_argument("GridSpec: ...") for non-positive dimensions or cell size, a periodic face
  /// whose opposite face is not periodic, an odd cell count >1 along a periodic axis, an out-of-range
  /// boundary value, or more than kMaxFaces faces.
  void validate() const;

  std::size_t cell_count() const { return std::size_t(nx) * ny * nz; }
  /// Cells along axis 0 (x), 1 (y) or 2 (z).
  int cells_along(int axis) const { return axis == 0 ? nx : (axis == 1 ? ny : nz); }
  std::size_t u_count() const { return std::size_t(nx + 1) * ny * nz; }
  std::size_t v_count() const { return std::size_t(nx) * (ny + 1) * nz; }
  std::size_t w_count() const { return std::size_t(nx) * ny * (nz + 1); }
  bool periodic(int axis) const { return boundary[2 * axis] == BoundaryType::periodic; }
  /// True when some face holds pressure at zero (outflow), which makes the Poisson problem non-singular.
  bool has_dirichlet_pressure() const;
  /// The cell (i, j, k) that holds a world position (m); positions outside the grid take the nearest cell.
  std::array<int, 3> cell_holding(const std::array<double, 3>& world) const;
  /// The same in the domain's cells (domain_cells() along x and y): for a rank's block, the cell of the
  /// whole domain that holds the position, whichever block holds it.
  std::array<int, 3> domain_cell_holding(const std::array<double, 3>& world) const;
  /// The domain's cells along x and y: block_domain for a rank's block, else nx, ny.
  std::array<int, 2> domain_cells() const {
    return {block_domain[0] > 0 ? block_domain[0] : nx, block_domain[1] > 0 ? block_domain[1] : ny};
  }

  FwGrid to_device() const;
};

}  // namespace fw::fluid
