#pragma once
/// \file
/// Images that components write and read (a camera's colour, depth and segmentation, a 3-D
/// lidar's range image and point cloud), and the camera shot the kernel's renderer draws.
/// An image's pixels live in the kernel and are read in place: no copy from the writer to a
/// controller, to Python or to a file.

#include <s2sim/math.hpp>

#include <cstddef>
#include <cstdint>

namespace s2sim {

/// What one pixel holds.
enum class PixelFormat : std::int32_t {
  rgb8 = 0,         ///< red, green, blue, one byte each (0..255)
  float32 = 1,      ///< one float: a depth or a range in metres (+infinity = nothing hit)
  uint16 = 2,       ///< one unsigned 16-bit integer: a segmentation id
  xyz_float32 = 3,  ///< three floats: a point in metres (NaN where nothing was hit)
};

/// Bytes of one pixel of `format`.
constexpr int bytes_per_pixel(PixelFormat format) {
  return format == PixelFormat::rgb8          ? 3
         : format == PixelFormat::float32     ? 4
         : format == PixelFormat::uint16      ? 2
         : format == PixelFormat::xyz_float32 ? 12
                                              : 0;
}

/// The most pixels one side of an image may have (a camera's, a canvas's, a lidar's).
inline constexpr int kMaxImageSide_px = 16384;
/// The most pixels one image may have.
inline constexpr std::int64_t kMaxImagePixels = std::int64_t{1} << 26;

/// The segmentation id of a pixel where the camera sees no body (the sky).
inline constexpr std::uint16_t kNoBodyId = 0xFFFF;

/// An image declared with `ConfigureContext::declare_image`, to read or write with
/// `StepContext::image` and `StepContext::begin_image`.
struct ImageHandle {
  std::int32_t index = -1;
};

/// An image as it stands: `height_px` rows of `stride_bytes`, the top row first, each of
/// `width_px` pixels of `format`. `frame` counts the frames written since the last reset (0:
/// none yet: the pixels are as the reset left them, zero, or white for a SimTwo canvas),
/// `time_s` is the simulated time of the last one.
struct Image {
  std::int32_t width_px = 0;
  std::int32_t height_px = 0;
  std::int32_t stride_bytes = 0;
  PixelFormat format = PixelFormat::rgb8;
  std::uint64_t frame = 0;
  double time_s = 0;
  std::uint8_t* data = nullptr;

  /// The first byte of row `y` (0 = top).
  std::uint8_t* row(int y) const { return data + static_cast<std::ptrdiff_t>(y) * stride_bytes; }
  std::size_t size_bytes() const {
    return static_cast<std::size_t>(height_px) * static_cast<std::size_t>(stride_bytes);
  }
};

/// What a camera sees from, for `StepContext::render_camera`. The camera frame looks along its
/// +Z axis with +Y up (SimTwo's `<camera>` convention), so +X points to the image's left.
struct CameraShot {
  Pose pose;                    ///< camera frame in the world
  double vertical_fov_rad = 0;  ///< full vertical field of view, in (0, pi)
  double near_m = 0.01;         ///< nearest distance drawn, along the optical axis
  double far_m = 100;           ///< farthest distance drawn, along the optical axis
  std::int32_t width_px = 0;
  std::int32_t height_px = 0;
};

/// The camera frame in a sensor frame: a sensor looks along its +X with +Z up (every sensor's
/// beam axis), a CameraShot along its +Z with +Y up. Columns: the camera's X, Y, Z axes in the
/// sensor frame (+Y, +Z, +X).
constexpr Mat3 camera_frame_in_sensor() {
  Mat3 r;
  r.m[0][0] = 0, r.m[0][1] = 0, r.m[0][2] = 1;
  r.m[1][0] = 1, r.m[1][1] = 0, r.m[1][2] = 0;
  r.m[2][0] = 0, r.m[2][1] = 1, r.m[2][2] = 0;
  return r;
}

}  // namespace s2sim
