// A line chart drawn into a panel of a picture: axes with round-numbered ticks (linear or log), axis titles
// with units, lines, a legend, and optional markers along the top (the times of the output frames).
//
//   fw::viz::Canvas canvas(1200, 500, {1, 1, 1});
//   fw::viz::ChartAxes axes{"time (s)", "wind speed (m/s)"};
//   fw::viz::Chart chart(canvas, {0, 0, 1200, 500}, axes, "probes",
//                        {{"mast", t, speed, fw::viz::series_colour(0)}}, /*markers=*/frame_times);
#pragma once

#include <array>
#include <optional>
#include <string>
#include <vector>

#include "viz/Camera.hpp"
#include "viz/Canvas.hpp"

namespace fw::viz {

struct Series {
  std::string label;
  std::vector<double> x, y;  ///< same length; non-finite values break the line
  Rgb colour;
  double width = 1.5;  ///< px
  double dash = 0.0;   ///< px; 0 draws it solid
};

struct ChartAxes {
  std::string x_title, y_title;  ///< with units, e.g. "time (s)"
  bool log_x = false, log_y = false;
  /// Default: the data's (log: positive data only). Initialised so that a designated initializer may leave
  /// them out without -Wmissing-field-initializers.
  std::optional<std::array<double, 2>> x_range = std::nullopt;
  std::optional<std::array<double, 2>> y_range = std::nullopt;
};

class Chart {
 public:
  /// Draws the chart into `panel` (px; the plot area leaves room for the ticks, titles and legend).
  /// Throws std::invalid_argument("Chart: ...") for a series whose x and y differ in length or a panel too
  /// small for its margins.
  Chart(Canvas& canvas, const Viewport& panel, const ChartAxes& axes, const std::string& title,
        const std::vector<Series>& series, const std::vector<double>& markers = {});

  /// The rectangle inside the axes, px.
  const Viewport& plot_area() const { return area_; }
  /// The data ranges the axes show.
  const std::array<double, 2>& x_range() const { return x_; }
  const std::array<double, 2>& y_range() const { return y_; }
  /// Pixel position of a data point.
  Point2 to_pixel(double x, double y) const;

 private:
  double axis_fraction(double value, const std::array<double, 2>& range, bool log) const;
  Viewport area_;
  std::array<double, 2> x_{0.0, 1.0}, y_{0.0, 1.0};
  bool log_x_ = false, log_y_ = false;
};

/// Line colours for series n = 0, 1, ... (eight distinct colours, then repeating).
Rgb series_colour(std::size_t n);

}  // namespace fw::viz
