#include "io/settings/SiteSettings.hpp"

#include <fmt/format.h>

namespace fw::io {

std::string SiteSettings::crs_label() const {
  if (!crs) return "none";
  if (crs->epsg)
    return crs->name.empty() ? fmt::format("EPSG:{}", *crs->epsg)
                             : fmt::format("EPSG:{} ({})", *crs->epsg, crs->name);
  return crs->name.empty() ? "a CRS without an EPSG code (its WKT)" : crs->name;
}

}  // namespace fw::io
