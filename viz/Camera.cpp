#include "viz/Camera.hpp"

#include <glm/gtc/matrix_transform.hpp>

#include <algorithm>
#include <cmath>

namespace fw::viz {

namespace {

// The perspective view: a 35-degree vertical field of view (a normal lens), the eye south-west of the
// domain and above it, far enough that the whole domain fits.
constexpr double kFieldOfViewDegrees = 35.0;
const glm::dvec3 kPerspectiveDirection = glm::normalize(glm::dvec3(-0.55, -1.0, 0.75));  // eye from centre
constexpr double kPerspectiveDistance = 1.25;  // eye distance in units of the domain's diagonal

double perspective_aspect(const Viewport& v) {
  return v.width / std::max(v.height, 1.0);
}

}  // namespace

Camera::Camera(ViewKind kind, const glm::dmat4& view, const glm::dmat4& projection, const Viewport& viewport,
               const Box& domain)
    : kind_(kind), view_(view), projection_(projection), viewport_(viewport) {
  const glm::dvec3 c = domain.centre();
  const Point2 a = to_pixel(c), b = to_pixel(c + glm::dvec3(1.0, 0.0, 0.0));
  pixels_per_metre_ = std::hypot(b.x - a.x, b.y - a.y);
}

Camera Camera::top(const Box& domain, const Viewport& viewport) {
  const glm::dvec3 c = domain.centre(), s = domain.size();
  const glm::dmat4 view = glm::lookAt(glm::dvec3(c.x, c.y, domain.hi.z + 1.0), c, glm::dvec3(0, 1, 0));
  const glm::dmat4 projection = glm::ortho(-0.5 * s.x, 0.5 * s.x, -0.5 * s.y, 0.5 * s.y, 0.0, s.z + 2.0);
  return Camera(ViewKind::top, view, projection, viewport, domain);
}

Camera Camera::side(const Box& domain, const Viewport& viewport) {
  const glm::dvec3 c = domain.centre(), s = domain.size();
  const glm::dmat4 view = glm::lookAt(glm::dvec3(c.x, domain.lo.y - 1.0, c.z), c, glm::dvec3(0, 0, 1));
  const glm::dmat4 projection = glm::ortho(-0.5 * s.x, 0.5 * s.x, -0.5 * s.z, 0.5 * s.z, 0.0, s.y + 2.0);
  return Camera(ViewKind::side, view, projection, viewport, domain);
}

Camera Camera::perspective(const Box& domain, const Viewport& viewport) {
  const glm::dvec3 c = domain.centre();
  const double diagonal = glm::length(domain.size());
  const glm::dvec3 eye = c + kPerspectiveDistance * diagonal * kPerspectiveDirection;
  const glm::dmat4 view = glm::lookAt(eye, c, glm::dvec3(0, 0, 1));
  const glm::dmat4 projection = glm::perspective(
      glm::radians(kFieldOfViewDegrees), perspective_aspect(viewport), 0.01 * diagonal, 4.0 * diagonal);
  return Camera(ViewKind::perspective, view, projection, viewport, domain);
}

Camera Camera::of(ViewKind kind, const Box& domain, const Viewport& viewport) {
  switch (kind) {
    case ViewKind::top:
      return top(domain, viewport);
    case ViewKind::side:
      return side(domain, viewport);
    case ViewKind::perspective:
      break;
  }
  return perspective(domain, viewport);
}

Viewport Camera::fit_viewport(ViewKind kind, const Box& domain, const Viewport& available) {
  if (kind == ViewKind::perspective) return available;
  const glm::dvec3 s = domain.size();
  const double aspect = kind == ViewKind::top ? s.x / s.y : s.x / s.z;  // width over height
  double width = available.width, height = width / aspect;
  if (height > available.height) height = available.height, width = height * aspect;
  return {available.x + 0.5 * (available.width - width), available.y + 0.5 * (available.height - height),
          width, height};
}

Point2 Camera::to_pixel(const glm::dvec3& world) const {
  const glm::dvec4 clip = projection_ * view_ * glm::dvec4(world, 1.0);
  const double x = clip.x / clip.w, y = clip.y / clip.w;
  return {viewport_.x + 0.5 * (x + 1.0) * viewport_.width, viewport_.y + 0.5 * (1.0 - y) * viewport_.height};
}

double Camera::depth(const glm::dvec3& world) const {
  return -(view_ * glm::dvec4(world, 1.0)).z;
}

}  // namespace fw::viz
