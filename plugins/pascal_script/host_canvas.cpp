// SimTwo's canvases (simtwo-script-api.md §3.8, §5.5; docs/scripting.md, "Canvases"): the
// kernel's white rgb8 image of each `<canvas>` box, drawn by the script's TCanvas through
// CanvasOp and copied into the image after the call that changed it, so that the viewer and
// the cameras show it on the box's +Z face.
#include "script_controller.hpp"

namespace s2sim::pascal {

namespace {

/// CanvasOp's operations (pascal/s2simtwo_rendering.pas sends the same numbers).
enum CanvasOpCode : int {
  kClear = 0,
  kRectangle = 1,
  kEllipse = 2,
  kFillRect = 3,
  kLine = 4,
  kTextOut = 5,
  kTextWidth = 6,
  kTextHeight = 7,
  kGetPixel = 8,
  kSetPixel = 9,
};

/// CanvasOp's arguments: canvas, op, x1, y1, x2, y2, then the tools.
constexpr int kToolsAt = 6;
constexpr int kCanvasOpArguments = kToolsAt + 9;

int to_int(double v) {
  if (!(v > -1e9 && v < 1e9)) return v > 0 ? 1000000000 : -1000000000;
  return static_cast<int>(std::lround(v));
}

CanvasTools tools_at(const double* a) {
  CanvasTools t;
  t.pen_color = static_cast<std::int32_t>(to_int(a[0]));
  t.pen_width = to_int(a[1]);
  t.pen_clear = a[2] != 0;
  t.brush_color = static_cast<std::int32_t>(to_int(a[3]));
  t.brush_clear = a[4] != 0;
  t.font_color = static_cast<std::int32_t>(to_int(a[5]));
  t.font_size_pt = a[6];
  t.bold = a[7] != 0;
  t.italic = a[8] != 0;
  return t;
}

}  // namespace

int ScriptController::configure_canvas(ConfigureContext& ctx, const std::string& image_name) {
  if (image_name.empty()) return -1;
  CanvasRef c;
  c.image = ctx.image(image_name);
  canvases_.push_back(std::move(c));
  return static_cast<int>(canvases_.size()) - 1;
}

void ScriptController::clear_canvases(StepContext& ctx) {
  for (CanvasRef& c : canvases_) {
    if (!c.painter) {  // the first initialize: the image's size is known from now on
      const Image& image = ctx.image(c.image);
      c.painter = std::make_unique<CanvasPainter>(image.width_px, image.height_px);
    }
    c.painter->clear(0xFFFFFF);
    c.painter->set_clean();  // as the reset left the image
  }
}

void ScriptController::flush_canvases(StepContext& ctx) {
  for (CanvasRef& c : canvases_)
    if (c.painter->dirty()) c.painter->copy_to(ctx.begin_image(c.image));
}

double ScriptController::call_canvas(HostFn fn, const double* a, int n, const std::string& s,
                                     const std::string& s2) {
  if (fn == HostFn::CanvasOf) {  // [0 solid | 1 obstacle, R or i, i]: the canvas or -1
    require_arguments(fn, n, 3);
    return a[0] == 0 ? solid(a[1], a[2]).canvas : obstacle(a[1]).canvas;
  }
  require_arguments(fn, n, kCanvasOpArguments);
  if (!(a[0] >= 0 && a[0] < static_cast<double>(canvases_.size()))) fail("not a canvas");
  CanvasPainter& p = *canvases_[static_cast<std::size_t>(a[0])].painter;
  const int x1 = to_int(a[2]), y1 = to_int(a[3]), x2 = to_int(a[4]), y2 = to_int(a[5]);
  const CanvasTools t = tools_at(a + kToolsAt);
  switch (to_int(a[1])) {
    case kClear:
      p.clear(t.brush_color);
      return 0;
    case kRectangle:
    case kEllipse:
      p.rectangle(x1, y1, x2, y2, t, to_int(a[1]) == kEllipse);
      return 0;
    case kFillRect:
      p.fill_rect(x1, y1, x2, y2, t);
      return 0;
    case kLine:
      p.line(x1, y1, x2, y2, t);
      return 0;
    case kTextOut:
      return p.text(x1, y1, s, s2, t);
    case kTextWidth:
    case kTextHeight:
      return p.text_size(s, s2, t, to_int(a[1]) == kTextHeight);
    case kGetPixel:
      return p.pixel(x1, y1);
    case kSetPixel:
      p.set_pixel(x1, y1, static_cast<std::int32_t>(x2));
      return 0;
    default:
      break;
  }
  fail("invalid canvas operation");
}

}  // namespace s2sim::pascal
