// SimTwo's camera routines for scripts (docs/scripting.md, "The camera image"):
// GetCameraPixel and CamBitmap's Canvas.Pixels read the rgb image of the scene's last
// <camera> shell (SimTwo has one on-board camera image; with several shells the last one
// declared wins). SimTwo's image is 640 × 480 pixels: the script's coordinates stay SimTwo's
// and are scaled to the camera's own size, pixel (X, Y) reading (floor(X·w/640),
// floor(Y·h/480)), row 0 the top. Without a camera shell the image is black with alpha 0, as
// SimTwo's is until its camera window draws.
#include "script_controller.hpp"

#include <cmath>

namespace s2sim::pascal {

namespace {

constexpr double kSimTwoWidth_px = 640, kSimTwoHeight_px = 480;

}  // namespace

void ScriptController::configure_camera(ConfigureContext& ctx) {
  const Params& p = ctx.params();
  const std::int64_t shells = p.integer("camera_shells", 0);
  if (shells <= 0) return;
  camera_prefix_ = p.text("camera_shell_" + std::to_string(shells - 1) + "_prefix");
  try {
    camera_image_ = ctx.image(camera_prefix_ + "/rgb");
  } catch (const Error&) {
    camera_image_.index = -1;  // no plugin gives 'camera': the routines say so
  }
}

double ScriptController::call_camera(HostFn fn, const double* a, int n) {
  require_arguments(fn, n, 2);
  const double X = a[0], Y = a[1];
  // SimTwo reads its array unchecked; here a pixel outside its 640 x 480 is an error.
  if (!(X >= 0 && X < kSimTwoWidth_px)) fail(index_error(X));
  if (!(Y >= 0 && Y < kSimTwoHeight_px)) fail(index_error(Y));
  if (camera_prefix_.empty()) {
    numbers_.assign({0.0, 0.0, 0.0, 0.0});
    return 0;
  }
  if (camera_image_.index < 0)
    fail("GetCameraPixel: camera " + camera_prefix_ +
         " has no rgb image (no plugin gives the kind 'camera')");
  const Image& img = ctx_->image(camera_image_);
  const int x = static_cast<int>(std::floor(std::floor(X) * img.width_px / kSimTwoWidth_px));
  const int y = static_cast<int>(std::floor(std::floor(Y) * img.height_px / kSimTwoHeight_px));
  const std::uint8_t* px = img.row(y) + 3 * x;
  numbers_.assign(
      {static_cast<double>(px[0]), static_cast<double>(px[1]), static_cast<double>(px[2]), 255.0});
  return 0;
}

}  // namespace s2sim::pascal
