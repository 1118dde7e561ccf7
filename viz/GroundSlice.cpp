#include "viz/GroundSlice.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <limits>
#include <stdexcept>

namespace fw::viz {

std::size_t GroundSlice::valid_count() const {
  std::size_t n = 0;
  for (const float v : values) n += !std::isnan(v);
  return n;
}

GroundSlice ground_slice(const WindGrid& wind, const std::string& field, double height) {
  if (!std::isfinite(height) || height < 0.0)
    throw std::invalid_argument(
        fmt::format("export: --height: a height above the ground (m, >= 0) expected, got {}", height));
  const std::vector<std::string> names = wind.field_names();
  if (std::find(names.begin(), names.end(), field) == names.end())
    throw std::invalid_argument(fmt::format("export: no field '{}' in {}: choose one of {}", field,
                                            wind.file.string(), fmt::join(names, ", ")));
  const ScalarField scalars = wind.field(field);
  const auto [nx, ny, nz] = wind.cells;
  const double h = wind.cell_size;
  GroundSlice slice;
  slice.field = field;
  slice.unit = scalars.unit;
  slice.height = height;
  slice.columns = nx;
  slice.rows = ny;
  slice.origin = {wind.origin[0], wind.origin[1]};
  slice.cell_size = h;
  slice.values.assign(std::size_t(nx) * std::size_t(ny), std::numeric_limits<float>::quiet_NaN());
  const auto solid = [&](int i, int j, int k) {
    return !wind.solid.empty() && wind.solid[wind.index(i, j, k)];
  };
  for (int j = 0; j < ny; ++j)
    for (int i = 0; i < nx; ++i) {
      int ground = 0;  // cells of solid from the floor up
      while (ground < nz && solid(i, j, ground)) ++ground;
      if (ground == nz) continue;
      // The height in cell-centre units: cell k's centre lies at k + 1/2 cells above the floor.
      const double level = std::max(ground + height / h - 0.5, double(ground));
      if (level > nz - 1.0) continue;
      const int k0 = int(level);
      const double t = level - k0;
      const int k1 = t > 0.0 ? k0 + 1 : k0;  // on a cell centre, only that cell
      if (solid(i, j, k0) || solid(i, j, k1)) continue;
      slice.values[std::size_t(j) * std::size_t(nx) + std::size_t(i)] =
          float((1.0 - t) * scalars.values[wind.index(i, j, k0)] + t * scalars.values[wind.index(i, j, k1)]);
    }
  return slice;
}

io::GeoGrid geo_grid(const GroundSlice& slice, double time, const io::SiteSettings* site) {
  io::GeoGrid grid;
  grid.columns = slice.columns;
  grid.rows = slice.rows;
  const double h = slice.cell_size;
  // Local metres, or with a site its CRS.
  const std::array<double, 3> local{slice.origin[0], slice.origin[1], 0.0};
  const std::array<double, 3> corner = site ? site->to_site(local) : local;
  grid.transform = {corner[0], h, 0.0, corner[1] + slice.rows * h, 0.0, -h};
  if (site && site->crs) grid.crs_wkt = site->crs->wkt;
  grid.values.reserve(slice.values.size());
  for (int row = slice.rows - 1; row >= 0; --row)  // GeoTIFF rows run north to south
    for (int i = 0; i < slice.columns; ++i) {
      const float v = slice.value(i, row);
      grid.values.push_back(std::isnan(v) ? float(kGeoTiffNoData) : v);
    }
  grid.nodata = kGeoTiffNoData;
  grid.description = fmt::format("{} at {:g} m above the ground{}, t = {:g} s", slice.field, slice.height,
                                 slice.unit.empty() ? "" : fmt::format(" ({})", slice.unit), time);
  return grid;
}

}  // namespace fw::viz
