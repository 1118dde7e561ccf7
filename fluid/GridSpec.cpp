#include "fluid/GridSpec.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <cmath>
#include <limits>
#include <stdexcept>

namespace fw::fluid {
namespace {
constexpr const char* kBoundaryNames[] = {"inflow", "outflow", "slip", "no_slip", "periodic"};
constexpr const char* kFaceNames[] = {"west", "east", "south", "north", "ground", "top"};
}  // namespace

std::string to_string(BoundaryType type) {
  const int i = static_cast<int>(type);
  return (i >= 0 && i < 5) ? kBoundaryNames[i] : fmt::format("<invalid boundary {}>", i);
}

std::string face_name(int face) {
  return (face >= 0 && face < 6) ? kFaceNames[face] : "<invalid face>";
}

void GridSpec::validate() const {
  if (nx <= 0 || ny <= 0 || nz <= 0)
    throw std::invalid_argument(
        fmt::format("GridSpec: dimensions must be positive, got {} x {} x {} cells", nx, ny, nz));
  if (!(h > 0.0) || !std::isfinite(h))
    throw std::invalid_argument(fmt::format("GridSpec: cell size must be > 0 m, got {}", h));
  for (double o : origin)
    if (!std::isfinite(o)) throw std::invalid_argument("GridSpec: origin must be finite");
  // Face counts (nx+1)*ny*nz must fit the 32-bit indices the kernels use.
  // In double from the start: nx + 1 in int would overflow for nx = INT_MAX.
  const double faces = (double(nx) + 1.0) * (double(ny) + 1.0) * (double(nz) + 1.0);
  if (faces > double(kMaxFaces))
    throw std::invalid_argument(
        fmt::format("GridSpec: {} x {} x {} cells exceed the 2^31 index range of the kernels", nx, ny, nz));
  for (int f = 0; f < 6; ++f) {
    const int value = static_cast<int>(boundary[f]);
    if (value < 0 || value > 4)
      throw std::invalid_argument(
          fmt::format("GridSpec: unknown boundary type {} on the {} face", value, face_name(f)));
  }
  for (int axis = 0; axis < 3; ++axis) {
    const bool lo = boundary[2 * axis] == BoundaryType::periodic;
    const bool hi = boundary[2 * axis + 1] == BoundaryType::periodic;
    const int n[3] = {nx, ny, nz};
    if (lo && hi && n[axis] > 1 && n[axis] % 2 != 0)
      throw std::invalid_argument(
          fmt::format("GridSpec: a periodic axis needs an even number of cells (red-black smoothing), the "
                      "{}-{} axis has {}",
                      face_name(2 * axis), face_name(2 * axis + 1), n[axis]));
    if (lo != hi)
      throw std::invalid_argument(fmt::format("GridSpec: the {} face is periodic but the {} face is not",
                                              face_name(lo ? 2 * axis : 2 * axis + 1),
                                              face_name(lo ? 2 * axis + 1 : 2 * axis)));
  }
}

bool GridSpec::has_dirichlet_pressure() const {
  for (auto b : boundary)
    if (b == BoundaryType::outflow) return true;
  return false;
}

FwGrid GridSpec::to_device() const {
  FwGrid g{};
  g.nx = nx;
  g.ny = ny;
  g.nz = nz;
  for (int f = 0; f < 6; ++f) g.bc[f] = static_cast<fw_int>(boundary[f]);
  g.h = static_cast<float>(h);
  for (int a = 0; a < 3; ++a) g.origin[a] = static_cast<float>(origin[a]);
  g.ox = block_offset[0];
  g.oy = block_offset[1];
  g.wrap[0] = block_period[0];
  g.wrap[1] = block_period[1];
  g.domain[0] = domain_cells()[0];
  g.domain[1] = domain_cells()[1];
  return g;
}

namespace {

// The cell of n[0] x n[1] x n[2] cells from `origin` that holds `world`, clamped into them.
std::array<int, 3> clamped_cell(const GridSpec& spec, const std::array<double, 3>& world, const int n[3]) {
  std::array<int, 3> cell{};
  for (std::size_t a = 0; a < 3; ++a)
    cell[a] = std::clamp(int(std::floor((world[a] - spec.origin[a]) / spec.h)), 0, n[a] - 1);
  return cell;
}

}  // namespace

std::array<int, 3> GridSpec::cell_holding(const std::array<double, 3>& world) const {
  const int n[3] = {nx, ny, nz};
  return clamped_cell(*this, world, n);
}

std::array<int, 3> GridSpec::domain_cell_holding(const std::array<double, 3>& world) const {
  const int n[3] = {domain_cells()[0], domain_cells()[1], nz};
  return clamped_cell(*this, world, n);
}

}  // namespace fw::fluid
