// `forestwind plot`: a run's probes.csv as a picture. One panel for the wind speed at each probe over time;
// in a run with storm damage, under it and on the same time axis, one for the number of broken and of
// overturned trees so far (steps: a count holds until the time at which it changes); one for the tip
// displacement of each tracked tree; all with the output frames' times marked along the top. With
// `spectrum`, a last panel with the power spectrum of each probe's wind speed on log axes and the
// Kolmogorov f^-5/3 slope for reference.
//
//   fw::viz::ProbeTable table = fw::viz::read_probe_table("out/storm/probes.csv");
//   fw::viz::ProbePlot plot = fw::viz::plot_probes(table, frame_times, "storm", {/*spectrum=*/true});
//   plot.canvas.write_png("out/storm/probes.png");
//
// Spectra: Welch's estimate (fluid/FlowStatistics: Hann windows, half overlap) of |u| about its mean, the
// samples first interpolated linearly onto their median interval (a run with an adaptive time step samples
// unevenly). Segments are the longest power of two that still gives at least 7 overlapping segments, which
// needs at least kSpectrumSamples samples.
#pragma once

#include <string>
#include <vector>

#include "viz/Canvas.hpp"
#include "viz/Chart.hpp"
#include "viz/ProbeTable.hpp"

namespace fw::viz {

/// The fewest samples per probe a spectrum is drawn from: 4 segments of 64, overlapping by half (7 in all).
constexpr std::size_t kSpectrumSamples = 256;

struct PlotSettings {
  bool spectrum = false;
  int width = 1280;        ///< px
  int panel_height = 340;  ///< px, per panel
};

struct ProbePlot {
  Canvas canvas;
  std::vector<Viewport> plot_areas;  ///< per panel drawn, top to bottom: the rectangle inside its axes
  std::vector<std::string> panels;   ///< "wind", "damage", "tips", "spectrum"
};

/// The damage panel is drawn from table.damage (probes.csv's tree counts, or damage.csv's failures through
/// DamageTable::counts_over) over the table's time span. Throws std::invalid_argument("plot: ...") when the
/// table has no rows, neither probes, nor trees, nor tree counts, or (with `spectrum`) fewer than
/// kSpectrumSamples samples or no probes.
ProbePlot plot_probes(const ProbeTable& table, const std::vector<double>& frame_times,
                      const std::string& scenario, const PlotSettings& settings);

}  // namespace fw::viz
