#pragma once
/// \file
/// One SimTwo canvas as a script draws on it (Delphi's TCanvas, docs/scripting.md "Canvases"):
/// a Cairo raster of the canvas's size, drawn with GDI's pixel conventions (a rectangle's
/// right and bottom edges excluded, aliased shapes, a 1-pixel pen for width 0), copied into
/// the kernel's canvas image when it changed. The Cairo surface is made once, at configure.

#include <s2sim/image.hpp>

#include <cstdint>
#include <string>

typedef struct _cairo cairo_t;
typedef struct _cairo_surface cairo_surface_t;

namespace s2sim::pascal {

/// Delphi's TPen, TBrush and TFont as the script's TCanvas holds them at a call.
struct CanvasTools {
  std::int32_t pen_color = 0;  ///< TColor, $BBGGRR
  int pen_width = 1;           ///< pixels; 0 draws 1
  bool pen_clear = false;      ///< Pen.Style = psClear: no outline
  std::int32_t brush_color = 0xFFFFFF;
  bool brush_clear = false;  ///< Brush.Style = bsClear: no fill (nor text background)
  std::int32_t font_color = 0;
  double font_size_pt = 8;  ///< Font.Size, points at 96 pixels per inch
  bool bold = false, italic = false;
};

class CanvasPainter {
 public:
  CanvasPainter(int width_px, int height_px);
  ~CanvasPainter();
  CanvasPainter(const CanvasPainter&) = delete;
  CanvasPainter& operator=(const CanvasPainter&) = delete;

  int width() const { return width_; }
  int height() const { return height_; }

  /// Every pixel `color` (SolidCanvasClear: the brush's colour; white at a reset).
  void clear(std::int32_t color);
  /// The outline (pen) and inside (brush) of the box from (x1, y1) to (x2, y2), x2 and y2
  /// excluded: Rectangle. `ellipse`: the ellipse inscribed in it (Ellipse).
  void rectangle(int x1, int y1, int x2, int y2, const CanvasTools& t, bool ellipse);
  /// The box filled with the brush, no outline: FillRect.
  void fill_rect(int x1, int y1, int x2, int y2, const CanvasTools& t);
  /// A pen line from (x1, y1) to (x2, y2): LineTo.
  void line(int x1, int y1, int x2, int y2, const CanvasTools& t);
  /// `text` with its cell's top-left corner at (x, y), on the brush's colour unless the brush
  /// is clear: TextOut. Returns the text's advance in pixels (the pen moves by it).
  double text(int x, int y, const std::string& text, const std::string& font_name,
              const CanvasTools& t);
  /// TextWidth (`height` false) or TextHeight of `text` in the font.
  double text_size(const std::string& text, const std::string& font_name, const CanvasTools& t,
                   bool height);
  /// Pixels[x, y]: the TColor there, -1 outside (GDI's CLR_INVALID).
  std::int32_t pixel(int x, int y);
  void set_pixel(int x, int y, std::int32_t color);

  /// Whether it changed since the last copy.
  bool dirty() const { return dirty_; }
  /// Counts it unchanged (its image already holds the same pixels).
  void set_clean() { dirty_ = false; }
  /// Copies the pixels into `image` (rgb8, the same size) and marks it clean.
  void copy_to(Image& image);

 private:
  void set_source(std::int32_t color);
  void select_font(const std::string& font_name, const CanvasTools& t);
  int width_ = 0, height_ = 0;
  cairo_surface_t* surface_ = nullptr;
  cairo_t* cr_ = nullptr;
  bool dirty_ = true;
};

}  // namespace s2sim::pascal
