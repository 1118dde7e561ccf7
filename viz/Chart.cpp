#include "viz/Chart.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <cmath>
#include <limits>
#include <stdexcept>

#include "viz/Ticks.hpp"

namespace fw::viz {

namespace {

constexpr double kMarginLeft = 78.0, kMarginRight = 170.0, kMarginTop = 34.0, kMarginBottom = 48.0;
constexpr double kLabelSize = 12.0, kTitleSize = 14.0, kLegendRow = 17.0;
constexpr double kMarkerLength = 6.0;
constexpr double kRangePadding = 0.05;  // of the span, above and below a linear data range
const Rgb kInk{0.1, 0.1, 0.1}, kGridLine{0.88, 0.88, 0.88}, kMarker{0.45, 0.45, 0.45}, kWhite{1, 1, 1};

// Qualitative colours, distinguishable from each other and on white (our own set).
const Rgb kSeriesColours[] = {{0.12, 0.38, 0.72}, {0.85, 0.37, 0.05}, {0.16, 0.60, 0.25}, {0.78, 0.12, 0.20},
                              {0.50, 0.30, 0.70}, {0.55, 0.35, 0.20}, {0.85, 0.40, 0.65}, {0.35, 0.35, 0.35}};

std::array<double, 2> data_range(const std::vector<Series>& series, bool x_axis, bool log) {
  double lo = std::numeric_limits<double>::max(), hi = std::numeric_limits<double>::lowest();
  for (const Series& s : series)
    for (double v : x_axis ? s.x : s.y)
      if (std::isfinite(v) && (!log || v > 0.0)) lo = std::min(lo, v), hi = std::max(hi, v);
  if (lo > hi) return log ? std::array<double, 2>{1.0, 10.0} : std::array<double, 2>{0.0, 1.0};
  if (log) return hi > lo ? std::array<double, 2>{lo, hi} : std::array<double, 2>{lo / 10.0, hi * 10.0};
  if (!(hi > lo)) return {lo - 1.0, hi + 1.0};
  if (x_axis) return {lo, hi};
  const double pad = kRangePadding * (hi - lo);
  return {lo - pad, hi + pad};
}

}  // namespace

Rgb series_colour(std::size_t n) {
  return kSeriesColours[n % std::size(kSeriesColours)];
}

double Chart::axis_fraction(double value, const std::array<double, 2>& range, bool log) const {
  if (log) return (std::log10(value) - std::log10(range[0])) / (std::log10(range[1]) - std::log10(range[0]));
  return (value - range[0]) / (range[1] - range[0]);
}

Point2 Chart::to_pixel(double x, double y) const {
  return {area_.x + area_.width * axis_fraction(x, x_, log_x_),
          area_.y + area_.height * (1.0 - axis_fraction(y, y_, log_y_))};
}

Chart::Chart(Canvas& canvas, const Viewport& panel, const ChartAxes& axes, const std::string& title,
             const std::vector<Series>& series, const std::vector<double>& markers)
    : log_x_(axes.log_x), log_y_(axes.log_y) {
  for (const Series& s : series)
    if (s.x.size() != s.y.size())
      throw std::invalid_argument(
          fmt::format("Chart: series '{}': {} x values but {} y values", s.label, s.x.size(), s.y.size()));
  // Edges on pixel centres, so that the 1 px frame and grid lines are crisp.
  area_ = {pixel_centre(panel.x + kMarginLeft), pixel_centre(panel.y + kMarginTop),
           std::round(panel.width - kMarginLeft - kMarginRight),
           std::round(panel.height - kMarginTop - kMarginBottom)};
  if (area_.width < 50.0 || area_.height < 40.0)
    throw std::invalid_argument(
        fmt::format("Chart: a panel of {} x {} px is too small", panel.width, panel.height));
  x_ = axes.x_range.value_or(data_range(series, true, log_x_));
  y_ = axes.y_range.value_or(data_range(series, false, log_y_));

  // Grid and ticks.
  const std::vector<double> xt = log_x_ ? log_ticks(x_[0], x_[1]) : nice_ticks(x_[0], x_[1], 8);
  const std::vector<double> yt = log_y_ ? log_ticks(y_[0], y_[1]) : nice_ticks(y_[0], y_[1], 6);
  auto label = [&](double v, const std::vector<double>& ticks, bool log) {
    return log ? fmt::format("{:g}", v) : tick_label(v, tick_step(ticks));
  };
  for (double v : xt) {
    const double px = pixel_centre(to_pixel(v, y_[0]).x);
    canvas.line({{px, area_.y}, {px, area_.y + area_.height}}, kGridLine, 1.0);
    canvas.line({{px, area_.y + area_.height}, {px, area_.y + area_.height + 5}}, kInk, 1.0);
    canvas.text({px, area_.y + area_.height + 18}, label(v, xt, log_x_), kLabelSize, kInk, Align::centre);
  }
  for (double v : yt) {
    const double py = pixel_centre(to_pixel(x_[0], v).y);
    canvas.line({{area_.x, py}, {area_.x + area_.width, py}}, kGridLine, 1.0);
    canvas.line({{area_.x - 5, py}, {area_.x, py}}, kInk, 1.0);
    canvas.text({area_.x - 8, py + 4}, label(v, yt, log_y_), kLabelSize, kInk, Align::right);
  }
  canvas.text({area_.x + 0.5 * area_.width, area_.y + area_.height + 38}, axes.x_title, kLabelSize, kInk,
              Align::centre);
  canvas.text({panel.x + 18, area_.y + 0.5 * area_.height}, axes.y_title, kLabelSize, kInk, Align::centre,
              90.0);
  canvas.text({area_.x, panel.y + 22}, title, kTitleSize, kInk);

  // Frame markers along the top edge.
  for (double m : markers) {
    if (m < x_[0] || m > x_[1]) continue;
    const double px = to_pixel(m, y_[1]).x;
    canvas.line({{px, area_.y}, {px, area_.y + kMarkerLength}}, kMarker, 1.0);
  }

  // The lines, clipped to the plot area, broken at non-finite values (and at non-positive ones on log axes).
  canvas.clip(area_.x, area_.y, area_.width, area_.height);
  for (const Series& s : series) {
    std::vector<Point2> run;
    auto flush = [&] {
      if (run.size() >= 2) canvas.line(run, s.colour, s.width, s.dash);
      run.clear();
    };
    for (std::size_t n = 0; n < s.x.size(); ++n) {
      const bool usable = std::isfinite(s.x[n]) && std::isfinite(s.y[n]) && (!log_x_ || s.x[n] > 0.0) &&
                          (!log_y_ || s.y[n] > 0.0);
      if (!usable) {
        flush();
        continue;
      }
      run.push_back(to_pixel(s.x[n], s.y[n]));
    }
    flush();
  }
  canvas.reset_clip();
  canvas.stroke_rect(area_.x, area_.y, area_.width, area_.height, kInk, 1.0);

  // Legend: right of the plot area, one row per labelled series (and the frame markers).
  std::vector<std::pair<std::string, const Series*>> rows;
  for (const Series& s : series)
    if (!s.label.empty()) rows.emplace_back(s.label, &s);
  if (!markers.empty()) rows.emplace_back("output frames", nullptr);
  if (rows.empty()) return;
  double widest = 0.0;
  for (const auto& row : rows) widest = std::max(widest, canvas.text_width(row.first, kLabelSize));
  const double box_w = widest + 44.0, box_h = kLegendRow * rows.size() + 8.0;
  const double bx = area_.x + area_.width + 12.0, by = area_.y;
  canvas.fill_rect(bx, by, box_w, box_h, kWhite);
  canvas.stroke_rect(bx, by, box_w, box_h, kGridLine, 1.0);
  for (std::size_t n = 0; n < rows.size(); ++n) {
    const double y = by + 4.0 + kLegendRow * (n + 0.5);
    if (rows[n].second)
      canvas.line({{bx + 6, y}, {bx + 30, y}}, rows[n].second->colour, rows[n].second->width,
                  rows[n].second->dash);
    else
      canvas.line({{bx + 18, y - 5}, {bx + 18, y + 5}}, kMarker, 1.0);
    canvas.text({bx + 36, y + 4}, rows[n].first, kLabelSize, kInk);
  }
}

}  // namespace fw::viz
