#include "fluid/PressureLevels.hpp"

#include <stdexcept>

namespace fw::fluid {
namespace {

// Neighbour offset of face f (FW_FACE_*): axis f/2, direction -1 for even f, +1 for odd f.
inline int axis_of(int f) {
  return f / 2;
}
inline int dir_of(int f) {
  return (f % 2) ? 1 : -1;
}

}  // namespace

PressureLevel build_fine_pressure_level(const GridSpec& spec, const std::vector<std::uint8_t>& solid) {
  spec.validate();
  if (!solid.empty() && solid.size() != spec.cell_count())
    throw std::invalid_argument("PressureLevels: solid map size does not match the grid");
  PressureLevel level{spec.nx, spec.ny, spec.nz, std::vector<std::uint8_t>(spec.cell_count(), 0)};
  const int n[3] = {spec.nx, spec.ny, spec.nz};
  auto is_fluid = [&](int i, int j, int k) {
    return solid.empty() ||
           solid[std::size_t(i) + std::size_t(spec.nx) * (j + std::size_t(spec.ny) * k)] == 0;
  };
  for (int k = 0; k < spec.nz; ++k)
    for (int j = 0; j < spec.ny; ++j)
      for (int i = 0; i < spec.nx; ++i) {
        if (!is_fluid(i, j, k)) continue;
        std::uint8_t m = FW_MASK_FLUID;
        for (int f = 0; f < 6; ++f) {
          int idx[3] = {i, j, k};
          const int a = axis_of(f);
          idx[a] += dir_of(f);
          if (idx[a] < 0 || idx[a] >= n[a]) {
            const BoundaryType bc = spec.boundary[f];
            if (bc == BoundaryType::outflow) {
              m |= std::uint8_t(1u << f);  // Dirichlet ghost
              continue;
            }
            if (bc != BoundaryType::periodic || n[a] == 1)
              continue;  // closed (a 1-cell periodic axis couples to itself)
            idx[a] = (idx[a] + n[a]) % n[a];
          }
          if (is_fluid(idx[0], idx[1], idx[2])) m |= std::uint8_t(1u << f);
        }
        level.mask[std::size_t(i) + std::size_t(spec.nx) * (j + std::size_t(spec.ny) * k)] = m;
      }
  return level;
}

bool can_coarsen(const PressureLevel& level, const GridSpec& spec) {
  const int n[3] = {level.nx, level.ny, level.nz};
  bool any_long = false;
  for (int a = 0; a < 3; ++a) {
    if (n[a] > 1) any_long = true;
    if (spec.periodic(a) && n[a] > 1 && (n[a] % 2) != 0) return false;
    // A periodic axis halved to an odd count > 1 would break the red-black colouring across the seam.
    const int coarse = (n[a] + 1) / 2;
    if (spec.periodic(a) && coarse > 1 && (coarse % 2) != 0) return false;
  }
  return any_long;
}

PressureLevel coarsen_pressure_level(const PressureLevel& fine, const GridSpec& spec) {
  PressureLevel c;
  c.nx = (fine.nx + 1) / 2;
  c.ny = (fine.ny + 1) / 2;
  c.nz = (fine.nz + 1) / 2;
  c.mask.assign(c.cell_count(), 0);
  const int nf[3] = {fine.nx, fine.ny, fine.nz};
  const int nc[3] = {c.nx, c.ny, c.nz};
  for (int K = 0; K < c.nz; ++K)
    for (int J = 0; J < c.ny; ++J)
      for (int I = 0; I < c.nx; ++I) {
        std::uint8_t m = 0;
        const int C[3] = {I, J, K};
        for (int dk = 0; dk < 2; ++dk)
          for (int dj = 0; dj < 2; ++dj)
            for (int di = 0; di < 2; ++di) {
              const int f[3] = {2 * I + di, 2 * J + dj, 2 * K + dk};
              if (f[0] >= nf[0] || f[1] >= nf[1] || f[2] >= nf[2]) continue;
              const std::uint8_t fm =
                  fine.mask[std::size_t(f[0]) + std::size_t(fine.nx) * (f[1] + std::size_t(fine.ny) * f[2])];
              if (!(fm & FW_MASK_FLUID)) continue;
              m |= FW_MASK_FLUID;
              for (int face = 0; face < 6; ++face) {
                const int a = axis_of(face);
                // Only the children on this side of the coarse cell carry the coarse face.
                const int side_child = dir_of(face) < 0 ? 2 * C[a] : std::min(2 * C[a] + 1, nf[a] - 1);
                if (f[a] == side_child && (fm & (1u << face))) m |= std::uint8_t(1u << face);
              }
            }
        // A coarse periodic axis of one cell couples to itself: drop it (it adds nothing to A).
        for (int a = 0; a < 3; ++a)
          if (nc[a] == 1 && spec.periodic(a)) m &= std::uint8_t(~((1u << (2 * a)) | (1u << (2 * a + 1))));
        c.mask[std::size_t(I) + std::size_t(c.nx) * (J + std::size_t(c.ny) * K)] = m;
      }
  return c;
}

std::vector<std::array<int, 3>> pressure_level_extents(const GridSpec& spec, std::size_t coarsest_cells) {
  PressureLevel level{spec.nx, spec.ny, spec.nz, {}};  // the rules read the extents only
  std::vector<std::array<int, 3>> extents{{level.nx, level.ny, level.nz}};
  while (level.cell_count() > coarsest_cells && can_coarsen(level, spec)) {
    level = PressureLevel{(level.nx + 1) / 2, (level.ny + 1) / 2, (level.nz + 1) / 2, {}};
    extents.push_back({level.nx, level.ny, level.nz});
  }
  return extents;
}

std::vector<PressureLevel> build_pressure_levels(const GridSpec& spec, const std::vector<std::uint8_t>& solid,
                                                 std::size_t coarsest_cells) {
  // The rule of how far to coarsen reads the extents only (pressure_level_extents).
  const std::size_t count = pressure_level_extents(spec, coarsest_cells).size();
  std::vector<PressureLevel> levels;
  levels.push_back(build_fine_pressure_level(spec, solid));
  while (levels.size() < count) levels.push_back(coarsen_pressure_level(levels.back(), spec));
  return levels;
}

}  // namespace fw::fluid
