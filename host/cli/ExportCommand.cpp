// `forestwind export`: a wind field of a run's frame at a height above the ground, as a GeoTIFF a GIS opens
// (viz/GroundSlice.hpp, io/gis/GeoTiff.hpp). A run with a site (the frames' field data) gets its file in the
// site's CRS; one without, in the domain's own coordinates, metres from its origin, without a CRS, and the
// summary says which.
#include <fmt/format.h>

#include <array>
#include <iostream>
#include <optional>
#include <stdexcept>
#include <string>

#include "host/cli/Commands.hpp"
#include "io/gis/GeoTiff.hpp"
#include "viz/GroundSlice.hpp"
#include "viz/RunFolder.hpp"

namespace fw::cli {

int run_export(const ExportOptions& options) {
  const viz::RunFolder run(options.folder);
  const viz::RunFolder::Frame& frame = run.select(options.frame, options.time);
  std::string note;
  // An explicit frame must read; the default (the last) falls back to the last complete one.
  const viz::FrameData data =
      options.frame || options.time ? run.load(frame) : run.load_last_complete(frame, &note);
  if (!note.empty()) std::cerr << "forestwind: " << note << "\n";
  if (!data.wind)
    throw std::invalid_argument(
        fmt::format("export: {} has no wind frames (output.wind off): nothing to export", options.folder));
  const viz::GroundSlice slice = viz::ground_slice(*data.wind, options.field, options.height);
  const std::optional<io::SiteSettings>& site = data.wind->site;
  io::write_geotiff(options.output, viz::geo_grid(slice, data.time, site ? &*site : nullptr));
  if (options.quiet) return 0;
  std::cout << fmt::format(
      "wrote {} ({} at {:g} m above the ground, frame {}, t = {:g} s: {} x {} pixels of {:g} m, {} of them "
      "without a value)\n",
      options.output, slice.field, slice.height, data.index, data.time, slice.columns, slice.rows,
      slice.cell_size, slice.values.size() - slice.valid_count());
  if (site) {
    const std::array<double, 3> corner = site->to_site({slice.origin[0], slice.origin[1], 0.0});
    std::cout << fmt::format("  in the site's CRS, {}: the domain's corner at ({:.12g}, {:.12g})\n",
                             site->crs_label(), corner[0], corner[1]);
  } else
    std::cout << fmt::format(
        "  local coordinates: metres from the domain's origin ({:g}, {:g}), no CRS (the "
        "scenario has no site)\n",
        slice.origin[0], slice.origin[1]);
  return 0;
}

}  // namespace fw::cli
