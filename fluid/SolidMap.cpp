#include "fluid/SolidMap.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <cmath>
#include <stdexcept>

namespace fw::fluid {
namespace {

std::string label(const char* kind, const std::string& name) {
  return name.empty() ? fmt::format("{} (unnamed)", kind) : fmt::format("{} '{}'", kind, name);
}

void check_finite(const std::string& shape, const char* field, double value) {
  if (!std::isfinite(value))
    throw std::invalid_argument(fmt::format("SolidMap: {}: {} must be finite, got {}", shape, field, value));
}

void check_finite(const std::string& shape, const char* field, const std::array<double, 3>& value) {
  for (int a = 0; a < 3; ++a) check_finite(shape, fmt::format("{}[{}]", field, a).c_str(), value[a]);
}

void check_positive(const std::string& shape, const char* field, double value_m) {
  if (!(value_m > 0.0) || !std::isfinite(value_m))
    throw std::invalid_argument(
        fmt::format("SolidMap: {}: {} must be a positive length in metres, got {}", shape, field, value_m));
}

/// Half-open range [lo, hi) of cell indices along one axis.
struct IndexRange {
  int lo = 0, hi = 0;
};

/// The cells along one axis whose centres may lie in [lo_m, hi_m], one cell of slack on each side so that
/// rounding never drops a cell; the exact inside test decides.
IndexRange cells_between(double lo_m, double hi_m, double origin_m, double h_m, int n) {
  const double lo = std::floor((lo_m - origin_m) / h_m - 0.5);
  const double hi = std::ceil((hi_m - origin_m) / h_m - 0.5) + 1.0;
  // Clamp in double first: a shape far outside the grid must not overflow the int conversion.
  return {int(std::clamp(lo, 0.0, double(n))), int(std::clamp(hi, 0.0, double(n)))};
}

/// Marks the cells of the bounding box [lo_m, hi_m] whose centres satisfy inside(x, y, z); returns how many
/// were newly marked.
template <class Inside>
std::size_t mark(const GridSpec& spec, std::vector<std::uint8_t>& cells, const std::array<double, 3>& lo_m,
                 const std::array<double, 3>& hi_m, Inside inside) {
  const IndexRange ri = cells_between(lo_m[0], hi_m[0], spec.origin[0], spec.h, spec.nx);
  const IndexRange rj = cells_between(lo_m[1], hi_m[1], spec.origin[1], spec.h, spec.ny);
  const IndexRange rk = cells_between(lo_m[2], hi_m[2], spec.origin[2], spec.h, spec.nz);
  std::size_t added = 0;
  for (int k = rk.lo; k < rk.hi; ++k) {
    const double z = spec.origin[2] + (k + 0.5) * spec.h;
    for (int j = rj.lo; j < rj.hi; ++j) {
      const double y = spec.origin[1] + (j + 0.5) * spec.h;
      const std::size_t row = std::size_t(spec.nx) * (j + std::size_t(spec.ny) * k);
      for (int i = ri.lo; i < ri.hi; ++i) {
        const double x = spec.origin[0] + (i + 0.5) * spec.h;
        std::uint8_t& cell = cells[row + i];
        if (cell == 0 && inside(x, y, z)) {
          cell = 1;
          ++added;
        }
      }
    }
  }
  return added;
}

}  // namespace

SolidMap::SolidMap(const GridSpec& spec) : spec_(spec) {
  spec_.validate();
  cells_.assign(spec_.cell_count(), 0);
}

bool SolidMap::solid(int i, int j, int k) const {
  if (i < 0 || i >= spec_.nx || j < 0 || j >= spec_.ny || k < 0 || k >= spec_.nz)
    throw std::out_of_range(fmt::format("SolidMap: cell ({}, {}, {}) is outside the {} x {} x {} grid", i, j,
                                        k, spec_.nx, spec_.ny, spec_.nz));
  return cells_[std::size_t(i) + std::size_t(spec_.nx) * (j + std::size_t(spec_.ny) * k)] != 0;
}

std::size_t SolidMap::add(const SolidBox& box) {
  const std::string shape = label("box", box.name);
  check_finite(shape, "center", box.center);
  check_positive(shape, "size[0]", box.size[0]);
  check_positive(shape, "size[1]", box.size[1]);
  check_positive(shape, "size[2]", box.size[2]);
  check_finite(shape, "yaw", box.yaw_rad);

  const double c = std::cos(box.yaw_rad), s = std::sin(box.yaw_rad);
  const std::array<double, 3> half{0.5 * box.size[0], 0.5 * box.size[1], 0.5 * box.size[2]};
  // Horizontal half-extents of the turned box's axis-aligned bounding box.
  const double ex = std::abs(c) * half[0] + std::abs(s) * half[1];
  const double ey = std::abs(s) * half[0] + std::abs(c) * half[1];
  const auto& o = box.center;
  const std::size_t added = mark(spec_, cells_, {o[0] - ex, o[1] - ey, o[2] - half[2]},
                                 {o[0] + ex, o[1] + ey, o[2] + half[2]}, [&](double x, double y, double z) {
                                   // Into the box's frame: turn the offset by -yaw.
                                   const double dx = x - o[0], dy = y - o[1], dz = z - o[2];
                                   const double lx = c * dx + s * dy, ly = -s * dx + c * dy;
                                   return -half[0] <= lx && lx < half[0] && -half[1] <= ly && ly < half[1] &&
                                          -half[2] <= dz && dz < half[2];
                                 });
  solid_count_ += added;
  return added;
}

std::size_t SolidMap::add(const SolidCylinder& cylinder) {
  const std::string shape = label("cylinder", cylinder.name);
  check_finite(shape, "base", cylinder.base);
  check_positive(shape, "radius", cylinder.radius);
  check_positive(shape, "height", cylinder.height);

  const auto& b = cylinder.base;
  const double r = cylinder.radius, r2 = r * r, top = b[2] + cylinder.height;
  const std::size_t added = mark(spec_, cells_, {b[0] - r, b[1] - r, b[2]}, {b[0] + r, b[1] + r, top},
                                 [&](double x, double y, double z) {
                                   const double dx = x - b[0], dy = y - b[1];
                                   return dx * dx + dy * dy <= r2 && b[2] <= z && z < top;
                                 });
  solid_count_ += added;
  return added;
}

std::size_t SolidMap::add(const SolidSphere& sphere) {
  const std::string shape = label("sphere", sphere.name);
  check_finite(shape, "center", sphere.center);
  check_positive(shape, "radius", sphere.radius);

  const auto& o = sphere.center;
  const double r = sphere.radius, r2 = r * r;
  const std::size_t added = mark(spec_, cells_, {o[0] - r, o[1] - r, o[2] - r},
                                 {o[0] + r, o[1] + r, o[2] + r}, [&](double x, double y, double z) {
                                   const double dx = x - o[0], dy = y - o[1], dz = z - o[2];
                                   return dx * dx + dy * dy + dz * dz <= r2;
                                 });
  solid_count_ += added;
  return added;
}

std::size_t SolidMap::add_terrain(const Heightmap& terrain) {
  // The heightmap clamps at its edges, so it covers every column; per column, only the cells up to the
  // surface are visited, and nothing above the terrain's highest sample.
  const double floor_m = spec_.origin[2];
  const IndexRange rk = cells_between(floor_m, floor_m + terrain.max_height(), floor_m, spec_.h, spec_.nz);
  std::size_t added = 0;
  for (int j = 0; j < spec_.ny; ++j) {
    const double y = spec_.origin[1] + (j + 0.5) * spec_.h;
    for (int i = 0; i < spec_.nx; ++i) {
      const double x = spec_.origin[0] + (i + 0.5) * spec_.h;
      const double surface = floor_m + terrain.height_at(x, y);
      for (int k = 0; k < rk.hi; ++k) {
        const double z = floor_m + (k + 0.5) * spec_.h;
        if (!(z < surface)) break;
        std::uint8_t& cell = cells_[std::size_t(i) + std::size_t(spec_.nx) * (j + std::size_t(spec_.ny) * k)];
        if (cell == 0) {
          cell = 1;
          ++added;
        }
      }
    }
  }
  solid_count_ += added;
  return added;
}

}  // namespace fw::fluid
