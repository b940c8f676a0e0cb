/// `camera` (docs/models/sensors.md, "Cameras"): at its period, the scene as the other sensors
/// see it this tick, drawn by the simulation's renderer into up to three images:
///   `rgb` (rgb8), `depth` (float32, metres along the optical axis, +infinity: nothing
///   within `far`) and `segmentation` (uint16, the simulation's body index; 0 the world's
///   floor and obstacles, 65535 the sky).
/// The sensor frame looks along its +X with +Z up, as every sensor's beam does; a `<camera>`
/// shell is made into one by the loader, looking along the shell's +Z with +Y up (SimTwo's).
/// Noise: `<noise>` (SimTwo's generic model) on each colour channel in 0..255 levels, rounded
/// and clamped; `<depth_noise>` the same model on the depth, in metres.
#include "kinds.hpp"

#include <algorithm>
#include <cmath>
#include <limits>

namespace s2sim::sensors {
namespace {

/// SimTwo's `focal length` (GLScene's FocalLength) as the full field of view across the
/// image's longer side: GLScene's ApplyPerspective puts the near plane at
/// f·2·dpi/(25.4·maxdim) with half-extents of ½ across the longer side, on SimTwo's
/// 640-pixel camera image at 96 dpi, so tan(fov/2) = 25.4·640/(4·96·f).
double focal_length_fov_rad(double focal_length) {
  return 2 * std::atan(25.4 * 640 / (4 * 96 * focal_length));
}

/// The default period of a camera without `<period>`: a frame every 40 ms, SimTwo's
/// `decimation` counting frames of 10 ms.
constexpr double kDefaultCameraPeriod_s = 0.04;
constexpr double kDecimationUnit_s = 0.01;

}  // namespace

void CameraSensor::configure(ConfigureContext& ctx) {
  s_.read(ctx);
  const Params& p = ctx.params();
  const int width = p.integer_in("frame.width", 320, 1, kMaxImageSide_px);
  const int height = p.integer_in("frame.height", 240, 1, kMaxImageSide_px);
  if (static_cast<std::int64_t>(width) * height > kMaxImagePixels)
    fail(p, "frame", "width",
         std::to_string(width) + " x " + std::to_string(height) + " pixels is more than " +
             std::to_string(kMaxImagePixels));
  shot_.width_px = width;
  shot_.height_px = height;

  // The field of view: one of <fov vertical>, <fov horizontal> or <focal length> (SimTwo's;
  // also the default, 50).
  const int ways =
      int{p.has("fov.vertical")} + int{p.has("fov.horizontal")} + int{p.has("focal.length")};
  if (ways > 1)
    fail(p, "fov", p.has("fov.vertical") ? "vertical" : "horizontal",
         "give one of <fov vertical>, <fov horizontal> and <focal length>, not several");
  const double longer = std::max(width, height),
               shorter_over_longer = std::min(width, height) / longer;
  double vertical_rad = 0;
  auto from_longer_side = [&](double fov_rad) {
    // The vertical field from the field across the longer side.
    return width >= height ? 2 * std::atan(std::tan(fov_rad / 2) * shorter_over_longer) : fov_rad;
  };
  if (p.has("fov.vertical")) {
    vertical_rad = p.number("fov.vertical", Range{0, 180, true, true}) * kPi / 180;
  } else if (p.has("fov.horizontal")) {
    const double h = p.number("fov.horizontal", Range{0, 180, true, true}) * kPi / 180;
    vertical_rad = 2 * std::atan(std::tan(h / 2) * height / static_cast<double>(width));
  } else {
    const double f = p.number("focal.length", 50.0, Range::positive());
    vertical_rad = from_longer_side(focal_length_fov_rad(f));
  }
  shot_.vertical_fov_rad = vertical_rad;
  shot_.near_m = p.number("clip.near", 0.01, Range::positive());
  shot_.far_m = p.number("clip.far", 100.0, Range::positive());
  if (!(shot_.far_m > shot_.near_m) || !std::isfinite(shot_.far_m))
    fail(p, "clip", "far",
         "must be finite and beyond near (" + num(shot_.near_m) + " m), got " + num(shot_.far_m));
  shot_.pose = Pose{s_.spec.pose.position, s_.spec.pose.rotation * camera_frame_in_sensor()};

  want_rgb_ = p.boolean("outputs.rgb", true);
  want_depth_ = p.boolean("outputs.depth", false);
  want_ids_ = p.boolean("outputs.segmentation", false);
  if (!want_rgb_ && !want_depth_ && !want_ids_)
    fail(p, "outputs", "rgb", "a camera needs at least one of rgb, depth and segmentation");
  if (want_rgb_) rgb_ = ctx.declare_image("rgb", width, height, PixelFormat::rgb8);
  if (want_depth_) depth_ = ctx.declare_image("depth", width, height, PixelFormat::float32);
  if (want_ids_) ids_ = ctx.declare_image("segmentation", width, height, PixelFormat::uint16);

  depth_noise_.on = p.has_element("depth_noise");
  depth_noise_.stdev = p.number("depth_noise.stdev", 0.0, Range::non_negative());
  depth_noise_.stdev_p = p.number("depth_noise.stdev_p", 0.0, Range::non_negative());
  depth_noise_.offset = p.number("depth_noise.offset", 0.0);
  depth_noise_.gain = p.number("depth_noise.gain", 1.0);
  zig_ = &ziggurat_tables();

  // The period: <period value>, or SimTwo's <frame decimation> in frames of 10 ms.
  s_.default_period(ctx, p.has("frame.decimation")
                             ? kDecimationUnit_s * static_cast<double>(p.integer_in(
                                                       "frame.decimation", 4, 1, kMaxImageSide_px))
                             : kDefaultCameraPeriod_s);
  s_.schedule(ctx);
  frames_ = ctx.declare_signal("frames", "1");
}

void CameraSensor::update(StepContext& ctx) {
  CameraShot shot = shot_;
  shot.pose = ctx.body_pose(s_.body) * shot_.pose;
  Image* rgb = want_rgb_ ? &ctx.begin_image(rgb_) : nullptr;
  Image* depth = want_depth_ ? &ctx.begin_image(depth_) : nullptr;
  Image* ids = want_ids_ ? &ctx.begin_image(ids_) : nullptr;
  ctx.render_camera(shot, rgb, depth, ids);

  RandomStream r = ctx.random();
  auto normal = [&]() { return ziggurat_normal(r, *zig_); };
  const GenericNoise& n = s_.noise;
  if (rgb && n.on) {
    for (int y = 0; y < rgb->height_px; ++y) {
      std::uint8_t* px = rgb->row(y);
      for (int i = 0; i < 3 * rgb->width_px; ++i) {
        const double v = px[i];
        double out = n.gain * v + n.offset;
        if (n.stdev > 0) out += n.stdev * normal();
        if (n.stdev_p > 0) out += n.stdev_p * v * normal();
        px[i] = static_cast<std::uint8_t>(std::clamp(std::lround(out), 0L, 255L));
      }
    }
  }
  if (depth && depth_noise_.on) {
    const GenericNoise& d = depth_noise_;
    for (int y = 0; y < depth->height_px; ++y) {
      auto* px = reinterpret_cast<float*>(depth->row(y));
      for (int i = 0; i < depth->width_px; ++i) {
        if (!std::isfinite(px[i])) continue;
        const double v = px[i];
        double out = d.gain * v + d.offset;
        if (d.stdev > 0) out += d.stdev * normal();
        if (d.stdev_p > 0) out += d.stdev_p * v * normal();
        px[i] = static_cast<float>(std::max(0.0, out));
      }
    }
  }
  const Image& any = rgb ? *rgb : depth ? *depth : *ids;
  ctx.publish(frames_, static_cast<double>(any.frame));
}

}  // namespace s2sim::sensors
