// Where a point of the world lands in a picture: the three views of `forestwind render`, built with GLM.
//
//   fw::viz::Box domain{{0, 0, 0}, {256, 256, 64}};
//   fw::viz::Camera top = fw::viz::Camera::top(domain, {80, 60, 800, 800});
//   fw::viz::Point2 p = top.to_pixel({128.0, 40.0, 10.0});   // px, y down
//
//   top          orthographic, looking down -z: x to the right, north (+y) up
//   side         orthographic, looking north (+y) from the south: x to the right, z up
//   perspective  a 35-degree lens from the south-west, above, looking at the domain's centre
// The viewport is the pixel rectangle the domain's projection fills; for the orthographic views its aspect
// is the domain's (fit_viewport picks it), so a metre is the same number of pixels across and up.
#pragma once

#include <array>

#include <glm/glm.hpp>

#include "viz/Canvas.hpp"

namespace fw::viz {

/// An axis-aligned box of the world, m.
struct Box {
  glm::dvec3 lo{0.0}, hi{0.0};
  glm::dvec3 size() const { return hi - lo; }
  glm::dvec3 centre() const { return 0.5 * (lo + hi); }
};

/// A pixel rectangle.
struct Viewport {
  double x = 0.0, y = 0.0, width = 0.0, height = 0.0;
};

enum class ViewKind { top, side, perspective };

class Camera {
 public:
  static Camera top(const Box& domain, const Viewport& viewport);
  static Camera side(const Box& domain, const Viewport& viewport);
  static Camera perspective(const Box& domain, const Viewport& viewport);
  static Camera of(ViewKind kind, const Box& domain, const Viewport& viewport);

  /// The largest rectangle inside `available` with the aspect the view gives `domain` (centred).
  static Viewport fit_viewport(ViewKind kind, const Box& domain, const Viewport& available);

  /// Pixel position of a world point (m).
  Point2 to_pixel(const glm::dvec3& world) const;
  /// Distance from the eye along the view direction (m): larger is farther; for painting far to near.
  double depth(const glm::dvec3& world) const;
  /// Pixels per metre at the domain's centre (exact everywhere in the orthographic views).
  double pixels_per_metre() const { return pixels_per_metre_; }
  const Viewport& viewport() const { return viewport_; }
  ViewKind kind() const { return kind_; }

 private:
  Camera(ViewKind kind, const glm::dmat4& view, const glm::dmat4& projection, const Viewport& viewport,
         const Box& domain);
  ViewKind kind_;
  glm::dmat4 view_, projection_;
  Viewport viewport_;
  double pixels_per_metre_ = 1.0;
};

}  // namespace fw::viz
