#include "viz/ModeShapes.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <cmath>
#include <stdexcept>

#include "viz/ColourMap.hpp"

namespace fw::viz {

namespace {

constexpr int kPanelWidth = 300, kPanelHeight = 360, kTitleHeight = 44, kLabelHeight = 44;
constexpr double kPanelPadding = 18.0;  // px around the tree in its panel
constexpr double kThinnest = 0.8;       // px
const Rgb kInk{0.1, 0.1, 0.1}, kRest{0.80, 0.80, 0.80}, kGround{0.45, 0.35, 0.25}, kFrame{0.85, 0.85, 0.85};

}  // namespace

Canvas draw_mode_shapes(const trees::Skeleton& skeleton, const std::vector<io::ModeShape>& modes,
                        const std::string& title) {
  if (modes.empty()) throw std::invalid_argument("draw_mode_shapes: expected at least one mode");
  const int count = std::min<int>(kModesDrawn, int(modes.size()));
  for (int m = 0; m < count; ++m)
    if (modes[std::size_t(m)].displacement.rows() != skeleton.size())
      throw std::invalid_argument(fmt::format("draw_mode_shapes: mode {} has {} rows for {} nodes", m + 1,
                                              modes[std::size_t(m)].displacement.rows(), skeleton.size()));
  Canvas canvas(kPanelWidth * count, kTitleHeight + kPanelHeight + kLabelHeight, {1, 1, 1});
  canvas.text({14, 28},
              fmt::format("{}: the first {} modes (shapes exaggerated to {:.0f}% of the height)", title,
                          count, 100 * kExaggeration),
              15.0, kInk);
  const double height = std::max(skeleton.height(), 1e-6);
  const Eigen::AlignedBox3d box = skeleton.bounding_box();
  const ColourMap& map = ColourMap::named("displacement");

  for (int m = 0; m < count; ++m) {
    const Eigen::MatrixX3d& phi = modes[std::size_t(m)].displacement;
    const int axis = phi.col(0).squaredNorm() >= phi.col(1).squaredNorm() ? 0 : 1;  // the plane of the motion
    const double largest = phi.rowwise().norm().maxCoeff();
    const double scale = largest > 0.0 ? kExaggeration * height / largest : 0.0;
    // One metre the same number of pixels in every panel: the rest shape's extent plus the sway's room.
    const double across = std::max(box.sizes()(0), box.sizes()(1)) + 2 * kExaggeration * height;
    const double ppm =
        std::min((kPanelWidth - 2 * kPanelPadding) / across,
                 (kPanelHeight - 2 * kPanelPadding) / (box.sizes()(2) + kExaggeration * height));
    const double x0 = m * kPanelWidth + 0.5 * kPanelWidth,
                 ground = kTitleHeight + kPanelHeight - kPanelPadding;
    const double centre = 0.5 * (box.min()(axis) + box.max()(axis));
    auto to_pixel = [&](const Eigen::Vector3d& p) {
      return Point2{x0 + (p(axis) - centre) * ppm, ground - (p(2) - box.min()(2)) * ppm};
    };
    canvas.stroke_rect(m * kPanelWidth + 4, kTitleHeight, kPanelWidth - 8, kPanelHeight, kFrame, 1.0);
    canvas.line({{m * kPanelWidth + 12.0, ground}, {(m + 1) * kPanelWidth - 12.0, ground}}, kGround, 1.5);
    for (const auto& [parent, child] : skeleton.elements()) {
      const auto& a = skeleton.node(parent);
      const auto& b = skeleton.node(child);
      const double width = std::max(kThinnest, (a.radius + b.radius) * ppm);
      canvas.line({to_pixel(a.position), to_pixel(b.position)}, kRest, width);
    }
    for (const auto& [parent, child] : skeleton.elements()) {
      const auto& a = skeleton.node(parent);
      const auto& b = skeleton.node(child);
      const Eigen::Vector3d pa = a.position + scale * phi.row(parent).transpose();
      const Eigen::Vector3d pb = b.position + scale * phi.row(child).transpose();
      const double d = largest > 0.0 ? 0.5 * (phi.row(parent).norm() + phi.row(child).norm()) / largest : 0.0;
      const double width = std::max(kThinnest, (a.radius + b.radius) * ppm);
      canvas.line({to_pixel(pa), to_pixel(pb)}, map.colour(d), width);
    }
    const double label_y = kTitleHeight + kPanelHeight + 20;
    canvas.text({x0, label_y}, fmt::format("mode {}: {:.3f} Hz", m + 1, modes[std::size_t(m)].frequency_hz),
                14.0, kInk, Align::centre);
    canvas.text({x0, label_y + 17}, axis == 0 ? "seen in the x-z plane" : "seen in the y-z plane", 11.0, kInk,
                Align::centre);
  }
  return canvas;
}

}  // namespace fw::viz
