#include "host/stages/WallFaces.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <array>
#include <stdexcept>

namespace fw::host {

namespace {

std::int32_t face_index(const fluid::GridSpec& spec, int c, const std::array<int, 3>& at) {
  const int ex = spec.nx + (c == 0 ? 1 : 0), ey = spec.ny + (c == 1 ? 1 : 0);
  return static_cast<std::int32_t>(at[0] + ex * (at[1] + ey * at[2]));
}

// A cell index one below the axis or one past it: wrapped on a periodic axis, else the edge cell.
int wrap_or_clamp(int x, int n, bool periodic) {
  if (periodic) return x < 0 ? x + n : (x >= n ? x - n : x);
  return std::clamp(x, 0, n - 1);
}

}  // namespace

WallFaces list_wall_faces(const fluid::GridSpec& spec, const std::vector<float>& walls) {
  if (walls.size() != spec.cell_count())
    throw std::invalid_argument(fmt::format("list_wall_faces: {} wall values for a grid of {} cells",
                                            walls.size(), spec.cell_count()));
  auto wall = [&](const std::array<int, 3>& cell) {
    return walls[std::size_t(cell[0]) + std::size_t(spec.nx) * (cell[1] + std::size_t(spec.ny) * cell[2])];
  };
  WallFaces list;
  for (int c = 0; c < 2; ++c) {
    const int d = 1 - c;  // the other horizontal component
    const int n = spec.cells_along(c);
    const bool periodic = spec.periodic(c);
    const std::array<int, 3> extent{spec.nx + (c == 0), spec.ny + (c == 1), spec.nz};
    for (int k = 0; k < extent[2]; ++k)
      for (int j = 0; j < extent[1]; ++j)
        for (int i = 0; i < extent[0]; ++i) {
          const std::array<int, 3> face{i, j, k};
          std::array<int, 3> lo = face, hi = face;
          lo[c] = wrap_or_clamp(face[c] - 1, n, periodic);
          hi[c] = wrap_or_clamp(face[c], n, periodic);
          const float weight = 0.5f * (wall(lo) + wall(hi));
          if (weight == 0.0f) continue;
          list.faces.push_back(face_index(spec, c, face));
          for (const auto& cell : {lo, hi})
            for (int side = 0; side < 2; ++side) {
              std::array<int, 3> across = cell;
              across[d] += side;
              list.faces.push_back(face_index(spec, d, across));
            }
          list.weights.push_back(weight);
        }
    if (c == 0) list.u_count = list.size();
  }
  return list;
}

}  // namespace fw::host
