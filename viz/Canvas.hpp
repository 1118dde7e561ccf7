// A picture being drawn: an RGB raster with anti-aliased lines, polygons, text and images, written as PNG.
// It draws with cairo into memory, so it needs no X server and no GL (README, "Pictures").
//
//   fw::viz::Canvas canvas(1200, 800, {1, 1, 1});       // white
//   canvas.line({{10, 10}, {200, 50}}, {0, 0, 0}, 1.5);  // pixels: x right, y down
//   canvas.text({20, 30}, "t = 12.5 s", 14.0, {0, 0, 0});
//   canvas.write_png("out/storm/frame.png");            // temporary name, then renamed
//
// Coordinates are in pixels, origin at the top-left corner, y down; a pixel (i, j) covers [i, i+1) x [j,
// j+1), so its centre is (i + 0.5, j + 0.5). Text uses the DejaVu Sans face (fonts-dejavu-core).
#pragma once

#include <array>
#include <cmath>
#include <cstdint>
#include <filesystem>
#include <memory>
#include <string>
#include <vector>

#include "viz/ColourMap.hpp"

namespace fw::viz {

struct Point2 {
  double x = 0.0, y = 0.0;
};

/// The centre of the pixel holding coordinate v: a 1 px line drawn there covers one whole pixel row or
/// column instead of two halves (crisp axes).
inline double pixel_centre(double v) {
  return std::floor(v) + 0.5;
}

/// Where a text's anchor point sits on the text's box.
enum class Align { left, centre, right };

class Canvas {
 public:
  /// width, height: pixels (1..16384). Throws std::invalid_argument("Canvas: ...") otherwise.
  Canvas(int width, int height, Rgb background);
  ~Canvas();
  Canvas(const Canvas&) = delete;
  Canvas& operator=(const Canvas&) = delete;
  Canvas(Canvas&&) noexcept;
  Canvas& operator=(Canvas&&) noexcept;

  int width() const { return width_; }
  int height() const { return height_; }

  /// A filled axis-aligned rectangle; `antialias` false gives hard, exactly coloured edges.
  void fill_rect(double x, double y, double w, double h, Rgb colour, bool antialias = true);
  /// A rectangle's outline.
  void stroke_rect(double x, double y, double w, double h, Rgb colour, double line_width);
  /// A filled polygon (at least 3 points).
  void fill_polygon(const std::vector<Point2>& points, Rgb colour, bool antialias = true);
  /// An open polyline (at least 2 points), round caps and joins; `dash` > 0 draws it dashed (px).
  void line(const std::vector<Point2>& points, Rgb colour, double line_width, double dash = 0.0);
  /// Separate straight segments (each a pair of end points) stroked at once in one colour and width, round
  /// caps: many segments cost about one stroke.
  void segments(const std::vector<std::array<Point2, 2>>& segments, Rgb colour, double line_width);
  /// A filled circle.
  void disc(Point2 centre, double radius, Rgb colour);
  /// Text whose baseline starts (left), centres or ends (right) at `anchor`; `angle` in degrees,
  /// counter-clockwise (90 reads bottom to top). size: px.
  void text(Point2 anchor, const std::string& text, double size, Rgb colour, Align align = Align::left,
            double angle = 0.0);
  /// Width of `text` at `size`, px.
  double text_width(const std::string& text, double size) const;
  /// An image of w x h colours (row-major, row 0 at the top) drawn into the rectangle (x, y, width, height),
  /// each source pixel a sharp block (nearest neighbour, so cells stay cells).
  void image(const std::vector<Rgb>& pixels, int w, int h, double x, double y, double width, double height);
  /// Restricts drawing to a rectangle until reset_clip().
  void clip(double x, double y, double w, double h);
  void reset_clip();

  /// The colour of pixel (i, j) as drawn so far (8 bits a channel, 0..255).
  std::array<std::uint8_t, 3> pixel(int i, int j) const;

  /// Writes the picture as an 8-bit RGB PNG through a temporary name and a rename (base/AtomicFile). Throws
  /// std::runtime_error("Canvas: cannot write PATH: ...") if the folder does not exist or writing fails.
  void write_png(const std::filesystem::path& path) const;

 private:
  struct Cairo;
  std::unique_ptr<Cairo> cairo_;
  int width_ = 0, height_ = 0;
};

}  // namespace fw::viz
