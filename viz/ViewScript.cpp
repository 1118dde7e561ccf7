#include "viz/ViewScript.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <stdexcept>
#include <string>
#include <vector>

#include "viz/ColourMap.hpp"

namespace fw::viz {

namespace {

// A double as a Python literal: the shortest text that reads back as the same double.
std::string python_number(double value, const char* what) {
  if (!std::isfinite(value))
    throw std::invalid_argument(fmt::format("view_script: {} is not a finite number", what));
  return fmt::format("{}", value);
}

std::string python_list(const std::array<double, 3>& values, const char* what) {
  return fmt::format("[{}, {}, {}]", python_number(values[0], what), python_number(values[1], what),
                     python_number(values[2], what));
}

// A colour map as ParaView's RGBPoints (value, r, g, b, ...) on lo..hi, one sample per line.
std::string rgb_points(const char* variable, const std::string& map_name, double lo, double hi,
                       const char* unit) {
  std::string text = fmt::format(
      "# value ({}), r, g, b (sRGB 0..1): forestwind's \"{}\" colour map (viz/ColourMap), {} samples.\n"
      "{} = [\n",
      unit, map_name, kViewScriptMapSamples, variable);
  for (const ColourMap::ControlPoint& p : ColourMap::named(map_name).samples(kViewScriptMapSamples)) {
    // Colours to 9 significant digits: far below an 8-bit step (1/255), and a short line.
    text += fmt::format("    {}, {:.9g}, {:.9g}, {:.9g},\n",
                        python_number(lo + p.position * (hi - lo), "a map value"), p.colour.r, p.colour.g,
                        p.colour.b);
  }
  text += "]\n";
  return text;
}

// The code point of one well-formed UTF-8 sequence of 1 to 4 bytes.
std::uint32_t utf8_code_point(std::string_view sequence) {
  const auto lead = std::uint8_t(sequence[0]);
  std::uint32_t c = sequence.size() == 1 ? lead : lead & (0x7f >> sequence.size());
  for (std::size_t k = 1; k < sequence.size(); ++k) c = (c << 6) | (std::uint8_t(sequence[k]) & 0x3f);
  return c;
}

// The length of the UTF-8 sequence at text[i], or 0 where it is not valid UTF-8 (a stray continuation
// byte, a cut sequence, an overlong form, a surrogate or a code point past U+10FFFF).
std::size_t utf8_length(std::string_view text, std::size_t i) {
  const auto byte = [&](std::size_t k) { return std::uint8_t(text[k]); };
  const std::uint8_t lead = byte(i);
  if (lead < 0x80) return 1;
  const std::size_t length = lead >= 0xf0 ? 4 : lead >= 0xe0 ? 3 : lead >= 0xc0 ? 2 : 0;
  if (length == 0 || lead >= 0xf8 || i + length > text.size()) return 0;
  for (std::size_t k = 1; k < length; ++k)
    if ((byte(i + k) & 0xc0) != 0x80) return 0;
  const std::uint32_t c = utf8_code_point(text.substr(i, length));
  const std::uint32_t least = length == 2 ? 0x80 : length == 3 ? 0x800 : 0x10000;  // shorter forms exist
  if (c < least || c > 0x10ffff || (c >= 0xd800 && c < 0xe000)) return 0;
  return length;
}

// Appends code point `c` to a Python literal: printable ASCII as itself, the rest escaped.
void append_code_point(std::string& out, std::uint32_t c) {
  switch (c) {
    case '\\':
      out += "\\\\";
      return;
    case '\'':
      out += "\\'";
      return;
    case '\n':
      out += "\\n";
      return;
    case '\r':
      out += "\\r";
      return;
    case '\t':
      out += "\\t";
      return;
    default:
      break;
  }
  if (c >= 0x20 && c < 0x7f)
    out += char(c);
  else if (c < 0x100)
    out += fmt::format("\\x{:02x}", c);
  else if (c < 0x10000)
    out += fmt::format("\\u{:04x}", c);
  else
    out += fmt::format("\\U{:08x}", c);
}

// --- the fixed parts of the script; the generated constants go between them ---------------------------

constexpr const char* kPreamble = R"PY(import math
import os
import sys

import paraview.simple
from paraview.simple import *

)PY";

constexpr const char* kHelpers = R"PY(

def script_folder():
    """This file's folder: the run's, so that a copied or moved folder still opens."""
    try:  # pvpython, pvbatch, runpy, the GUI's Python shell
        return os.path.dirname(os.path.abspath(__file__))
    except NameError:
        pass
    # `paraview --script=view.py` (5.11) runs the file's text without __file__: the argument names the file.
    try:
        with open('/proc/self/cmdline', 'rb') as cmdline:
            arguments = [os.fsdecode(a) for a in cmdline.read().split(b'\0')]
    except OSError:  # not Linux
        arguments = list(sys.argv)
    for i, argument in enumerate(arguments):
        if argument.startswith('--script='):
            return os.path.dirname(os.path.abspath(argument[len('--script='):]))
        if argument == '--script' and i + 1 < len(arguments):
            return os.path.dirname(os.path.abspath(arguments[i + 1]))
    print('view.py: cannot tell where this file is, so the run is read from the working folder ' + os.getcwd())
    return os.getcwd()


RUN = script_folder()

paraview.simple._DisableFirstRenderCameraReset()  # the camera is set below
view = GetActiveViewOrCreate('RenderView')
view.OrientationAxesVisibility = 1


def open_collection(name):
    """The reader of RUN/<name>.pvd, or None while the file is missing or lists no frame yet."""
    path = os.path.join(RUN, name + '.pvd')
    if not os.path.exists(path):
        print('view.py: %s is missing, shown without it' % path)
        return None
    with open(path) as pvd:
        if '<DataSet' not in pvd.read():
            print('view.py: %s lists no frame yet, shown without it' % path)
            return None
    return PVDReader(registrationName=name + '.pvd', FileName=path)


def use_colour_map(display, association, array, component, rgb_points, title, corner, rescale):
    """Colours `display` by `array` with one of forestwind's maps and shows its scalar bar. rescale: how the
    range follows the data as the animation plays ('Grow and update every timestep': growing only, so a
    colour keeps its value; 'Never': the range set below stays)."""
    ColorBy(display, (association, array) if component is None else (association, array, component))
    lut = GetColorTransferFunction(array)
    lut.ColorSpace = 'Lab'  # the maps are interpolated in CIELAB, as viz/ColourMap does
    lut.RGBPoints = rgb_points
    lut.ScalarRangeInitialized = 1.0
    lut.AutomaticRescaleRangeMode = rescale
    display.SetScalarBarVisibility(view, True)
    bar = GetScalarBar(lut, view)
    bar.Title = title
    bar.ComponentTitle = ''
    bar.HorizontalTitle = 1
    bar.WindowLocation = corner
    bar.RangeLabelFormat = '%-#.3g'
    return lut


def plain_colour(display, rgb):
    """Shows `display` in one colour (ColorBy(display, None) in 5.11 fails on a display not coloured yet)."""
    if display.ColorArrayName[1]:
        ColorBy(display, None)
    display.AmbientColor = display.DiffuseColor = rgb


def set_range(lut, array, lo, hi, min_span):
    """Sets the colour scale of `lut` (and its opacity) to lo..hi, widened to at least min_span."""
    if not hi - lo >= min_span:
        hi = lo + min_span
    lut.RescaleTransferFunction(lo, hi)
    GetOpacityTransferFunction(array).RescaleTransferFunction(lo, hi)


readers = []
)PY";

constexpr const char* kWind = R"PY(
# --- the wind: the domain's outline, the obstacles and a horizontal slice coloured by speed ---------------
speed_lut = None
wind = open_collection('wind')
if wind is not None:
    readers.append(wind)
    wind_cells = wind.CellData.keys()
    outline = Show(wind, view)
    outline.Representation = 'Outline'
    plain_colour(outline, [0.75, 0.75, 0.75])
    if 'solid' in wind_cells and wind.CellData['solid'].GetRange()[1] >= 0.5:
        obstacles = Threshold(registrationName='obstacles', Input=wind)
        obstacles.Scalars = ['CELLS', 'solid']
        obstacles.LowerThreshold = 0.5  # solid is 0 (air) or 1 (solid)
        obstacles.UpperThreshold = 1.5
        obstacle_display = Show(obstacles, view)
        plain_colour(obstacle_display, [0.55, 0.55, 0.55])
    speed_slice = Slice(registrationName='speed slice', Input=wind)
    speed_slice.SliceType = 'Plane'
    speed_slice.SliceType.Origin = [DOMAIN_ORIGIN[0] + 0.5 * DOMAIN_SIZE[0],
                                    DOMAIN_ORIGIN[1] + 0.5 * DOMAIN_SIZE[1], SLICE_Z]
    speed_slice.SliceType.Normal = [0.0, 0.0, 1.0]
    slice_display = Show(speed_slice, view)
    slice_display.Opacity = 0.75  # what stands below the slice shows through (1: the map's exact colours)
    if 'speed' in wind_cells:
        speed_array, speed_component = 'speed', None
    elif 'velocity' in wind_cells:  # a run that writes velocity but not speed
        speed_array, speed_component = 'velocity', 'Magnitude'
    else:
        speed_array = None
        plain_colour(slice_display, [0.8, 0.8, 0.8])
    if speed_array is not None:
        speed_lut = use_colour_map(slice_display, 'CELLS', speed_array, speed_component, SPEED_RGB_POINTS,
                                   'speed (m/s)', 'Lower Right Corner', 'Grow and update every timestep')
)PY";

constexpr const char* kTrees = R"PY(
# --- the trees: tubes of their radius at their deformed positions, coloured by displacement ---------------
displacement_lut = None
trees = open_collection('trees')
if trees is not None:
    readers.append(trees)
    tubes = Tube(registrationName='tree tubes', Input=trees)
    tubes.Scalars = ['POINTS', 'radius']
    tubes.VaryRadius = 'By Absolute Scalar'  # the tube's radius is the branch radius, m
    tubes.NumberofSides = 8
    tube_display = Show(tubes, view)
    if 'displacement' in trees.PointData.keys():
        # render's scale, held: growing to the largest displacement would leave most branches dark.
        displacement_lut = use_colour_map(tube_display, 'POINTS', 'displacement', 'Magnitude',
                                          DISPLACEMENT_RGB_POINTS, 'displacement (m)', 'Upper Right Corner',
                                          'Never')
    else:
        plain_colour(tube_display, [0.45, 0.3, 0.15])
)PY";

constexpr const char* kLeaves = R"PY(
# --- the leaves: points coloured by state ------------------------------------------------------------------
leaves = open_collection('leaves')
if leaves is not None:
    readers.append(leaves)
    leaf_display = Show(leaves, view)
    leaf_display.Representation = 'Points'
    leaf_display.PointSize = 3.0
    leaf_display.RenderPointsAsSpheres = 1
    if 'state' in leaves.PointData.keys():
        ColorBy(leaf_display, ('POINTS', 'state'))
        state_lut = GetColorTransferFunction('state')
        state_lut.InterpretValuesAsCategories = 1
        state_lut.Annotations = ['0', 'attached', '1', 'flying', '2', 'landed']  # trees::LeafState
        state_lut.IndexedColors = [0.25, 0.6, 0.2, 1.0, 0.6, 0.1, 0.5, 0.35, 0.2]
        leaf_display.SetScalarBarVisibility(view, True)
        state_bar = GetScalarBar(state_lut, view)
        state_bar.Title = 'leaf state'
        state_bar.HorizontalTitle = 1
        state_bar.WindowLocation = 'Upper Left Corner'
    else:
        plain_colour(leaf_display, [0.25, 0.6, 0.2])
)PY";

constexpr const char* kFinish = R"PY(
# --- one time line for every reader, at the last frame; the colour scales on its data ----------------------
scene = GetAnimationScene()
scene.UpdateAnimationUsingDataTimeSteps()
times = list(GetTimeKeeper().TimestepValues)
# The last frame's time itself: with a single frame, GoToLast() would go to the scene's default end, 1 s.
if times:
    scene.AnimationTime = times[-1]
last_time = view.ViewTime
for reader in readers:
    reader.UpdatePipeline(last_time)
if speed_lut is not None:
    lo, hi = wind.CellData[speed_array].GetRange(0 if speed_component is None else -1)
    if SPEED_RANGE is not None:
        lo, hi = min(lo, SPEED_RANGE[0]), max(hi, SPEED_RANGE[1])
    set_range(speed_lut, speed_array, lo, hi, 0.1)  # m/s
if displacement_lut is not None:
    top = DISPLACEMENT_TOP
    if top is None:  # view.py written before the run's first frame: the data's largest displacement
        top = trees.PointData['displacement'].GetRange(-1)[1]
    set_range(displacement_lut, 'displacement', 0.0, top, 1e-3)  # m

clock = AnnotateTime(registrationName='time')
clock.Format = 't = {time:.2f} s'
clock_display = Show(clock, view)
clock_display.WindowLocation = 'Lower Center'
title = Text(registrationName='scenario', Text=SCENARIO)
title_display = Show(title, view)
title_display.WindowLocation = 'Upper Center'

# --- the camera: from the south-west (x east, y north), above the domain, on its centre --------------------
centre = [DOMAIN_ORIGIN[i] + 0.5 * DOMAIN_SIZE[i] for i in range(3)]
reach = math.sqrt(sum(s * s for s in DOMAIN_SIZE))
view.CameraFocalPoint = centre
view.CameraPosition = [centre[0] - 0.7 * reach, centre[1] - 0.7 * reach, centre[2] + 0.6 * reach]
view.CameraViewUp = [0.0, 0.0, 1.0]
view.ResetCamera(False)  # fit what is shown, keeping the direction
if readers:
    SetActiveSource(readers[0])
Render(view)
)PY";

}  // namespace

std::string python_string_literal(std::string_view text) {
  std::string out = "'";
  std::size_t i = 0;
  while (i < text.size()) {
    const std::size_t length = utf8_length(text, i);
    if (length == 0) {
      append_code_point(out, 0xfffd);  // one replacement per stray byte
      ++i;
      continue;
    }
    append_code_point(out, utf8_code_point(text.substr(i, length)));
    i += length;
  }
  out += "'";
  return out;
}

std::string view_script(const ViewScriptSettings& s) {
  // python_number() refuses NaN and infinities; these checks refuse what the script could not show.
  for (int a = 0; a < 3; ++a) {
    python_number(s.origin[a], "the domain origin");
    python_number(s.size[a], "the domain size");
    if (!(s.size[a] > 0.0))
      throw std::invalid_argument("view_script: the domain size must be positive along x, y and z");
  }
  python_number(s.cell_size, "the cell size");
  if (!(s.cell_size > 0.0)) throw std::invalid_argument("view_script: the cell size must be positive");
  python_number(s.slice_height, "the slice height");
  if (s.slice_height < s.origin[2] || s.slice_height > s.origin[2] + s.size[2]) {
    throw std::invalid_argument(
        fmt::format("view_script: the slice height {} m is outside the domain ({} to {} m)", s.slice_height,
                    s.origin[2], s.origin[2] + s.size[2]));
  }
  if (s.speed_range) {
    const auto [lo, hi] = *s.speed_range;
    python_number(lo, "the speed range");
    python_number(hi, "the speed range");
    if (!(lo < hi)) throw std::invalid_argument("view_script: the speed range needs lo < hi");
  }
  if (s.displacement_top) {
    python_number(*s.displacement_top, "the displacement scale");
    if (!(*s.displacement_top >= 0.0))
      throw std::invalid_argument("view_script: the displacement scale must be >= 0 m");
  }
  const std::string name = python_string_literal(s.scenario_name);

  std::vector<std::string> shown;
  if (s.wind) {
    shown.push_back(
        fmt::format("wind.pvd: a slice at z = {} m coloured by speed (m/s), the outline, obstacles",
                    python_number(s.slice_height, "the slice height")));
  }
  if (s.trees)
    shown.push_back(
        "trees.pvd: tubes of the branch radius coloured by displacement (m), on forestwind render's scale");
  if (s.leaves) shown.push_back("leaves.pvd: points coloured by state (attached, flying, landed)");
  if (shown.empty()) shown.push_back("nothing: the run writes no wind, trees or leaves collection");

  std::string py;
  py += fmt::format(
      "# view.py: the forestwind run {} in ParaView 5.11 (written by the run; viz/ViewScript).\n", name);
  py += "#   paraview --script=view.py     opens it in the ParaView GUI, at the last frame, ready to play\n";
  py +=
      "#   pvpython view.py              the same without a window (then e.g. SaveScreenshot('view.png'))\n";
  py += "# What it shows, every reader on one time line:\n";
  for (const std::string& line : shown) py += "#   " + line + "\n";
  py += kPreamble;
  py += "SCENARIO = " + name + "\n";
  py += "DOMAIN_ORIGIN = " + python_list(s.origin, "the domain origin") + "  # m, the minimum corner\n";
  py += "DOMAIN_SIZE = " + python_list(s.size, "the domain size") +
        "  # m, along x (east), y (north), z (up)\n";
  py += "CELL_SIZE = " + python_number(s.cell_size, "the cell size") + "  # m\n";
  if (s.wind) {
    const std::array<double, 2> range = s.speed_range.value_or(std::array<double, 2>{0.0, 1.0});
    py += "# z of the speed slice, m (by default the anemometer height: 10 m above the domain floor).\n";
    py += "SLICE_Z = " + python_number(s.slice_height, "the slice height") + "\n";
    if (s.speed_range) {
      py +=
          fmt::format("SPEED_RANGE = [{}, {}]  # m/s: the speed scale covers at least this\n",
                      python_number(range[0], "the speed range"), python_number(range[1], "the speed range"));
    } else {
      py += "SPEED_RANGE = None  # m/s: no hint, the speed scale is the data's range\n";
    }
    py += rgb_points("SPEED_RGB_POINTS", "wind", range[0], range[1], "m/s");
  }
  if (s.trees) {
    py += rgb_points("DISPLACEMENT_RGB_POINTS", "displacement", 0.0, 1.0, "m");
    py +=
        "# The top of the displacement scale, m: `forestwind render`'s (the 99th percentile of the nodes'\n"
        "# displacements, viz/DisplacementScale) at the last frame the run wrote; None before its first.\n";
    py += "DISPLACEMENT_TOP = " +
          (s.displacement_top ? python_number(*s.displacement_top, "the displacement scale") : "None") + "\n";
  }
  py += kHelpers;
  if (s.wind) py += kWind;
  if (s.trees) py += kTrees;
  if (s.leaves) py += kLeaves;
  if (!s.wind) py += "speed_lut = None\n";
  if (!s.trees) py += "displacement_lut = None\n";
  py += kFinish;
  return py;
}

}  // namespace fw::viz
