// A run's site (io/settings/SiteSettings.hpp) as VTK field data, written into every wind and trees frame of
// a run with a site and read back by `export` (docs/gis.md, "The site in the outputs"):
//   site_origin   Float64 x 3, 1 tuple: domain.origin in the CRS (x, y, the floor's elevation), m; a local
//                 point p is at site_origin + p
//   site_epsg     Int32, 1 tuple: the CRS's EPSG code, 0 when it has none
//   site_crs      String, 1 tuple: the CRS as WKT2; absent for a site without a CRS
//
//   fw::io::add_site_field_data(*image->GetFieldData(), site);
//   std::optional<fw::io::SiteSettings> site = fw::io::read_site_field_data(*image->GetFieldData());
#pragma once

#include <optional>

#include "io/settings/SiteSettings.hpp"

class vtkFieldData;

namespace fw::io {

void add_site_field_data(vtkFieldData& data, const SiteSettings& site);

/// The site, when `data` holds site_origin (3 finite components); its CRS when it also holds site_crs (the
/// name and whether it is geographic are not kept in the frames: empty and false). The raster is not kept.
std::optional<SiteSettings> read_site_field_data(vtkFieldData& data);

}  // namespace fw::io
