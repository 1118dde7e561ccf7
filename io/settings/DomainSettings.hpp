// The domain section of a scenario (docs/scenario.md, "domain"): the wind grid's corner, extent and cells,
// and its blocks over MPI ranks. Defaults are the schema's (io/schema/DomainKeys.hpp).
//
//   fw::io::DomainSettings domain;   // origin {0, 0, 0}
//   domain.max_corner();             // origin + size, m
#pragma once

#include <array>
#include <optional>

#include "io/schema/DomainKeys.hpp"

namespace fw::io {

struct DomainSettings {
  /// minimum corner, m; (0, 0, 0) once a terrain.raster has taken the file's origin for the site
  /// (TerrainSettings::site)
  std::array<double, 3> origin{schema::key(schema::kDomainKeys, "domain.origin").number,
                               schema::key(schema::kDomainKeys, "domain.origin").number,
                               schema::key(schema::kDomainKeys, "domain.origin").number};
  int origin_line = 0;                  ///< the line of origin in the file (of domain when not given)
  std::array<double, 3> size{0, 0, 0};  ///< extent along x, y, z, m (> 0)
  double cell_size = 0.0;               ///< h, m (> 0); cells are cubic
  std::array<int, 3> cells{0, 0, 0};    ///< round(size / h); size is a whole multiple of h
  /// Blocks along x and y over MPI ranks (fluid/Decomposition), as given; else chosen from the ranks.
  std::optional<std::array<int, 2>> decomposition;
  int decomposition_line = 0;  ///< the line of decomposition in the file (of domain when not given)

  /// origin + size, m.
  std::array<double, 3> max_corner() const {
    return {origin[0] + size[0], origin[1] + size[1], origin[2] + size[2]};
  }
};

}  // namespace fw::io
