#include "fluid/UpwindStencil.hpp"

#include <fmt/format.h>

#include <stdexcept>

namespace fw::fluid {
namespace {

int cells_along(const GridSpec& spec, int a) {
  return a == 0 ? spec.nx : (a == 1 ? spec.ny : spec.nz);
}

int faces_along(const GridSpec& spec, int c, int a) {
  return cells_along(spec, a) + (c == a ? 1 : 0);
}

// Per face of component c: whether it lies inside a solid, every cell beside it along c being solid (a
// face on a non-periodic domain face has only the one cell inside the domain).
std::vector<std::uint8_t> faces_inside_solids(const GridSpec& spec, const std::vector<std::uint8_t>& solid,
                                              int c) {
  const int ex = faces_along(spec, c, 0), ey = faces_along(spec, c, 1), ez = faces_along(spec, c, 2);
  std::vector<std::uint8_t> inside(std::size_t(ex) * ey * ez, 0);
  if (solid.empty()) return inside;
  const int n = cells_along(spec, c);
  std::size_t id = 0;
  for (int k = 0; k < ez; ++k)
    for (int j = 0; j < ey; ++j)
      for (int i = 0; i < ex; ++i, ++id) {
        int cell[3] = {i, j, k};
        const int own = cell[c];
        bool all_solid = true;
        for (int side = own - 1; side <= own; ++side) {
          int at = side;
          if (at < 0 || at >= n) {
            if (!spec.periodic(c)) continue;
            at = (at + n) % n;
          }
          cell[c] = at;
          all_solid =
              all_solid &&
              solid[std::size_t(cell[0]) + std::size_t(spec.nx) * (cell[1] + std::size_t(spec.ny) * cell[2])];
        }
        inside[id] = all_solid ? 1 : 0;
      }
  return inside;
}

}  // namespace

UpwindOrders upwind_orders(const GridSpec& spec, const std::vector<std::uint8_t>& solid) {
  if (!solid.empty() && solid.size() != spec.cell_count())
    throw std::invalid_argument(
        fmt::format("upwind_orders: solid map has {} cells, the grid {}", solid.size(), spec.cell_count()));
  // The values m + first .. m + last along axis a a flux of each order uses (m: the face below the point).
  constexpr int kFirst[] = {0, -1, -2}, kLast[] = {1, 2, 3};  // FW_UPWIND_FIRST, _THIRD, _FIFTH
  UpwindOrders orders;
  for (int c = 0; c < 3; ++c) {
    const int extent[3] = {faces_along(spec, c, 0), faces_along(spec, c, 1), faces_along(spec, c, 2)};
    const std::vector<std::uint8_t> inside = faces_inside_solids(spec, solid, c);
    auto usable = [&](int face[3], int a, int at) {
      if (at < 0 || at >= extent[a]) {
        // Beyond an inflow face the ghosts hold the prescribed inflow (FW_PAD deep), as good as any value.
        if (spec.boundary[std::size_t(2 * a + (at < 0 ? 0 : 1))] == BoundaryType::inflow) return true;
        if (!spec.periodic(a)) return false;
        const int n = cells_along(spec, a);  // a periodic axis' faces repeat every n
        at = ((at % n) + n) % n;
      }
      const int saved = face[a];
      face[a] = at;
      const bool ok = !inside[std::size_t(face[0]) +
                              std::size_t(extent[0]) * (face[1] + std::size_t(extent[1]) * face[2])];
      face[a] = saved;
      return ok;
    };
    auto& packed = orders[c];
    packed.assign(inside.size(), 0);
    std::size_t id = 0;
    for (int k = 0; k < extent[2]; ++k)
      for (int j = 0; j < extent[1]; ++j)
        for (int i = 0; i < extent[0]; ++i, ++id) {
          int face[3] = {i, j, k};
          std::uint16_t bits = 0;
          for (int a = 0; a < 3; ++a)
            for (int side = 0; side < 2; ++side) {
              const int m = face[a] - 1 + side;  // the face below the flux point
              int code = FW_UPWIND_FIFTH;
              for (; code > FW_UPWIND_FIRST; --code) {
                bool all = true;
                for (int at = m + kFirst[code]; at <= m + kLast[code] && all; ++at) all = usable(face, a, at);
                if (all) break;
              }
              bits |= std::uint16_t(code << FW_UPWIND_SHIFT(a, side));
            }
          packed[id] = bits;
        }
  }
  return orders;
}

double upwind_interpolation(int order_code, double normal_velocity, const std::array<double, 6>& q) {
  const double sign = normal_velocity > 0.0 ? 1.0 : (normal_velocity < 0.0 ? -1.0 : 0.0);
  switch (order_code) {
    case FW_UPWIND_FIFTH:
      return (37.0 * (q[2] + q[3]) - 8.0 * (q[1] + q[4]) + (q[0] + q[5])) / 60.0 -
             sign * (10.0 * (q[3] - q[2]) - 5.0 * (q[4] - q[1]) + (q[5] - q[0])) / 60.0;
    case FW_UPWIND_THIRD:
      return (7.0 * (q[2] + q[3]) - (q[1] + q[4])) / 12.0 -
             sign * (3.0 * (q[3] - q[2]) - (q[4] - q[1])) / 12.0;
    case FW_UPWIND_FIRST:
      return 0.5 * (q[2] + q[3]) - sign * 0.5 * (q[3] - q[2]);
  }
  throw std::invalid_argument(fmt::format("upwind_interpolation: unknown order code {}", order_code));
}

}  // namespace fw::fluid
