#include "viz/ColourMap.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <cmath>
#include <stdexcept>

namespace fw::viz {

namespace {

// sRGB <-> CIELAB through linear RGB and CIE XYZ with the D65 white (IEC 61966-2-1, CIE 15).
constexpr double kWhiteX = 0.95047, kWhiteY = 1.0, kWhiteZ = 1.08883;
constexpr double kLabEpsilon = 216.0 / 24389.0, kLabKappa = 24389.0 / 27.0;
// The utilisation map's scale runs 0 .. kUtilisationTop; a utilisation of 1 (failure) sits here on it.
constexpr double kUtilisationFailure = 1.0 / kUtilisationTop;

double to_linear(double c) {
  return c <= 0.04045 ? c / 12.92 : std::pow((c + 0.055) / 1.055, 2.4);
}
double to_srgb(double c) {
  c = std::clamp(c, 0.0, 1.0);
  return c <= 0.0031308 ? 12.92 * c : 1.055 * std::pow(c, 1.0 / 2.4) - 0.055;
}
double lab_f(double t) {
  return t > kLabEpsilon ? std::cbrt(t) : (kLabKappa * t + 16.0) / 116.0;
}
double lab_f_inverse(double f) {
  const double t = f * f * f;
  return t > kLabEpsilon ? t : (116.0 * f - 16.0) / kLabKappa;
}

std::array<double, 3> to_lab(const Rgb& c) {
  const double r = to_linear(c.r), g = to_linear(c.g), b = to_linear(c.b);
  const double x = 0.4124564 * r + 0.3575761 * g + 0.1804375 * b;
  const double y = 0.2126729 * r + 0.7151522 * g + 0.0721750 * b;
  const double z = 0.0193339 * r + 0.1191920 * g + 0.9503041 * b;
  const double fx = lab_f(x / kWhiteX), fy = lab_f(y / kWhiteY), fz = lab_f(z / kWhiteZ);
  return {116.0 * fy - 16.0, 500.0 * (fx - fy), 200.0 * (fy - fz)};
}

Rgb from_lab(const std::array<double, 3>& lab) {
  const double fy = (lab[0] + 16.0) / 116.0, fx = fy + lab[1] / 500.0, fz = fy - lab[2] / 200.0;
  const double x = kWhiteX * lab_f_inverse(fx), y = kWhiteY * lab_f_inverse(fy),
               z = kWhiteZ * lab_f_inverse(fz);
  const double r = 3.2404542 * x - 1.5371385 * y - 0.4985314 * z;
  const double g = -0.9692660 * x + 1.8760108 * y + 0.0415560 * z;
  const double b = 0.0556434 * x - 0.2040259 * y + 1.0572252 * z;
  return {to_srgb(r), to_srgb(g), to_srgb(b)};
}

std::vector<ColourMap> make_named_maps() {
  const Rgb no_data{0.5, 0.5, 0.5};
  return {
      ColourMap("wind",
                {{0.0, {0.09, 0.05, 0.36}},
                 {0.25, {0.14, 0.33, 0.62}},
                 {0.5, {0.10, 0.60, 0.58}},
                 {0.75, {0.52, 0.80, 0.32}},
                 {1.0, {0.99, 0.92, 0.20}}},
                no_data),
      ColourMap("displacement",
                {{0.0, {0.22, 0.12, 0.05}}, {0.5, {0.86, 0.24, 0.10}}, {1.0, {1.0, 0.95, 0.72}}}, no_data),
      ColourMap("diverging",
                {{0.0, {0.230, 0.299, 0.754}}, {0.5, {0.865, 0.865, 0.865}}, {1.0, {0.706, 0.016, 0.150}}},
                no_data),
      // Greys darkening up to a utilisation of 1 (of 1.5), then reds: a step of hue at failure.
      ColourMap("utilisation",
                {{0.0, {0.97, 0.97, 0.97}},
                 {kUtilisationFailure - 1e-9, {0.40, 0.40, 0.40}},
                 {kUtilisationFailure, {0.90, 0.11, 0.09}},
                 {1.0, {0.48, 0.00, 0.16}}},
                no_data),
  };
}

const std::vector<ColourMap>& named_maps() {
  static const std::vector<ColourMap> maps = make_named_maps();
  return maps;
}

}  // namespace

ColourMap::ColourMap(std::string name, std::vector<ControlPoint> points, Rgb missing)
    : name_(std::move(name)), points_(std::move(points)), missing_(missing) {
  if (points_.size() < 2) throw std::invalid_argument("ColourMap: " + name_ + ": needs two control points");
  if (points_.front().position != 0.0 || points_.back().position != 1.0)
    throw std::invalid_argument("ColourMap: " + name_ + ": control points must run from 0 to 1");
  for (std::size_t n = 0; n < points_.size(); ++n) {
    const Rgb& c = points_[n].colour;
    for (double channel : {c.r, c.g, c.b})
      if (!(channel >= 0.0 && channel <= 1.0))
        throw std::invalid_argument(
            fmt::format("ColourMap: {}: point {} has a channel outside 0..1", name_, n));
    if (n > 0 && !(points_[n].position > points_[n - 1].position))
      throw std::invalid_argument(fmt::format("ColourMap: {}: positions must increase (point {})", name_, n));
    lab_.push_back(to_lab(c));
  }
}

const ColourMap& ColourMap::named(const std::string& name) {
  for (const ColourMap& map : named_maps())
    if (map.name() == name) return map;
  throw std::invalid_argument(
      fmt::format("ColourMap: no map '{}': choose one of {}", name, fmt::join(names(), ", ")));
}

const std::vector<std::string>& ColourMap::names() {
  static const std::vector<std::string> list = [] {
    std::vector<std::string> n;
    for (const ColourMap& map : named_maps()) n.push_back(map.name());
    return n;
  }();
  return list;
}

Rgb ColourMap::colour(double t) const {
  if (std::isnan(t)) return missing_;
  t = std::clamp(t, 0.0, 1.0);
  std::size_t n = 1;
  while (n + 1 < points_.size() && points_[n].position < t) ++n;
  const double a = points_[n - 1].position, b = points_[n].position;
  const double s = (t - a) / (b - a);
  std::array<double, 3> lab;
  for (int c = 0; c < 3; ++c) lab[c] = (1.0 - s) * lab_[n - 1][c] + s * lab_[n][c];
  return from_lab(lab);
}

Rgb ColourMap::colour(double value, double lo, double hi) const {
  if (std::isnan(value)) return missing_;
  if (!(hi > lo)) return colour(0.5);
  return colour((value - lo) / (hi - lo));
}

std::vector<ColourMap::ControlPoint> ColourMap::samples(int count) const {
  if (count < 2) throw std::invalid_argument("ColourMap: samples: count must be at least 2");
  std::vector<ControlPoint> out;
  for (int n = 0; n < count; ++n) {
    const double t = double(n) / (count - 1);
    out.push_back({t, colour(t)});
  }
  return out;
}

}  // namespace fw::viz
