#include "fluid/SubgridStress.hpp"

#include <fmt/format.h>

#include <cmath>
#include <stdexcept>

namespace fw::fluid {

double eddy_viscosity_cap(double h, double dt) {
  if (!std::isfinite(h) || !(h > 0.0) || !std::isfinite(dt) || !(dt > 0.0))
    throw std::invalid_argument(fmt::format(
        "eddy_viscosity_cap: needs a finite cell size and dt > 0, got h = {} m, dt = {} s", h, dt));
  return kEddyDiffusionLimit * h * h / dt;
}

double wall_drag_coefficient(double h, double roughness_length) {
  const double z1 = wall_centre_height(h);
  if (!std::isfinite(h) || !(roughness_length > 0.0) || !(roughness_length < z1))
    throw std::invalid_argument(
        fmt::format("wall_drag_coefficient: the roughness length must lie in (0, h/2) = (0, {}) m, got {} m",
                    z1, roughness_length));
  const double ratio = kVonKarman / std::log(z1 / roughness_length);
  return ratio * ratio;
}

bool ground_is_wall(const GridSpec& spec) {
  const BoundaryType ground = spec.boundary[FW_FACE_GROUND];
  return ground == BoundaryType::slip || ground == BoundaryType::no_slip;
}

std::vector<float> wall_cells(const GridSpec& spec, const std::vector<std::uint8_t>& solid) {
  if (!solid.empty() && solid.size() != spec.cell_count())
    throw std::invalid_argument(
        fmt::format("wall_cells: solid map has {} cells, the grid {}", solid.size(), spec.cell_count()));
  const std::size_t layer = std::size_t(spec.nx) * std::size_t(spec.ny);
  auto is_solid = [&](std::size_t id) { return !solid.empty() && solid[id] != 0; };
  const bool ground = ground_is_wall(spec);
  std::vector<float> walls(spec.cell_count(), 0.0f);
  for (std::size_t id = 0; id < walls.size(); ++id) {
    if (is_solid(id)) continue;
    const bool bottom = id < layer;
    if (bottom ? ground : is_solid(id - layer)) walls[id] = 1.0f;
  }
  return walls;
}

}  // namespace fw::fluid
