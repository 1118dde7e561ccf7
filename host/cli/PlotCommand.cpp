// `forestwind plot`: a run's probes over time, and their spectra (docs/design.md, "Command line";
// viz/ProbePlots.hpp); with --profiles, its stats.nc (viz/ProfilePlots.hpp).
#include <fmt/format.h>

#include <filesystem>
#include <iostream>
#include <stdexcept>
#include <string>
#include <vector>

#include "host/cli/Commands.hpp"
#include "io/StatsNetcdf.hpp"
#include "viz/DamageTable.hpp"
#include "viz/ProbePlots.hpp"
#include "viz/ProbeTable.hpp"
#include "viz/ProfilePlots.hpp"
#include "viz/RunFolder.hpp"

namespace fw::cli {

namespace {

// `plot --profiles`: stats.nc's profiles (viz/ProfilePlots.hpp).
int plot_profiles(const PlotOptions& options) {
  namespace fs = std::filesystem;
  const fs::path file = fs::path(options.folder) / "stats.nc";
  if (!fs::is_regular_file(file))
    throw std::invalid_argument(
        fmt::format("plot: {}: no stats.nc: the scenario has no output.statistics, or no record is due yet",
                    options.folder));
  io::StatsFile stats;
  try {
    stats = io::read_stats_netcdf(file);
  } catch (const std::runtime_error& e) {
    throw std::invalid_argument(fmt::format("plot: {}", e.what()));
  }
  const viz::ProfilePlot plot = viz::plot_profiles(stats, options.region);
  plot.canvas.write_png(options.output);
  if (!options.quiet)
    std::cout << fmt::format("wrote {} ({} x {} px: {} records, {} heights{})\n", options.output,
                             plot.canvas.width(), plot.canvas.height(), stats.profiles.time.size(),
                             stats.z.size(), options.region.empty() ? "" : ", region " + options.region);
  return 0;
}

}  // namespace

int run_plot(const PlotOptions& options) {
  namespace fs = std::filesystem;
  const fs::path folder = options.folder;
  if (!fs::is_directory(folder))
    throw std::invalid_argument(fmt::format("plot: {}: expected a run's output folder", folder.string()));
  if (!options.region.empty() && !options.profiles)
    throw std::invalid_argument("plot: --region goes with --profiles");
  if (options.profiles) {
    if (options.spectrum)
      throw std::invalid_argument("plot: --spectrum goes with the probes, not --profiles");
    return plot_profiles(options);
  }
  const fs::path csv = folder / "probes.csv";
  if (!fs::is_regular_file(csv))
    throw std::invalid_argument(fmt::format(
        "plot: {}: no probes.csv: the scenario has no output.probes and tracks no trees", folder.string()));
  viz::ProbeTable table = viz::read_probe_table(csv);
  // Storm damage: probes.csv's tree counts, else damage.csv's failures over the probes' time span.
  if (!table.damage && !table.time.empty() && fs::is_regular_file(folder / "damage.csv"))
    table.damage =
        viz::read_damage_table(folder / "damage.csv").counts_over(table.time.front(), table.time.back());
  // The frames' times, from whichever collection the run wrote.
  std::vector<double> frame_times;
  try {
    const viz::RunFolder run(folder);
    for (const auto& frame : run.frames()) frame_times.push_back(frame.time);
  } catch (const std::invalid_argument&) {
    // probes without frames: nothing to mark
  }
  viz::PlotSettings settings;
  settings.spectrum = options.spectrum;
  const viz::ProbePlot plot = viz::plot_probes(table, frame_times, viz::scenario_name_of(folder), settings);
  plot.canvas.write_png(options.output);
  if (!options.quiet)
    std::cout << fmt::format("wrote {} ({} x {} px: {} probes, {} trees, {} samples{}{})\n", options.output,
                             plot.canvas.width(), plot.canvas.height(), table.probes.size(),
                             table.tips.size(), table.time.size(), table.damage ? ", damage" : "",
                             options.spectrum ? ", spectra" : "");
  return 0;
}

}  // namespace fw::cli
