#include "viz/FrameRender.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <cmath>
#include <limits>
#include <numeric>
#include <stdexcept>

#include "viz/ColourBar.hpp"
#include "viz/DisplacementScale.hpp"
#include "viz/SliceHeight.hpp"
#include "viz/Ticks.hpp"

namespace fw::viz {

namespace {

// Layout, px: the margins hold the title (top), the axes' labels (left, bottom) and the colour bars (right).
constexpr double kMarginLeft = 80.0, kMarginRight = 230.0, kMarginTop = 64.0, kMarginBottom = 56.0;
constexpr int kSmallestWidth = 480, kSmallestHeight = 320;
constexpr double kTitleSize = 17.0, kLabelSize = 12.0;
constexpr int kArrowsAcross = 24;        // wind arrows along the slice's longer side
constexpr int kMostQuadsAcross = 256;    // perspective: cells merged into blocks beyond this many
constexpr double kThinnestBranch = 1.0;  // px
constexpr double kBranchEdge = 1.2;      // px of dark edge around each branch ...
constexpr double kEdgedBranch = 1.5;     // ... this thick or more: a dense crown's twigs would be all edge
constexpr double kLeafSmallest = 1.2;    // px, radius

const Rgb kWhite{1.0, 1.0, 1.0}, kInk{0.1, 0.1, 0.1}, kGrid{0.55, 0.55, 0.55};
const Rgb kSolidFill{0.62, 0.62, 0.62}, kSolidEdge{0.15, 0.15, 0.15}, kFootprintEdge{0.3, 0.3, 0.3};
const Rgb kBranchShade{0.08, 0.06, 0.04};
// Leaves by trees::LeafState: attached, flying, landed.
const Rgb kLeafColour[] = {{0.22, 0.58, 0.16}, {0.96, 0.56, 0.10}, {0.50, 0.34, 0.16}};

const char* view_name(ViewKind kind) {
  return kind == ViewKind::top ? "top" : kind == ViewKind::side ? "side" : "perspective";
}

Box domain_of(const FrameData& frame) {
  if (frame.wind) {
    const WindGrid& g = *frame.wind;
    const glm::dvec3 lo(g.origin[0], g.origin[1], g.origin[2]);
    return {lo, lo + g.cell_size * glm::dvec3(g.cells[0], g.cells[1], g.cells[2])};
  }
  Box box{glm::dvec3(std::numeric_limits<double>::max()), glm::dvec3(std::numeric_limits<double>::lowest())};
  if (frame.trees)
    for (const auto& p : frame.trees->points)
      box.lo = glm::min(box.lo, glm::dvec3(p[0], p[1], p[2])),
      box.hi = glm::max(box.hi, glm::dvec3(p[0], p[1], p[2]));
  if (!(box.hi.x >= box.lo.x)) return {glm::dvec3(0.0), glm::dvec3(1.0)};
  const glm::dvec3 pad = 0.1 * glm::max(box.size(), glm::dvec3(1.0));  // air around a forest without a grid
  return {box.lo - pad, box.hi + pad};
}

Viewport plot_area(const RenderSettings& s) {
  if (s.width < kSmallestWidth || s.height_px < kSmallestHeight)
    throw std::invalid_argument(fmt::format("render: a picture of {} x {} px is too small: at least {} x {}",
                                            s.width, s.height_px, kSmallestWidth, kSmallestHeight));
  return {kMarginLeft, kMarginTop, s.width - kMarginLeft - kMarginRight,
          s.height_px - kMarginTop - kMarginBottom};
}

Camera camera_for(const FrameData& frame, const RenderSettings& s) {
  const Box domain = domain_of(frame);
  return Camera::of(s.view, domain, Camera::fit_viewport(s.view, domain, plot_area(s)));
}

// The slice: a 2D array of cells (columns a, rows b) of the 3D grid and where each lies in the world.
struct Slice {
  int columns = 0, rows = 0;      // top/perspective: x, y; side: x, z
  int layer = 0;                  // top/perspective: k; side: j
  double position = 0.0;          // top/perspective: the layer's centre height; side: its centre y, m
  std::vector<std::size_t> cell;  // grid index of (a, b), a fastest
  bool solid(const WindGrid& g, std::size_t n) const { return !g.solid.empty() && g.solid[cell[n]]; }
};

Slice slice_of(const WindGrid& g, ViewKind view, std::optional<double> height) {
  Slice s;
  if (view == ViewKind::side) {
    s.columns = g.cells[0], s.rows = g.cells[2], s.layer = g.cells[1] / 2;
    s.position = g.origin[1] + (s.layer + 0.5) * g.cell_size;
    for (int k = 0; k < s.rows; ++k)
      for (int i = 0; i < s.columns; ++i) s.cell.push_back(g.index(i, s.layer, k));
    return s;
  }
  // The perspective view looks at the trees: its default slice is the lowest layer, under every crown.
  const double z = height.value_or(
      view == ViewKind::perspective
          ? g.origin[2]
          : default_slice_height(
                g.origin, {g.cells[0] * g.cell_size, g.cells[1] * g.cell_size, g.cells[2] * g.cell_size},
                g.cell_size));
  const int k = int(std::floor((z - g.origin[2]) / g.cell_size));
  s.columns = g.cells[0], s.rows = g.cells[1], s.layer = std::clamp(k, 0, g.cells[2] - 1);
  s.position = g.origin[2] + (s.layer + 0.5) * g.cell_size;
  for (int j = 0; j < s.rows; ++j)
    for (int i = 0; i < s.columns; ++i) s.cell.push_back(g.index(i, j, s.layer));
  return s;
}

// The world position of slice corner (a, b) (a in 0..columns, b in 0..rows).
glm::dvec3 slice_corner(const WindGrid& g, const Slice& s, ViewKind view, double a, double b) {
  const glm::dvec3 o(g.origin[0], g.origin[1], g.origin[2]);
  if (view == ViewKind::side) return o + glm::dvec3(a * g.cell_size, s.position - o.y, b * g.cell_size);
  return o + glm::dvec3(a * g.cell_size, b * g.cell_size, s.position - o.z);
}

std::array<double, 2> field_range(const ScalarField& field, const Slice& slice, const WindGrid& g) {
  double largest = 0.0;
  for (std::size_t n = 0; n < slice.cell.size(); ++n)
    if (!slice.solid(g, n) && std::isfinite(field.values[slice.cell[n]]))
      largest = std::max(largest, double(std::abs(field.values[slice.cell[n]])));
  if (largest == 0.0) largest = 1.0;  // a calm slice: a scale of one unit rather than none
  return field.is_signed ? std::array<double, 2>{-largest, largest} : std::array<double, 2>{0.0, largest};
}

void draw_slice(Canvas& canvas, const Camera& camera, const WindGrid& g, const Slice& s,
                const ScalarField& field, const ColourMap& map, const std::array<double, 2>& range) {
  auto colour_of = [&](std::size_t n) {
    return s.solid(g, n) ? kSolidFill : map.colour(field.values[s.cell[n]], range[0], range[1]);
  };
  if (camera.kind() != ViewKind::perspective) {
    // Rows from the top of the picture: north (top) or the domain's top (side) first.
    std::vector<Rgb> pixels(s.cell.size());
    for (int b = 0; b < s.rows; ++b)
      for (int a = 0; a < s.columns; ++a)
        pixels[std::size_t(s.rows - 1 - b) * s.columns + a] = colour_of(std::size_t(b) * s.columns + a);
    const Viewport& v = camera.viewport();
    canvas.image(pixels, s.columns, s.rows, v.x, v.y, v.width, v.height);
    return;
  }
  // Perspective: one quad per cell (blocks of cells on big grids), without anti-aliasing so neighbouring
  // quads meet without seams.
  const int block = std::max(1, (std::max(s.columns, s.rows) + kMostQuadsAcross - 1) / kMostQuadsAcross);
  for (int b = 0; b < s.rows; b += block)
    for (int a = 0; a < s.columns; a += block) {
      const int a1 = std::min(a + block, s.columns), b1 = std::min(b + block, s.rows);
      const std::size_t n = std::size_t((b + b1) / 2) * s.columns + (a + a1) / 2;
      canvas.fill_polygon({camera.to_pixel(slice_corner(g, s, ViewKind::perspective, a, b)),
                           camera.to_pixel(slice_corner(g, s, ViewKind::perspective, a1, b)),
                           camera.to_pixel(slice_corner(g, s, ViewKind::perspective, a1, b1)),
                           camera.to_pixel(slice_corner(g, s, ViewKind::perspective, a, b1))},
                          colour_of(n), false);
    }
}

// Solid outlines: edges between solid and fluid cells of the slice; in the top view also the edges where
// the height of the solid below the slice changes (obstacle footprints, terrain contours).
void draw_solids(Canvas& canvas, const Camera& camera, const WindGrid& g, const Slice& s) {
  if (g.solid.empty()) return;
  const ViewKind view = camera.kind() == ViewKind::side ? ViewKind::side : ViewKind::top;
  auto edge = [&](double a0, double b0, double a1, double b1, Rgb colour, double width) {
    canvas.line({camera.to_pixel(slice_corner(g, s, view, a0, b0)),
                 camera.to_pixel(slice_corner(g, s, view, a1, b1))},
                colour, width);
  };
  if (view == ViewKind::top) {
    std::vector<int> top(std::size_t(s.columns) * s.rows, 0);  // solid cells from the floor up to the slice
    for (int j = 0; j < s.rows; ++j)
      for (int i = 0; i < s.columns; ++i) {
        int k = 0;
        while (k <= s.layer && g.solid[g.index(i, j, k)]) ++k;
        top[std::size_t(j) * s.columns + i] = k;
      }
    for (int j = 0; j < s.rows; ++j)
      for (int i = 0; i < s.columns; ++i) {
        const int here = top[std::size_t(j) * s.columns + i];
        if (i + 1 < s.columns && top[std::size_t(j) * s.columns + i + 1] != here)
          edge(i + 1, j, i + 1, j + 1, kFootprintEdge, 0.8);
        if (j + 1 < s.rows && top[std::size_t(j + 1) * s.columns + i] != here)
          edge(i, j + 1, i + 1, j + 1, kFootprintEdge, 0.8);
      }
  }
  for (int b = 0; b < s.rows; ++b)
    for (int a = 0; a < s.columns; ++a) {
      const bool here = s.solid(g, std::size_t(b) * s.columns + a);
      if (a + 1 < s.columns && s.solid(g, std::size_t(b) * s.columns + a + 1) != here)
        edge(a + 1, b, a + 1, b + 1, kSolidEdge, 1.4);
      if (b + 1 < s.rows && s.solid(g, std::size_t(b + 1) * s.columns + a) != here)
        edge(a, b + 1, a + 1, b + 1, kSolidEdge, 1.4);
    }
}

void draw_arrows(Canvas& canvas, const Camera& camera, const WindGrid& g, const Slice& s) {
  const bool side = camera.kind() == ViewKind::side;
  const ScalarField along = g.field("velocity_x"), across = g.field(side ? "velocity_z" : "velocity_y");
  const int step = std::max(1, std::max(s.columns, s.rows) / kArrowsAcross);
  double fastest = 0.0;
  for (std::size_t n = 0; n < s.cell.size(); ++n)
    fastest = std::max(fastest, double(std::hypot(along.values[s.cell[n]], across.values[s.cell[n]])));
  if (!(fastest > 0.0)) return;
  const double metres_per_speed = 0.9 * step * g.cell_size / fastest;  // the fastest arrow: 0.9 of a spacing
  const ViewKind plane = side ? ViewKind::side : ViewKind::top;
  for (int b = step / 2; b < s.rows; b += step)
    for (int a = step / 2; a < s.columns; a += step) {
      const std::size_t n = std::size_t(b) * s.columns + a;
      if (s.solid(g, n)) continue;
      const glm::dvec3 start = slice_corner(g, s, plane, a + 0.5, b + 0.5);
      const glm::dvec3 wind = side ? glm::dvec3(along.values[s.cell[n]], 0.0, across.values[s.cell[n]])
                                   : glm::dvec3(along.values[s.cell[n]], across.values[s.cell[n]], 0.0);
      const Point2 p0 = camera.to_pixel(start), p1 = camera.to_pixel(start + metres_per_speed * wind);
      const double dx = p1.x - p0.x, dy = p1.y - p0.y, length = std::hypot(dx, dy);
      if (length < 2.0) continue;
      const double head = std::min(6.0, 0.35 * length), ux = dx / length, uy = dy / length;
      canvas.line({p0, p1}, kInk, 1.0);
      canvas.line({{p1.x - head * (ux - 0.5 * uy), p1.y - head * (uy + 0.5 * ux)},
                   p1,
                   {p1.x - head * (ux + 0.5 * uy), p1.y - head * (uy - 0.5 * ux)}},
                  kInk, 1.0);
    }
}

// The trees are drawn as strokes of many segments at once: a forest has about a million, and one stroke
// each cost seconds. Segments are painted far to near in layers kDepthLayer deep; within a layer, segments of
// the same colour step (kColourSteps along the map) and width step (kWidthStep px) go into one stroke. A
// layer is thin enough that what overlaps within it is the same branch.
constexpr double kDepthLayer = 0.5;  // m
constexpr int kColourSteps = 64;
constexpr double kWidthStep = 0.25;  // px

struct TreeStroke {
  long layer = 0;  // painting order: far layers first
  int colour = 0, width = 0;
  Point2 a, b;
};

// The segments of the trees as strokes in painting order (all of them, or those `below` / above the slice
// in the perspective view), grouped as above.
std::vector<TreeStroke> tree_strokes(const TreeLines& t, const Camera& camera, std::optional<bool> below,
                                     double slice_z, double largest_displacement) {
  const double ppm = camera.pixels_per_metre();
  std::vector<TreeStroke> strokes;
  strokes.reserve(t.segments.size());
  for (const auto& [i, j] : t.segments) {
    const auto& p = t.points[std::size_t(i)];
    const auto& q = t.points[std::size_t(j)];
    const glm::dvec3 pa(p[0], p[1], p[2]), pb(q[0], q[1], q[2]);
    const glm::dvec3 mid = 0.5 * (pa + pb);
    if (below && ((mid.z < slice_z) != *below)) continue;
    const double width =
        std::max(kThinnestBranch, (t.radius[std::size_t(i)] + t.radius[std::size_t(j)]) * ppm);
    const double d = 0.5 * (t.displacement[std::size_t(i)] + t.displacement[std::size_t(j)]);
    const double fraction = largest_displacement > 0.0 ? std::clamp(d / largest_displacement, 0.0, 1.0) : 0.0;
    strokes.push_back({-long(std::floor(camera.depth(mid) / kDepthLayer)),
                       int(std::lround(fraction * (kColourSteps - 1))), int(std::lround(width / kWidthStep)),
                       camera.to_pixel(pa), camera.to_pixel(pb)});
  }
  std::stable_sort(strokes.begin(), strokes.end(), [](const TreeStroke& x, const TreeStroke& y) {
    if (x.layer != y.layer) return x.layer < y.layer;
    if (x.width != y.width) return x.width < y.width;
    return x.colour < y.colour;
  });
  return strokes;
}

void draw_trees(Canvas& canvas, const std::vector<TreeStroke>& strokes) {
  const ColourMap& map = ColourMap::named("displacement");
  std::vector<std::array<Point2, 2>> batch;
  for (std::size_t first = 0; first < strokes.size();) {
    std::size_t last = first;
    batch.clear();
    while (last < strokes.size() && strokes[last].layer == strokes[first].layer &&
           strokes[last].width == strokes[first].width && strokes[last].colour == strokes[first].colour)
      batch.push_back({strokes[last].a, strokes[last].b}), ++last;
    const double width = strokes[first].width * kWidthStep;
    if (width >= kEdgedBranch) canvas.segments(batch, kBranchShade, width + kBranchEdge);
    canvas.segments(batch, map.colour(double(strokes[first].colour) / (kColourSteps - 1)), width);
    first = last;
  }
}

// Leaves (all, or those `below` / above the slice in the perspective view), painted far to near, and in one
// order whatever order the files list them in (a run over MPI ranks writes them rank by rank), so that the
// same leaves give the same picture.
void draw_leaves(Canvas& canvas, const Camera& camera, const LeafPoints& leaves, std::optional<bool> below,
                 double slice_z) {
  const double ppm = camera.pixels_per_metre();
  std::vector<std::size_t> order(leaves.position.size());
  std::iota(order.begin(), order.end(), std::size_t(0));
  const auto depth = [&](std::size_t n) {
    const auto& p = leaves.position[n];
    return camera.depth({p[0], p[1], p[2]});
  };
  std::sort(order.begin(), order.end(), [&](std::size_t a, std::size_t b) {
    const double da = depth(a), db = depth(b);
    return da != db ? da > db : leaves.position[a] < leaves.position[b];
  });
  for (const std::size_t n : order) {
    const auto& p = leaves.position[n];
    if (below && ((p[2] < slice_z) != *below)) continue;
    const int state = std::min<int>(leaves.state[n], 2);
    canvas.disc(camera.to_pixel({p[0], p[1], p[2]}), std::max(kLeafSmallest, 0.5 * leaves.size[n] * ppm),
                kLeafColour[state]);
  }
}

// Axes along the bottom and the left of an orthographic view, in world metres.
void draw_axes(Canvas& canvas, const Camera& camera, const Box& domain) {
  const Viewport& v = camera.viewport();
  const bool side = camera.kind() == ViewKind::side;
  canvas.stroke_rect(pixel_centre(v.x), pixel_centre(v.y), std::round(v.width), std::round(v.height), kInk,
                     1.0);
  const std::vector<double> x_ticks = nice_ticks(domain.lo.x, domain.hi.x, 8);
  for (double x : x_ticks) {
    const double px = camera.to_pixel({x, domain.lo.y, domain.lo.z}).x;
    canvas.line({{px, v.y + v.height}, {px, v.y + v.height + 5}}, kInk, 1.0);
    canvas.text({px, v.y + v.height + 19}, tick_label(x, tick_step(x_ticks)), kLabelSize, kInk,
                Align::centre);
  }
  canvas.text({v.x + 0.5 * v.width, v.y + v.height + 40}, "x (m)", kLabelSize, kInk, Align::centre);
  const double lo = side ? domain.lo.z : domain.lo.y, hi = side ? domain.hi.z : domain.hi.y;
  const std::vector<double> y_ticks = nice_ticks(lo, hi, 6);
  for (double y : y_ticks) {
    const double py = camera
                          .to_pixel(side ? glm::dvec3(domain.lo.x, domain.lo.y, y)
                                         : glm::dvec3(domain.lo.x, y, domain.lo.z))
                          .y;
    canvas.line({{v.x - 5, py}, {v.x, py}}, kInk, 1.0);
    canvas.text({v.x - 8, py + 4}, tick_label(y, tick_step(y_ticks)), kLabelSize, kInk, Align::right);
  }
  canvas.text({v.x - 50, v.y + 0.5 * v.height}, side ? "z (m)" : "y (m)", kLabelSize, kInk, Align::centre,
              90.0);
}

void draw_box(Canvas& canvas, const Camera& camera, const Box& d) {
  auto corner = [&](int n) {
    return glm::dvec3(n & 1 ? d.hi.x : d.lo.x, n & 2 ? d.hi.y : d.lo.y, n & 4 ? d.hi.z : d.lo.z);
  };
  for (int a = 0; a < 8; ++a)
    for (int bit : {1, 2, 4})
      if (!(a & bit)) canvas.line({camera.to_pixel(corner(a)), camera.to_pixel(corner(a | bit))}, kGrid, 1.0);
}

}  // namespace

std::array<double, 2> slice_range(const FrameData& frame, const RenderSettings& settings) {
  if (settings.range) return *settings.range;
  if (!frame.wind) return {0.0, 1.0};
  const WindGrid& g = *frame.wind;
  return field_range(g.field(settings.field), slice_of(g, settings.view, settings.height), g);
}

Viewport colour_bar_place(const RenderSettings& settings, int n) {
  const double x = settings.width - kMarginRight + 40, h = settings.height_px;
  return n == 0 ? Viewport{x, kMarginTop + 20, 22, 0.42 * h}
                : Viewport{x, kMarginTop + 60 + 0.42 * h, 22, 0.28 * h};
}

ViewKind parse_view(const std::string& name) {
  for (ViewKind kind : {ViewKind::top, ViewKind::side, ViewKind::perspective})
    if (name == view_name(kind)) return kind;
  throw std::invalid_argument(fmt::format("render: --view {}: choose one of top, side, perspective", name));
}

FrameRender::FrameRender(const FrameData& frame, const std::string& scenario, const RenderSettings& settings)
    : canvas_(std::max(settings.width, 1), std::max(settings.height_px, 1), kWhite),
      camera_(camera_for(frame, settings)) {
  if (settings.range && !(settings.range->at(1) > settings.range->at(0)))
    throw std::invalid_argument(
        fmt::format("render: --range {} {}: expected LO < HI", settings.range->at(0), settings.range->at(1)));
  const Box domain = domain_of(frame);
  std::string subject = "trees";
  std::optional<Slice> slice;
  std::optional<ScalarField> field;
  if (frame.wind) {
    const WindGrid& g = *frame.wind;
    field = g.field(settings.field);
    slice = slice_of(g, settings.view, settings.height);
    slice_layer_ = slice->layer;
    slice_position_ = slice->position;
    range_ = settings.range.value_or(field_range(*field, *slice, g));
    field_map_ = &ColourMap::named(field->is_signed ? "diverging" : "wind");
    subject = settings.view == ViewKind::side ? fmt::format("{} at y = {:g} m", field->name, slice->position)
                                              : fmt::format("{} at z = {:g} m", field->name, slice->position);
    draw_colour_bar(canvas_, colour_bar_place(settings, 0), *field_map_, range_[0], range_[1],
                    field->unit.empty() ? field->name : fmt::format("{} ({})", field->name, field->unit));
  }
  const bool trees = frame.trees && settings.trees, leaves = frame.leaves && settings.trees;
  if (trees) displacement_range_ = displacement_scale(frame.trees->displacement);
  if (trees && !frame.trees->segments.empty())
    draw_colour_bar(canvas_, colour_bar_place(settings, 1), ColourMap::named("displacement"), 0.0,
                    displacement_range_ > 0.0 ? displacement_range_ : 1.0, "tree displacement (m)");

  const bool perspective = settings.view == ViewKind::perspective;
  if (perspective) draw_box(canvas_, camera_, domain);
  // Perspective: what lies below the slice is painted first, so the slice hides it.
  if (perspective && trees)
    draw_trees(canvas_, tree_strokes(*frame.trees, camera_, true, slice_position_, displacement_range_));
  if (perspective && leaves) draw_leaves(canvas_, camera_, *frame.leaves, true, slice_position_);
  if (slice) {
    const WindGrid& g = *frame.wind;
    if (!perspective)
      canvas_.clip(camera_.viewport().x, camera_.viewport().y, camera_.viewport().width,
                   camera_.viewport().height);
    draw_slice(canvas_, camera_, g, *slice, *field, *field_map_, range_);
    draw_solids(canvas_, camera_, g, *slice);
    if (settings.arrows) draw_arrows(canvas_, camera_, g, *slice);
  } else if (!perspective) {
    canvas_.clip(camera_.viewport().x, camera_.viewport().y, camera_.viewport().width,
                 camera_.viewport().height);
  }
  if (trees)
    draw_trees(canvas_,
               tree_strokes(*frame.trees, camera_, perspective ? std::optional<bool>(false) : std::nullopt,
                            slice_position_, displacement_range_));
  if (leaves)
    draw_leaves(canvas_, camera_, *frame.leaves, perspective ? std::optional<bool>(false) : std::nullopt,
                slice_position_);
  canvas_.reset_clip();
  if (!perspective) draw_axes(canvas_, camera_, domain);

  canvas_.text({kMarginLeft, 28},
               fmt::format("{}    t = {:.2f} s    frame {}", scenario, frame.time, frame.index), kTitleSize,
               kInk);
  canvas_.text({kMarginLeft, 48}, fmt::format("{}, {} view", subject, view_name(settings.view)), kLabelSize,
               kInk);
}

}  // namespace fw::viz
