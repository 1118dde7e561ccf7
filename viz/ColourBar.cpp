#include "viz/ColourBar.hpp"

#include <algorithm>
#include <cmath>
#include <vector>

#include "viz/Ticks.hpp"

namespace fw::viz {

namespace {
constexpr double kTickLength = 5.0, kLabelSize = 12.0, kTitleSize = 13.0;
constexpr int kTicks = 5;
const Rgb kInk{0.1, 0.1, 0.1};
}  // namespace

void draw_colour_bar(Canvas& canvas, const Viewport& bar, const ColourMap& map, double lo, double hi,
                     const std::string& title) {
  const int rows = std::max(2, int(std::lround(bar.height)));
  std::vector<Rgb> pixels(static_cast<std::size_t>(rows));
  // Row r of the bar shows the value at its centre, hi at the top.
  for (int r = 0; r < rows; ++r) pixels[std::size_t(r)] = map.colour(1.0 - (r + 0.5) / rows);
  canvas.image(pixels, 1, rows, bar.x, bar.y, bar.width, bar.height);
  canvas.stroke_rect(bar.x, bar.y, bar.width, bar.height, kInk, 1.0);
  const std::vector<double> ticks = nice_ticks(lo, hi, kTicks);
  for (double value : ticks) {
    const double y = bar.y + bar.height * (1.0 - (value - lo) / (hi - lo));
    canvas.line({{bar.x + bar.width, y}, {bar.x + bar.width + kTickLength, y}}, kInk, 1.0);
    canvas.text({bar.x + bar.width + kTickLength + 4, y + 4}, tick_label(value, tick_step(ticks)), kLabelSize,
                kInk);
  }
  canvas.text({bar.x, bar.y - 10}, title, kTitleSize, kInk);
}

}  // namespace fw::viz
