#include "canvas_painter.hpp"

#include <cairo/cairo.h>

#include <algorithm>
#include <cmath>
#include <cstring>
#include <stdexcept>

namespace s2sim::pascal {

namespace {

/// Pixels per point of a Delphi font (Screen.PixelsPerInch 96).
constexpr double kPixelsPerPoint = 96.0 / 72.0;

/// A TColor's red, green and blue bytes ($BBGGRR; a system colour's flag byte ignored).
void channels(std::int32_t color, int& r, int& g, int& b) {
  const auto c = static_cast<std::uint32_t>(color);
  r = static_cast<int>(c & 0xFF);
  g = static_cast<int>((c >> 8) & 0xFF);
  b = static_cast<int>((c >> 16) & 0xFF);
}

}  // namespace

CanvasPainter::CanvasPainter(int width_px, int height_px) : width_(width_px), height_(height_px) {
  surface_ = cairo_image_surface_create(CAIRO_FORMAT_RGB24, width_px, height_px);
  if (cairo_surface_status(surface_) != CAIRO_STATUS_SUCCESS) {
    cairo_surface_destroy(surface_);
    throw std::runtime_error("cannot make a " + std::to_string(width_px) + " x " +
                             std::to_string(height_px) + " canvas (Cairo)");
  }
  cr_ = cairo_create(surface_);
  cairo_set_antialias(cr_, CAIRO_ANTIALIAS_NONE);  // GDI draws shapes aliased
  clear(0xFFFFFF);
}

CanvasPainter::~CanvasPainter() {
  cairo_destroy(cr_);
  cairo_surface_destroy(surface_);
}

void CanvasPainter::set_source(std::int32_t color) {
  int r = 0, g = 0, b = 0;
  channels(color, r, g, b);
  cairo_set_source_rgb(cr_, r / 255.0, g / 255.0, b / 255.0);
}

void CanvasPainter::clear(std::int32_t color) {
  set_source(color);
  cairo_paint(cr_);
  dirty_ = true;
}

void CanvasPainter::rectangle(int x1, int y1, int x2, int y2, const CanvasTools& t, bool ellipse) {
  if (x2 < x1) std::swap(x1, x2);
  if (y2 < y1) std::swap(y1, y2);
  const double w = x2 - x1, h = y2 - y1;
  if (w <= 0 || h <= 0) return;
  auto path = [&](double inset) {
    cairo_new_path(cr_);
    if (!ellipse) {
      cairo_rectangle(cr_, x1 + inset, y1 + inset, w - 2 * inset, h - 2 * inset);
      return;
    }
    cairo_save(cr_);
    cairo_translate(cr_, x1 + w / 2, y1 + h / 2);
    cairo_scale(cr_, std::max(w / 2 - inset, 0.01), std::max(h / 2 - inset, 0.01));
    cairo_arc(cr_, 0, 0, 1, 0, 2 * 3.14159265358979323846);
    cairo_restore(cr_);
  };
  if (!t.brush_clear) {
    path(0);
    set_source(t.brush_color);
    cairo_fill(cr_);
  }
  if (!t.pen_clear) {
    const int pen = std::max(t.pen_width, 1);
    path(pen / 2.0);  // the outline inside the box, its centre half a pen in
    set_source(t.pen_color);
    cairo_set_line_width(cr_, pen);
    cairo_stroke(cr_);
  }
  dirty_ = true;
}

void CanvasPainter::fill_rect(int x1, int y1, int x2, int y2, const CanvasTools& t) {
  if (x2 < x1) std::swap(x1, x2);
  if (y2 < y1) std::swap(y1, y2);
  if (x2 == x1 || y2 == y1) return;
  cairo_new_path(cr_);
  cairo_rectangle(cr_, x1, y1, x2 - x1, y2 - y1);
  set_source(t.brush_color);
  cairo_fill(cr_);
  dirty_ = true;
}

void CanvasPainter::line(int x1, int y1, int x2, int y2, const CanvasTools& t) {
  if (t.pen_clear) return;
  cairo_new_path(cr_);
  cairo_move_to(cr_, x1 + 0.5, y1 + 0.5);  // through the pixels' centres
  cairo_line_to(cr_, x2 + 0.5, y2 + 0.5);
  set_source(t.pen_color);
  cairo_set_line_width(cr_, std::max(t.pen_width, 1));
  cairo_set_line_cap(cr_, CAIRO_LINE_CAP_BUTT);
  cairo_stroke(cr_);
  dirty_ = true;
}

void CanvasPainter::select_font(const std::string& font_name, const CanvasTools& t) {
  // fontconfig stands in its sans-serif face for a name it does not have (Tahoma, Arial...).
  cairo_select_font_face(cr_, font_name.empty() ? "sans-serif" : font_name.c_str(),
                         t.italic ? CAIRO_FONT_SLANT_ITALIC : CAIRO_FONT_SLANT_NORMAL,
                         t.bold ? CAIRO_FONT_WEIGHT_BOLD : CAIRO_FONT_WEIGHT_NORMAL);
  cairo_set_font_size(cr_, std::max(t.font_size_pt, 1.0) * kPixelsPerPoint);
}

double CanvasPainter::text(int x, int y, const std::string& text, const std::string& font_name,
                           const CanvasTools& t) {
  select_font(font_name, t);
  cairo_font_extents_t font;
  cairo_font_extents(cr_, &font);
  cairo_text_extents_t ext;
  cairo_text_extents(cr_, text.c_str(), &ext);
  if (!t.brush_clear) {  // GDI's opaque background: the text's cell
    cairo_new_path(cr_);
    cairo_rectangle(cr_, x, y, std::ceil(ext.x_advance), std::ceil(font.ascent + font.descent));
    set_source(t.brush_color);
    cairo_fill(cr_);
  }
  cairo_set_antialias(cr_, CAIRO_ANTIALIAS_GRAY);  // text reads better smoothed
  cairo_new_path(cr_);
  cairo_move_to(cr_, x, y + font.ascent);
  set_source(t.font_color);
  cairo_show_text(cr_, text.c_str());
  cairo_set_antialias(cr_, CAIRO_ANTIALIAS_NONE);
  dirty_ = true;
  return ext.x_advance;
}

double CanvasPainter::text_size(const std::string& text, const std::string& font_name,
                                const CanvasTools& t, bool height) {
  select_font(font_name, t);
  if (height) {
    cairo_font_extents_t font;
    cairo_font_extents(cr_, &font);
    return std::ceil(font.ascent + font.descent);
  }
  cairo_text_extents_t ext;
  cairo_text_extents(cr_, text.c_str(), &ext);
  return std::ceil(ext.x_advance);
}

std::int32_t CanvasPainter::pixel(int x, int y) {
  if (x < 0 || y < 0 || x >= width_ || y >= height_) return -1;
  cairo_surface_flush(surface_);
  const unsigned char* row =
      cairo_image_surface_get_data(surface_) + y * cairo_image_surface_get_stride(surface_);
  std::uint32_t p = 0;
  std::memcpy(&p, row + 4 * x, 4);  // 0x00RRGGBB in native byte order
  return static_cast<std::int32_t>(((p >> 16) & 0xFF) | (p & 0xFF00) | ((p & 0xFF) << 16));
}

void CanvasPainter::set_pixel(int x, int y, std::int32_t color) {
  if (x < 0 || y < 0 || x >= width_ || y >= height_) return;
  cairo_surface_flush(surface_);
  unsigned char* row =
      cairo_image_surface_get_data(surface_) + y * cairo_image_surface_get_stride(surface_);
  int r = 0, g = 0, b = 0;
  channels(color, r, g, b);
  const std::uint32_t p = (static_cast<std::uint32_t>(r) << 16) |
                          (static_cast<std::uint32_t>(g) << 8) | static_cast<std::uint32_t>(b);
  std::memcpy(row + 4 * x, &p, 4);
  cairo_surface_mark_dirty_rectangle(surface_, x, y, 1, 1);
  dirty_ = true;
}

void CanvasPainter::copy_to(Image& image) {
  cairo_surface_flush(surface_);
  const unsigned char* data = cairo_image_surface_get_data(surface_);
  const int stride = cairo_image_surface_get_stride(surface_);
  const int w = std::min(width_, image.width_px), h = std::min(height_, image.height_px);
  for (int y = 0; y < h; ++y) {
    const unsigned char* in = data + y * stride;
    std::uint8_t* out = image.row(y);
    for (int x = 0; x < w; ++x) {
      std::uint32_t p = 0;
      std::memcpy(&p, in + 4 * x, 4);
      out[3 * x] = static_cast<std::uint8_t>(p >> 16);
      out[3 * x + 1] = static_cast<std::uint8_t>(p >> 8);
      out[3 * x + 2] = static_cast<std::uint8_t>(p);
    }
  }
  dirty_ = false;
}

}  // namespace s2sim::pascal
