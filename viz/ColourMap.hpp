// Colour maps for the pictures (viz/): a value range mapped to sRGB colours, the same maps the ParaView view
// (view.py) is given, so a render and the ParaView view of a run agree.
//
//   const fw::viz::ColourMap& map = fw::viz::ColourMap::named("wind");
//   fw::viz::Rgb c = map.colour(6.0, 0.0, 12.0);   // a speed of 6 m/s on a 0..12 m/s scale
//
// A map is a list of control colours at positions 0..1, interpolated in CIELAB (D65), so that equal steps of
// the value look like equal steps of colour; values outside the range take the end colours, NaN the map's
// "missing" colour. The maps (our own control points):
//   wind          sequential, deep blue -> teal -> yellow-green -> yellow: speeds, densities (>= 0)
//   displacement  sequential, dark brown -> red -> pale yellow: the trees' displacement (m)
//   diverging     blue -> light grey -> red (Moreland's cool-to-warm end points): signed fields
//   utilisation   storm damage, on a scale of 0 .. kUtilisationTop: light grey darkening to mid grey up to
//                 a utilisation of 1, then bright red darkening to wine red: a tree at or past failure is a
//                 different hue, not a shade further along
#pragma once

#include <array>
#include <string>
#include <vector>

namespace fw::viz {

/// The top of the "utilisation" map's scale (applied-to-critical load ratio); 1 is failure.
inline constexpr double kUtilisationTop = 1.5;

/// An sRGB colour, each channel 0..1.
struct Rgb {
  double r = 0.0, g = 0.0, b = 0.0;
};

class ColourMap {
 public:
  struct ControlPoint {
    double position = 0.0;  ///< 0..1, increasing
    Rgb colour;
  };

  /// Throws std::invalid_argument("ColourMap: ...") for fewer than two points, positions that do not rise
  /// from 0 to 1, or a channel outside 0..1.
  ColourMap(std::string name, std::vector<ControlPoint> points, Rgb missing);

  /// One of the maps above by name. Throws std::invalid_argument("ColourMap: no map 'X': choose one of ...").
  static const ColourMap& named(const std::string& name);
  /// The names named() knows, in a fixed order.
  static const std::vector<std::string>& names();

  /// The colour at t in 0..1 (clamped; NaN gives missing()).
  Rgb colour(double t) const;
  /// The colour of `value` on the scale lo..hi (hi > lo; a degenerate scale maps everything to t = 0.5).
  Rgb colour(double value, double lo, double hi) const;

  const std::string& name() const { return name_; }
  Rgb missing() const { return missing_; }
  /// `count` >= 2 evenly spaced samples t = 0 .. 1 as (t, colour): for ParaView's RGBPoints.
  std::vector<ControlPoint> samples(int count) const;

 private:
  std::string name_;
  std::vector<ControlPoint> points_;
  std::vector<std::array<double, 3>> lab_;  // the control colours in CIELAB
  Rgb missing_;
};

}  // namespace fw::viz
