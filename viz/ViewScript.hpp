// view.py, the ParaView script every run writes into its output folder (docs/design.md, "Outputs"): it opens
// the run ready to look at, in ParaView 5.11.
//
//   fw::viz::ViewScriptSettings view;
//   view.scenario_name = "storm";
//   view.wind = view.trees = true;                          // the collections the run writes
//   view.origin = {0, 0, 0}; view.size = {400, 240, 60}; view.cell_size = 2.0;   // m
//   view.slice_height = fw::viz::default_slice_height(view.origin, view.size, view.cell_size);
//   view.speed_range = std::array<double, 2>{0.0, 25.0};    // m/s, optional
//   std::string python = fw::viz::view_script(view);       // the text of view.py
//
// Using it (the run folder is the script's own folder, so a copied or moved folder opens too):
//   paraview --script=out/storm/view.py    the ParaView GUI, at the last frame, ready to play the run
//   pvpython out/storm/view.py             no window; to keep a picture, run it with runpy.run_path and
//                                          then SaveScreenshot('view.png', ImageResolution=[1200, 800])
// The script finds its folder from __file__ (pvpython, pvbatch, runpy, the GUI's Python shell) or, since
// `paraview --script=` in ParaView 5.11 runs the file's text without __file__, from that argument of the
// process (/proc/self/cmdline, else sys.argv); failing both, it reads the working folder and says so.
//
// What it shows, at the last frame, every reader on one time line (the animation uses the data's time
// steps, so wind, trees and leaves move together; "t = ... s" at the bottom is the frames' time):
//   - the wind (wind.pvd): a horizontal slice at slice_height coloured by the cell array `speed` (else
//     the magnitude of `velocity`), scalar bar "speed (m/s)", at 75% opacity so that the trees and
//     obstacles below it show through; the domain's outline; when the frames hold `solid`, the
//     obstacles and terrain as grey cells;
//   - the trees (trees.pvd): tubes whose radius is the point array `radius` (m), coloured by the
//     magnitude of `displacement`, scalar bar "displacement (m)";
//   - the leaves (leaves.pvd): points coloured by `state` (attached, flying, landed);
//   - the camera from the south-west (x east, y north, z up), above the domain, on its centre.
// The speed slice sits by default at the anemometer height, 10 m above the domain floor (origin z),
// clamped into the domain's cell centres. The colour maps are the project's own (viz/ColourMap: "wind"
// for speed, "displacement" for the trees), written as RGBPoints interpolated in CIELAB, so that
// ParaView and `forestwind render` agree. The speed scale starts at speed_range (else 0..1 m/s), is set to
// the data at the last frame (grown to cover speed_range) and grows as the animation plays. The displacement
// scale is render's: 0 to displacement_top, the 99th percentile of the nodes' displacements at the last
// frame the run wrote (viz/DisplacementScale, computed by the run and written in), held as the animation
// plays (before a first frame, none: the data's largest displacement at the last frame).
// The script opens only the collections named in the settings, and of those only the ones whose
// .pvd lists a frame when it runs, so a folder that a run is still writing (or that a failed run left)
// opens too.
#pragma once

#include "viz/SliceHeight.hpp"

#include <array>
#include <optional>
#include <string>
#include <string_view>

namespace fw::viz {

struct ViewScriptSettings {
  std::string scenario_name;              ///< any text: written as an escaped Python string literal
  bool wind = false;                      ///< the run writes wind.pvd
  bool trees = false;                     ///< the run writes trees.pvd
  bool leaves = false;                    ///< the run writes leaves.pvd
  std::array<double, 3> origin{0, 0, 0};  ///< the domain's minimum corner, m
  std::array<double, 3> size{0, 0, 0};    ///< the domain's extent along x, y, z, m (> 0)
  double cell_size = 0.0;                 ///< m (> 0)
  double slice_height = 0.0;              ///< z of the speed slice, m (world frame, inside the domain)
  /// A first range of the speed colour scale, m/s (lo < hi): e.g. 0 to the ambient wind's peak. ParaView
  /// grows it to the data; none: it starts at 0..1 m/s and follows the data.
  std::optional<std::array<double, 2>> speed_range;
  /// The top of the trees' displacement scale, m (>= 0): viz::displacement_scale of the last frame the run
  /// wrote (ViewScriptWriter fills it in); none before the first frame.
  std::optional<double> displacement_top;
};

/// The Python text of view.py (ASCII only, LF line ends). Throws std::invalid_argument("view_script: ...")
/// for non-finite numbers, a non-positive size or cell size, a slice outside the domain, a speed range
/// with lo >= hi or a negative displacement_top.
std::string view_script(const ViewScriptSettings& settings);

/// `text` as a Python 3 string literal in single quotes, in ASCII: backslash, quote and control characters
/// escaped, other characters as \uXXXX / \UXXXXXXXX from their UTF-8 (a byte that is not valid UTF-8 becomes
/// U+FFFD), so that any scenario name gives a valid script that shows the name as it was meant.
std::string python_string_literal(std::string_view text);

/// The number of evenly spaced samples of a colour map in the script's RGBPoints.
inline constexpr int kViewScriptMapSamples = 33;

}  // namespace fw::viz
