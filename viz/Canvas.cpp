#include "viz/Canvas.hpp"

#include <cairo.h>
#include <fmt/format.h>

#include <algorithm>
#include <cmath>
#include <numbers>
#include <stdexcept>

#include "base/AtomicFile.hpp"

namespace fw::viz {

namespace {

constexpr int kLargestSide = 16384;  // px: cairo's image surfaces stop at 32767; a sane picture far sooner
constexpr const char* kFontFace = "DejaVu Sans";

std::uint8_t channel_byte(double c) {
  return std::uint8_t(std::lround(std::clamp(c, 0.0, 1.0) * 255.0));
}

}  // namespace

struct Canvas::Cairo {
  cairo_surface_t* surface = nullptr;
  cairo_t* context = nullptr;
  ~Cairo() {
    if (context) cairo_destroy(context);
    if (surface) cairo_surface_destroy(surface);
  }
  void set_colour(Rgb c) const { cairo_set_source_rgb(context, c.r, c.g, c.b); }
  void set_font(double size) const {
    cairo_select_font_face(context, kFontFace, CAIRO_FONT_SLANT_NORMAL, CAIRO_FONT_WEIGHT_NORMAL);
    cairo_set_font_size(context, size);
  }
};

Canvas::Canvas(int width, int height, Rgb background)
    : cairo_(std::make_unique<Cairo>()), width_(width), height_(height) {
  if (width < 1 || height < 1 || width > kLargestSide || height > kLargestSide)
    throw std::invalid_argument(
        fmt::format("Canvas: {} x {} px: each side must be 1..{}", width, height, kLargestSide));
  cairo_->surface = cairo_image_surface_create(CAIRO_FORMAT_RGB24, width, height);
  cairo_->context = cairo_create(cairo_->surface);
  if (cairo_status(cairo_->context) != CAIRO_STATUS_SUCCESS)
    throw std::runtime_error(std::string("Canvas: cairo: ") +
                             cairo_status_to_string(cairo_status(cairo_->context)));
  fill_rect(0, 0, width, height, background, false);
}

Canvas::~Canvas() = default;
Canvas::Canvas(Canvas&&) noexcept = default;
Canvas& Canvas::operator=(Canvas&&) noexcept = default;

void Canvas::fill_rect(double x, double y, double w, double h, Rgb colour, bool antialias) {
  cairo_t* cr = cairo_->context;
  cairo_set_antialias(cr, antialias ? CAIRO_ANTIALIAS_DEFAULT : CAIRO_ANTIALIAS_NONE);
  cairo_->set_colour(colour);
  cairo_rectangle(cr, x, y, w, h);
  cairo_fill(cr);
  cairo_set_antialias(cr, CAIRO_ANTIALIAS_DEFAULT);
}

void Canvas::stroke_rect(double x, double y, double w, double h, Rgb colour, double line_width) {
  cairo_t* cr = cairo_->context;
  cairo_->set_colour(colour);
  cairo_set_line_width(cr, line_width);
  cairo_rectangle(cr, x, y, w, h);
  cairo_stroke(cr);
}

void Canvas::fill_polygon(const std::vector<Point2>& points, Rgb colour, bool antialias) {
  if (points.size() < 3) throw std::invalid_argument("Canvas: fill_polygon needs at least 3 points");
  cairo_t* cr = cairo_->context;
  cairo_set_antialias(cr, antialias ? CAIRO_ANTIALIAS_DEFAULT : CAIRO_ANTIALIAS_NONE);
  cairo_->set_colour(colour);
  cairo_move_to(cr, points[0].x, points[0].y);
  for (std::size_t n = 1; n < points.size(); ++n) cairo_line_to(cr, points[n].x, points[n].y);
  cairo_close_path(cr);
  cairo_fill(cr);
  cairo_set_antialias(cr, CAIRO_ANTIALIAS_DEFAULT);
}

void Canvas::line(const std::vector<Point2>& points, Rgb colour, double line_width, double dash) {
  if (points.size() < 2) throw std::invalid_argument("Canvas: line needs at least 2 points");
  cairo_t* cr = cairo_->context;
  cairo_->set_colour(colour);
  cairo_set_line_width(cr, line_width);
  cairo_set_line_cap(cr, dash > 0.0 ? CAIRO_LINE_CAP_BUTT : CAIRO_LINE_CAP_ROUND);
  cairo_set_line_join(cr, CAIRO_LINE_JOIN_ROUND);
  if (dash > 0.0) cairo_set_dash(cr, &dash, 1, 0.0);
  cairo_move_to(cr, points[0].x, points[0].y);
  for (std::size_t n = 1; n < points.size(); ++n) cairo_line_to(cr, points[n].x, points[n].y);
  cairo_stroke(cr);
  cairo_set_dash(cr, nullptr, 0, 0.0);
}

void Canvas::segments(const std::vector<std::array<Point2, 2>>& segments, Rgb colour, double line_width) {
  if (segments.empty()) return;
  cairo_t* cr = cairo_->context;
  cairo_->set_colour(colour);
  cairo_set_line_width(cr, line_width);
  cairo_set_line_cap(cr, CAIRO_LINE_CAP_ROUND);
  cairo_new_path(cr);
  for (const auto& [a, b] : segments) {
    cairo_move_to(cr, a.x, a.y);
    cairo_line_to(cr, b.x, b.y);
  }
  cairo_stroke(cr);
}

void Canvas::disc(Point2 centre, double radius, Rgb colour) {
  cairo_t* cr = cairo_->context;
  cairo_->set_colour(colour);
  cairo_new_path(cr);
  cairo_arc(cr, centre.x, centre.y, radius, 0.0, 2.0 * std::numbers::pi);
  cairo_fill(cr);
}

void Canvas::text(Point2 anchor, const std::string& text, double size, Rgb colour, Align align,
                  double angle) {
  cairo_t* cr = cairo_->context;
  cairo_->set_font(size);
  cairo_text_extents_t extents;
  cairo_text_extents(cr, text.c_str(), &extents);
  const double shift = align == Align::left     ? 0.0
                       : align == Align::centre ? extents.x_advance / 2
                                                : extents.x_advance;
  cairo_save(cr);
  cairo_translate(cr, anchor.x, anchor.y);
  cairo_rotate(cr, -angle * std::numbers::pi / 180.0);
  cairo_move_to(cr, -shift, 0.0);
  cairo_->set_colour(colour);
  cairo_show_text(cr, text.c_str());
  cairo_restore(cr);
}

double Canvas::text_width(const std::string& text, double size) const {
  cairo_->set_font(size);
  cairo_text_extents_t extents;
  cairo_text_extents(cairo_->context, text.c_str(), &extents);
  return extents.x_advance;
}

void Canvas::image(const std::vector<Rgb>& pixels, int w, int h, double x, double y, double width,
                   double height) {
  if (w < 1 || h < 1 || pixels.size() != std::size_t(w) * std::size_t(h))
    throw std::invalid_argument(fmt::format("Canvas: image of {} x {} needs {} pixels, got {}", w, h,
                                            std::size_t(std::max(w, 0)) * std::size_t(std::max(h, 0)),
                                            pixels.size()));
  cairo_surface_t* source = cairo_image_surface_create(CAIRO_FORMAT_RGB24, w, h);
  cairo_surface_flush(source);
  unsigned char* data = cairo_image_surface_get_data(source);
  const int stride = cairo_image_surface_get_stride(source);
  for (int j = 0; j < h; ++j) {
    auto* row = reinterpret_cast<std::uint32_t*>(data + std::size_t(j) * stride);
    for (int i = 0; i < w; ++i) {
      const Rgb& c = pixels[std::size_t(j) * w + i];
      row[i] = (std::uint32_t(channel_byte(c.r)) << 16) | (std::uint32_t(channel_byte(c.g)) << 8) |
               channel_byte(c.b);
    }
  }
  cairo_surface_mark_dirty(source);
  cairo_t* cr = cairo_->context;
  cairo_save(cr);
  cairo_rectangle(cr, x, y, width, height);
  cairo_clip(cr);
  cairo_translate(cr, x, y);
  cairo_scale(cr, width / w, height / h);
  cairo_set_source_surface(cr, source, 0.0, 0.0);
  cairo_pattern_set_filter(cairo_get_source(cr), CAIRO_FILTER_NEAREST);
  cairo_paint(cr);
  cairo_restore(cr);
  cairo_surface_destroy(source);
}

void Canvas::clip(double x, double y, double w, double h) {
  cairo_reset_clip(cairo_->context);
  cairo_rectangle(cairo_->context, x, y, w, h);
  cairo_clip(cairo_->context);
}

void Canvas::reset_clip() {
  cairo_reset_clip(cairo_->context);
}

std::array<std::uint8_t, 3> Canvas::pixel(int i, int j) const {
  if (i < 0 || j < 0 || i >= width_ || j >= height_)
    throw std::invalid_argument(fmt::format("Canvas: pixel ({}, {}) outside {} x {}", i, j, width_, height_));
  cairo_surface_flush(cairo_->surface);
  const unsigned char* data = cairo_image_surface_get_data(cairo_->surface);
  const int stride = cairo_image_surface_get_stride(cairo_->surface);
  const std::uint32_t value = reinterpret_cast<const std::uint32_t*>(data + std::size_t(j) * stride)[i];
  return {std::uint8_t(value >> 16), std::uint8_t(value >> 8), std::uint8_t(value)};
}

void Canvas::write_png(const std::filesystem::path& path) const {
  base::require_output_folder("Canvas", path);
  base::AtomicFile file(path);
  cairo_surface_flush(cairo_->surface);
  const cairo_status_t status = cairo_surface_write_to_png(cairo_->surface, file.temporary_path().c_str());
  if (status != CAIRO_STATUS_SUCCESS)
    throw std::runtime_error(
        fmt::format("Canvas: cannot write {}: {}", path.string(), cairo_status_to_string(status)));
  file.commit();
}

}  // namespace fw::viz
