// `forestwind plot --profiles`: a run's stats.nc as a picture (docs/statistics.md). Four panels side by side,
// each against height: the mean wind (u, v, w, and u plus and minus its resolved standard deviation, dashed);
// the vertical flux of x momentum, resolved (u_w), subgrid (u_diff) and total (u_flux), with the total of y
// momentum (v_flux); the variances (u_2, v_2, w_2) with the resolved and subgrid kinetic energies; and the
// skewness of u and w (u_3 / u_2^1.5, w_3 / w_2^1.5). Each panel shows the last record in colour and every
// earlier record of the same variables as thin grey lines behind it: the spread of the records over the run.
// A canopy (lad > 0 somewhere) adds a fifth panel with its drag density.
//
//   fw::io::StatsFile stats = fw::io::read_stats_netcdf("out/canopy/stats.nc");
//   fw::viz::ProfilePlot plot = fw::viz::plot_profiles(stats, "");   // "" the domain, or a region's name
//   plot.canvas.write_png("out/canopy/profiles.png");
#pragma once

#include <string>
#include <vector>

#include "io/StatsNetcdf.hpp"
#include "viz/Canvas.hpp"
#include "viz/Chart.hpp"

namespace fw::viz {

struct ProfilePlotSettings {
  int panel_width = 520;  ///< px, per panel (the legend takes its right part)
  int height = 720;       ///< px
};

struct ProfilePlot {
  Canvas canvas;
  std::vector<Viewport> plot_areas;  ///< per panel, left to right: the rectangle inside its axes
  std::vector<std::string> panels;   ///< "mean", "flux", "variance", "skewness", "canopy"
};

/// The profiles of `region` ("" for the whole domain, else a group regions/NAME). Throws
/// std::invalid_argument("plot: ...") when the file holds no record yet, lacks one of the variables drawn,
/// or has no such region (naming those it has).
ProfilePlot plot_profiles(const io::StatsFile& stats, const std::string& region,
                          const ProfilePlotSettings& settings = {});

}  // namespace fw::viz
