#include "viz/DamageMap.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <numeric>
#include <stdexcept>
#include <tuple>

#include "viz/ColourBar.hpp"

namespace fw::viz {

namespace {

using trees::TreeState;

constexpr double kCrownPerHeight = 0.15;  // a disc's radius per metre of the tree's height
constexpr double kOutline = 1.2;          // px of dark ring around a disc
constexpr double kLabelSize = 12.0, kLegendRow = 20.0, kLegendDisc = 7.0;
const Rgb kInk{0.1, 0.1, 0.1}, kMarkInk{0.0, 0.0, 0.0}, kHalo{1.0, 1.0, 1.0};

// A tree at `c` with a disc of radius r, filled with `fill`, marked by its state.
void draw_tree(Canvas& canvas, Point2 c, double r, Rgb fill, TreeState state) {
  canvas.disc(c, r + kOutline, kInk);
  canvas.disc(c, r, fill);
  const double stroke = std::clamp(0.18 * r, 1.5, 4.0);
  if (state == TreeState::broken) {
    const double a = std::max(0.7 * r, 3.0);
    const std::vector<std::array<Point2, 2>> cross{{Point2{c.x - a, c.y - a}, Point2{c.x + a, c.y + a}},
                                                   {Point2{c.x - a, c.y + a}, Point2{c.x + a, c.y - a}}};
    canvas.segments(cross, kHalo, stroke + 2.5);
    canvas.segments(cross, kMarkInk, stroke);
  } else if (state == TreeState::overturned) {
    const double s = std::max(0.45 * r, 2.5), halo = 0.5 * stroke;
    canvas.fill_rect(c.x - s - halo, c.y - s - halo, 2 * (s + halo), 2 * (s + halo), kHalo);
    canvas.fill_rect(c.x - s, c.y - s, 2 * s, 2 * s, kMarkInk);
  }
}

// The utilisation bar with its line at failure, and the legend of the marks with the counts, in the place
// of the trees' colour bar.
void draw_key(Canvas& canvas, const RenderSettings& settings, const std::array<int, 3>& counts, double time) {
  const Viewport place = colour_bar_place(settings, 1);
  const double legend = 30.0 + 4 * kLegendRow;  // the gap, its heading and three rows
  const double height =
      std::clamp(settings.height_px - 8.0 - place.y - legend, 40.0, std::max(40.0, 0.2 * settings.height_px));
  const Viewport bar{place.x, place.y, place.width, height};
  const ColourMap& map = ColourMap::named("utilisation");
  draw_colour_bar(canvas, bar, map, 0.0, kUtilisationTop, "max utilisation");
  const double y1 = bar.y + bar.height * (1.0 - 1.0 / kUtilisationTop);
  canvas.line({{bar.x - 4, y1}, {bar.x + bar.width + 5, y1}}, kMarkInk, 2.0);
  // After the bar's tick labels (0.5 steps: "1.0" is the widest).
  canvas.text({bar.x + bar.width + 15 + canvas.text_width("1.0", kLabelSize), y1 + 4}, "failure", kLabelSize,
              kInk);

  double y = bar.y + bar.height + 30.0;
  canvas.text({bar.x, y}, fmt::format("trees at t = {:.2f} s", time), kLabelSize + 1, kInk);
  const char* words[] = {"standing", "broken", "overturned"};
  for (int n = 0; n < 3; ++n) {
    y += kLegendRow;
    draw_tree(canvas, {bar.x + kLegendDisc, y - 4}, kLegendDisc, map.colour(n == 0 ? 0.3 : 0.8),
              TreeState(n));
    canvas.text({bar.x + 2 * kLegendDisc + 8, y}, fmt::format("{} {}", words[n], counts[std::size_t(n)]),
                kLabelSize, kInk);
  }
}

}  // namespace

RenderSettings damage_map_settings(RenderSettings settings) {
  if (settings.view != ViewKind::top)
    throw std::invalid_argument("render: --field damage: draws the top view only (--view top)");
  settings.trees = false;
  return settings;
}

DamageMap::DamageMap(const FrameData& frame, const DamageTable& damage, const std::string& scenario,
                     const RenderSettings& settings)
    : picture_(frame, scenario, damage_map_settings(settings)), counts_(damage.counts_at(frame.time)) {
  Canvas& canvas = picture_.canvas();
  const Camera& camera = picture_.camera();
  const ColourMap& map = ColourMap::named("utilisation");
  // Standing trees first, then the failed ones (their marks on top), each group from the least loaded up.
  std::vector<std::size_t> order(damage.trees.size());
  std::iota(order.begin(), order.end(), std::size_t(0));
  auto key = [&](std::size_t n) {
    const DamagedTree& t = damage.trees[n];
    return std::make_tuple(t.state_at(frame.time) != TreeState::standing, t.max_utilisation, t.id);
  };
  std::sort(order.begin(), order.end(), [&](std::size_t a, std::size_t b) { return key(a) < key(b); });
  const Viewport& v = camera.viewport();
  canvas.clip(v.x, v.y, v.width, v.height);
  for (const std::size_t n : order) {
    const DamagedTree& t = damage.trees[n];
    const double z = picture_.slice_position();
    draw_tree(canvas, camera.to_pixel({t.x, t.y, z}), disc_radius(t),
              map.colour(t.max_utilisation, 0.0, kUtilisationTop), t.state_at(frame.time));
  }
  canvas.reset_clip();
  draw_key(canvas, settings, counts_, frame.time);
}

double DamageMap::disc_radius(const DamagedTree& tree) const {
  return std::max(kSmallestDisc, kCrownPerHeight * tree.height * picture_.camera().pixels_per_metre());
}

}  // namespace fw::viz
