// One frame of a run as a picture (`forestwind render`): a slice of a wind field with its colour bar, the
// deformed trees over it coloured by displacement, the leaves, the solids outlined, optional wind arrows,
// and the scenario's name and the time.
//
//   fw::viz::RunFolder run("out/storm");
//   fw::viz::FrameData data = run.load(run.select(std::nullopt, std::nullopt));
//   fw::viz::RenderSettings settings;                  // top view of the speed at 10 m above the floor
//   fw::viz::FrameRender picture(data, run.scenario_name(), settings);
//   picture.canvas().write_png("out/storm/storm.png");
//
// The slice: `top` and `perspective` show the horizontal layer of cells holding `height` (default: 10 m
// above the domain's floor, the standard anemometer height, or the top layer of a lower domain; for the
// perspective view the lowest layer, so that it shows the whole trees over the ground wind); `side`
// shows the vertical x-z layer through the domain's middle (y). Cells are drawn as they are stored (each
// cell one flat colour): what the grid holds, not a smoothed impression of it. Solid cells are grey and
// outlined; in the top view, the edges where the height of the solid ground or of an obstacle changes are
// drawn too, so buildings and terrain contours show below the slice.
// Colours: unsigned fields (speed, magnitudes, densities) on the "wind" map from 0 to the slice's largest
// value; signed ones (components, pressure) on the "diverging" map symmetric about 0; `range` overrides.
// Trees: every element a line as thick as the branch (at least a pixel), on the "displacement" map from 0 to
// the 99th percentile of the frame's nodal displacements (viz/DisplacementScale, shared with view.py; a few
// whipping tips would otherwise leave every other branch dark), limbs and trunks with a dark edge so they
// read over any colour.
#pragma once

#include <array>
#include <optional>
#include <string>

#include "viz/Camera.hpp"
#include "viz/Canvas.hpp"
#include "viz/RunFolder.hpp"

namespace fw::viz {

struct RenderSettings {
  ViewKind view = ViewKind::top;
  std::string field = "speed";                 ///< a name of WindGrid::field_names()
  std::optional<double> height;                ///< slice height z (world), m
  std::optional<std::array<double, 2>> range;  ///< colour range of the field, its unit
  bool arrows = false;                         ///< in-plane wind arrows over the slice
  bool trees = true;  ///< draw the deformed trees and leaves (without wind, the view still fits the trees)
  int width = 1280, height_px = 800;  ///< picture size, px
};

class FrameRender {
 public:
  /// Draws `frame`. Throws std::invalid_argument("render: ...") for a field the frame does not hold (listing
  /// the ones it does), a range with hi <= lo, or a picture too small for its margins.
  FrameRender(const FrameData& frame, const std::string& scenario, const RenderSettings& settings);

  const Canvas& canvas() const { return canvas_; }
  /// For drawing over the picture (viz/DamageMap).
  Canvas& canvas() { return canvas_; }
  /// Where the world lands in the picture (the slice's and the trees' projection).
  const Camera& camera() const { return camera_; }
  /// The slice's layer (top, perspective: k; side: j) and its height or position, m.
  int slice_layer() const { return slice_layer_; }
  double slice_position() const { return slice_position_; }
  /// The colour range used for the field, and the top of the trees' displacement scale (m).
  const std::array<double, 2>& range() const { return range_; }
  double displacement_range() const { return displacement_range_; }
  /// The map the field is drawn with.
  const ColourMap& field_map() const { return *field_map_; }

 private:
  Canvas canvas_;
  Camera camera_;
  int slice_layer_ = 0;
  double slice_position_ = 0.0;
  std::array<double, 2> range_{0.0, 1.0};
  double displacement_range_ = 0.0;
  const ColourMap* field_map_ = nullptr;
};

/// The colour range FrameRender gives the field of `frame` (settings.range, else the slice's, as above),
/// without drawing; for one scale over many frames. Throws as FrameRender for a field the frame lacks.
std::array<double, 2> slice_range(const FrameData& frame, const RenderSettings& settings);

/// Where FrameRender puts its colour bars in a picture of `settings`' size, px: n = 0 the field's, n = 1 the
/// trees' displacement's (free in a frame without trees, for a picture drawn over it).
Viewport colour_bar_place(const RenderSettings& settings, int n);

/// "top", "side", "perspective" -> ViewKind. Throws std::invalid_argument naming the choices.
ViewKind parse_view(const std::string& name);

}  // namespace fw::viz
