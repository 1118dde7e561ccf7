#include "viz/ProfilePlots.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <cmath>
#include <functional>
#include <limits>
#include <stdexcept>

namespace fw::viz {

namespace {

constexpr double kTitleHeight = 40.0;  // px above the panels for the scenario, region and time
const Rgb kInk{0.1, 0.1, 0.1}, kEarlier{0.78, 0.78, 0.78};
constexpr double kEarlierWidth = 0.8;  // px: the earlier records, behind the last one
constexpr double kDash = 6.0;          // px: the mean's standard-deviation envelope

// [record][k] of one variable, by name.
class Columns {
 public:
  Columns(const io::StatsFile& stats, const std::vector<std::vector<std::vector<double>>>& values)
      : stats_(stats), values_(values) {}
  /// Variable `name` of record r at every height.
  const std::vector<double>& at(const std::string& name, std::size_t r) const {
    const auto& v = stats_.profiles.variables;
    for (std::size_t n = 0; n < v.size(); ++n)
      if (v[n].name == name) return values_[r][n];
    throw std::invalid_argument(fmt::format("plot: stats.nc has no profile {}", name));
  }
  std::size_t records() const { return values_.size(); }

 private:
  const io::StatsFile& stats_;
  const std::vector<std::vector<std::vector<double>>>& values_;
};

// Third moment over the variance to the 3/2; NaN where the variance is 0 (no resolved fluctuation).
double skewness(double third, double variance) {
  return variance > 0.0 ? third / std::pow(variance, 1.5) : std::numeric_limits<double>::quiet_NaN();
}

// A line of a panel: its label and how to get its values from record r.
struct Line {
  std::string label;
  std::function<std::vector<double>(std::size_t)> values;
  double dash = 0.0;
};

}  // namespace

ProfilePlot plot_profiles(const io::StatsFile& stats, const std::string& region,
                          const ProfilePlotSettings& settings) {
  const std::vector<std::vector<std::vector<double>>>* values = &stats.profiles.values;
  if (!region.empty()) {
    values = nullptr;
    std::string names;
    for (const io::StatsRegion& r : stats.regions) {
      if (r.name == region) values = &r.values;
      names += (names.empty() ? "" : ", ") + r.name;
    }
    if (!values)
      throw std::invalid_argument(fmt::format("plot: --region {}: stats.nc has no such region ({})", region,
                                              names.empty() ? "it has none" : "it has " + names));
  }
  if (values->empty()) throw std::invalid_argument("plot: stats.nc holds no profile record yet");
  const Columns c(stats, *values);
  const std::size_t nz = stats.z.size(), last = c.records() - 1;
  const auto column = [&](const char* name) {
    return std::function<std::vector<double>(std::size_t)>(
        [&c, name](std::size_t r) { return c.at(name, r); });
  };
  const auto plus_sigma = [&](double sign) {
    return std::function<std::vector<double>(std::size_t)>([&c, nz, sign](std::size_t r) {
      const std::vector<double>&u = c.at("u", r), &u_2 = c.at("u_2", r);
      std::vector<double> out(nz);
      for (std::size_t k = 0; k < nz; ++k) out[k] = u[k] + sign * std::sqrt(std::max(0.0, u_2[k]));
      return out;
    });
  };
  const auto skew = [&](const char* third, const char* variance) {
    return std::function<std::vector<double>(std::size_t)>([&c, nz, third, variance](std::size_t r) {
      const std::vector<double>&m3 = c.at(third, r), &m2 = c.at(variance, r);
      std::vector<double> out(nz);
      for (std::size_t k = 0; k < nz; ++k) out[k] = skewness(m3[k], m2[k]);
      return out;
    });
  };
  struct Panel {
    std::string name, title, x_title;
    std::vector<Line> lines;
  };
  std::vector<Panel> panels{
      {"mean",
       "mean wind",
       "wind (m/s)",
       {{"u", column("u")},
        {"v", column("v")},
        {"w", column("w")},
        {"u +- sd", plus_sigma(1.0), kDash},
        {"", plus_sigma(-1.0), kDash}}},
      {"flux",
       "vertical momentum flux",
       "flux (m2/s2)",
       {{"u_w (resolved)", column("u_w")},
        {"u_diff (subgrid)", column("u_diff")},
        {"u_flux (total)", column("u_flux")},
        {"v_flux (total)", column("v_flux")}}},
      {"variance",
       "variances and kinetic energy",
       "variance (m2/s2)",
       {{"u_2", column("u_2")},
        {"v_2", column("v_2")},
        {"w_2", column("w_2")},
        {"tke", column("tke")},
        {"sgs_tke", column("sgs_tke")}}},
      {"skewness", "skewness", "skewness", {{"u", skew("u_3", "u_2")}, {"w", skew("w_3", "w_2")}}},
  };
  const std::vector<double>& lad = c.at("lad", last);
  if (std::any_of(lad.begin(), lad.end(), [](double a) { return a > 0.0; }))
    panels.push_back({"canopy", "canopy drag density", "lad (1/m)", {{"lad", column("lad")}}});
  ProfilePlot plot{Canvas(settings.panel_width * int(panels.size()), settings.height, {1, 1, 1}), {}, {}};
  const double t = stats.profiles.time[last];
  const std::string window = stats.averaging > 0.0
                                 ? fmt::format("averaged over the {:g} s before it", stats.averaging)
                                 : "one sample";
  plot.canvas.text(
      {60, 26},
      fmt::format("{}{}: profiles at t = {:g} s ({}; record {} of {}, the earlier ones in grey)", stats.title,
                  region.empty() ? "" : ", region " + region, t, window, last + 1, c.records()),
      17.0, kInk);
  for (std::size_t p = 0; p < panels.size(); ++p) {
    std::vector<Series> series;
    // The earlier records first, unlabelled, so that the last one draws over them.
    for (std::size_t r = 0; r < last; ++r)
      for (const Line& line : panels[p].lines)
        if (line.dash == 0.0) series.push_back({"", line.values(r), stats.z, kEarlier, kEarlierWidth});
    for (std::size_t n = 0; n < panels[p].lines.size(); ++n) {
      const Line& line = panels[p].lines[n];
      // The envelope in the colour of the line it surrounds (u's).
      const Rgb colour = line.dash > 0.0 ? series_colour(0) : series_colour(n);
      series.push_back({line.label, line.values(last), stats.z, colour, 1.8, line.dash});
    }
    const Viewport panel{double(p) * settings.panel_width, kTitleHeight, double(settings.panel_width),
                         double(settings.height) - kTitleHeight};
    const ChartAxes axes{.x_title = panels[p].x_title, .y_title = "height (m)"};
    const Chart chart(plot.canvas, panel, axes, panels[p].title, series);
    plot.plot_areas.push_back(chart.plot_area());
    plot.panels.push_back(panels[p].name);
  }
  return plot;
}

}  // namespace fw::viz
