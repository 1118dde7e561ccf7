#include "viz/ProbePlots.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <cmath>
#include <stdexcept>

#include "fluid/FlowStatistics.hpp"

namespace fw::viz {

namespace {

constexpr double kTitleHeight = 40.0;  // px above the first panel for the scenario's name
constexpr std::size_t kShortestSegment = 64;
constexpr double kKolmogorovSlope = -5.0 / 3.0;
const Rgb kInk{0.1, 0.1, 0.1}, kReference{0.45, 0.45, 0.45};
// The damage panel's lines: the utilisation map's reds (viz/ColourMap.hpp), overturned the darker.
const Rgb kBroken{0.90, 0.11, 0.09}, kOverturned{0.48, 0.00, 0.16};
// Its y axis: up to 8% above the most failed trees (at least kFewestOnAxis), and 5% of that below 0, so that
// a count of 0 shows above the axis rather than on it.
constexpr double kAboveMost = 1.08, kBelowZero = 0.05;
constexpr int kFewestOnAxis = 5;  // trees: an axis of whole numbers for one or two failures too

double median_interval(const std::vector<double>& t) {
  std::vector<double> d;
  for (std::size_t n = 1; n < t.size(); ++n) d.push_back(t[n] - t[n - 1]);
  std::nth_element(d.begin(), d.begin() + d.size() / 2, d.end());
  return d[d.size() / 2];
}

// x(t) linearly interpolated at t0, t0 + dt, ... up to the last sample.
std::vector<double> resample(const std::vector<double>& t, const std::vector<double>& x, double dt) {
  std::vector<double> out;
  std::size_t n = 0;
  for (double s = t.front(); s <= t.back() + 1e-9 * dt; s = t.front() + dt * out.size()) {
    while (n + 2 < t.size() && t[n + 1] < s) ++n;
    const double span = t[n + 1] - t[n];
    const double f = span > 0.0 ? std::clamp((s - t[n]) / span, 0.0, 1.0) : 0.0;
    out.push_back((1.0 - f) * x[n] + f * x[n + 1]);
  }
  return out;
}

std::size_t segment_for(std::size_t samples) {
  std::size_t segment = kShortestSegment;
  while (2 * segment * 4 <= samples) segment *= 2;  // at least 4 whole segments: 7 with half overlap
  return segment;
}

// `count` as steps: each value holds from its time until the next time, where the line rises (or falls).
std::array<std::vector<double>, 2> steps(const std::vector<double>& time, const std::vector<int>& count) {
  std::array<std::vector<double>, 2> xy;
  for (std::size_t n = 0; n < time.size(); ++n) {
    if (n > 0 && count[n] != count[n - 1]) xy[0].push_back(time[n]), xy[1].push_back(count[n - 1]);
    xy[0].push_back(time[n]), xy[1].push_back(count[n]);
  }
  return xy;
}

// Broken and overturned trees so far, over the wind panel's time span; returns the plot area.
Viewport damage_panel(Canvas& canvas, const Viewport& panel, const DamageCounts& counts,
                      const std::array<double, 2>& span, const std::vector<double>& frame_times) {
  const auto [broken_t, broken] = steps(counts.time, counts.broken);
  const auto [overturned_t, overturned] = steps(counts.time, counts.overturned);
  int most = kFewestOnAxis;
  for (std::size_t n = 0; n < counts.time.size(); ++n)
    most = std::max({most, counts.broken[n], counts.overturned[n]});
  const int trees = counts.time.empty() ? 0 : counts.standing[0] + counts.broken[0] + counts.overturned[0];
  const ChartAxes axes{.x_title = "time (s)",
                       .y_title = "failed trees",
                       .x_range = span[1] > span[0] ? std::optional(span) : std::nullopt,
                       .y_range = std::array<double, 2>{-kBelowZero * kAboveMost * most, kAboveMost * most}};
  const Chart chart(canvas, panel, axes, fmt::format("trees broken and overturned so far (of {})", trees),
                    // Overturned first, wide and dashed, so that where the counts are equal both show.
                    {{"overturned", overturned_t, overturned, kOverturned, 3.5, 5.0},
                     {"broken", broken_t, broken, kBroken, 1.8}},
                    frame_times);
  return chart.plot_area();
}

}  // namespace

ProbePlot plot_probes(const ProbeTable& table, const std::vector<double>& frame_times,
                      const std::string& scenario, const PlotSettings& settings) {
  if (table.time.empty()) throw std::invalid_argument("plot: probes.csv holds no samples yet");
  if (table.probes.empty() && table.tips.empty() && !table.damage)
    throw std::invalid_argument("plot: probes.csv holds neither probes nor tracked trees");
  std::vector<std::string> panels;
  if (!table.probes.empty()) panels.push_back("wind");
  if (table.damage) panels.push_back("damage");
  if (!table.tips.empty()) panels.push_back("tips");
  if (settings.spectrum) {
    if (table.probes.empty())
      throw std::invalid_argument("plot: --spectrum: probes.csv holds no wind probes");
    if (table.time.size() < kSpectrumSamples)
      throw std::invalid_argument(
          fmt::format("plot: --spectrum: probes.csv holds {} samples per probe; a spectrum needs at least {} "
                      "(sample more "
                      "often with output.probe_interval, or run longer)",
                      table.time.size(), kSpectrumSamples));
    panels.push_back("spectrum");
  }
  const int height = int(kTitleHeight) + settings.panel_height * int(panels.size());
  ProbePlot plot{Canvas(settings.width, height, {1, 1, 1}), {}, panels};
  plot.canvas.text({78, 26},
                   fmt::format("{}: {} samples, t = {:g} .. {:g} s", scenario, table.time.size(),
                               table.time.front(), table.time.back()),
                   17.0, kInk);
  for (std::size_t p = 0; p < panels.size(); ++p) {
    const Viewport panel{0.0, kTitleHeight + p * settings.panel_height, double(settings.width),
                         double(settings.panel_height)};
    std::vector<Series> series;
    if (panels[p] == "wind" || panels[p] == "tips") {
      const auto& list = panels[p] == "wind" ? table.probes : table.tips;
      for (std::size_t n = 0; n < list.size(); ++n)
        series.push_back({list[n].name, table.time, list[n].magnitude(), series_colour(n)});
      const bool wind = panels[p] == "wind";
      const ChartAxes axes{.x_title = "time (s)",
                           .y_title = wind ? "wind speed (m/s)" : "tip displacement (m)"};
      const Chart chart(plot.canvas, panel, axes,
                        wind ? "wind speed at the probes" : "tip displacement of the tracked trees", series,
                        frame_times);
      plot.plot_areas.push_back(chart.plot_area());
      continue;
    }
    if (panels[p] == "damage") {
      plot.plot_areas.push_back(damage_panel(plot.canvas, panel, *table.damage,
                                             {table.time.front(), table.time.back()}, frame_times));
      continue;
    }
    // Spectra of the wind speed at each probe.
    const double dt = median_interval(table.time);
    std::size_t segment = 0, count = 0;
    double f_lo = 0.0, f_hi = 0.0, level = 0.0;
    for (std::size_t n = 0; n < table.probes.size(); ++n) {
      std::vector<double> speed = resample(table.time, table.probes[n].magnitude(), dt);
      segment = segment_for(speed.size());
      const fluid::Spectrum s = fluid::power_spectrum(speed, dt, segment);
      series.push_back({table.probes[n].name, s.frequency, s.density, series_colour(n)});
      count = speed.size();
      f_lo = s.frequency.front(), f_hi = s.frequency.back();
      // The reference line passes through the first probe's density at the geometric middle frequency.
      if (n == 0) {
        const double middle = std::sqrt(s.frequency.front() * s.frequency.back());
        std::size_t mid = 0;
        while (mid + 1 < s.frequency.size() && s.frequency[mid] < middle) ++mid;
        level = s.density[mid] / std::pow(s.frequency[mid], kKolmogorovSlope);
      }
    }
    if (level > 0.0 && std::isfinite(level))
      series.push_back({"f^-5/3",
                        {f_lo, f_hi},
                        {level * std::pow(f_lo, kKolmogorovSlope), level * std::pow(f_hi, kKolmogorovSlope)},
                        kReference,
                        1.2,
                        6.0});
    const ChartAxes axes{.x_title = "frequency (Hz)",
                         .y_title = "power spectral density ((m/s)^2/Hz)",
                         .log_x = true,
                         .log_y = true};
    const Chart chart(
        plot.canvas, panel, axes,
        fmt::format("spectra of the wind speed (Welch: Hann windows of {} samples, {} samples at "
                    "{:.3g} s)",
                    segment, count, dt),
        series);
    plot.plot_areas.push_back(chart.plot_area());
  }
  return plot;
}

}  // namespace fw::viz
