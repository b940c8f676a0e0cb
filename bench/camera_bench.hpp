#pragma once
/// \file
/// The camera benchmark's shared parts (camera_bench.cpp, camera_mujoco.cpp): image sizes, a
/// view from an eye at a target, and the frames-per-second timing.

#include <chrono>
#include <cstdio>
#include <string>
#include <vector>

namespace camera_bench {

struct Size {
  int width_px = 0;
  int height_px = 0;
};

/// A free view: the eye looking at the target (world, metres), +Z up in the image.
struct View {
  double eye[3] = {0, 0, 0};
  double target[3] = {1, 0, 0};
  double vertical_fov_deg = 60;
  double near_m = 0.05;
  double far_m = 50;
};

struct Result {
  Size size;
  bool depth = false;  ///< depth only (else colour only)
  long frames = 0;
  double ms_per_frame = 0;
};

/// Calls `frame` three times unmeasured, then for `seconds` of wall time (10 frames at least).
template <class Frame>
Result time_frames(Size size, bool depth, double seconds, Frame&& frame) {
  using Clock = std::chrono::steady_clock;
  for (int i = 0; i < 3; ++i)
    frame();
  Result r;
  r.size = size;
  r.depth = depth;
  const auto start = Clock::now();
  double elapsed = 0;
  while (r.frames < 10 || elapsed < seconds) {
    frame();
    ++r.frames;
    elapsed = std::chrono::duration<double>(Clock::now() - start).count();
  }
  r.ms_per_frame = 1e3 * elapsed / static_cast<double>(r.frames);
  return r;
}

/// Writes `rgb` (3 bytes a pixel, rows of `width_px`) as a binary PPM, the bottom row first
/// when `bottom_up`; for looking at what each engine drew (--images).
void write_ppm(const std::string& path, const unsigned char* rgb, Size size, bool bottom_up);

/// MuJoCo's offscreen frames of the MJCF file `mjcf` after `settle_s` of stepping, colour then
/// depth at each size (camera_mujoco.cpp); the colour frames written to
/// `images_path`-<width>.ppm unless it is empty. Throws std::runtime_error saying why it cannot.
std::vector<Result> mujoco_fps(const std::string& mjcf, const View& view,
                               const std::vector<Size>& sizes, double seconds, double settle_s,
                               const std::string& images_path);

inline void write_ppm(const std::string& path, const unsigned char* rgb, Size size,
                      bool bottom_up) {
  std::FILE* f = std::fopen(path.c_str(), "wb");
  if (!f) return;
  std::fprintf(f, "P6\n%d %d\n255\n", size.width_px, size.height_px);
  const auto row = static_cast<std::size_t>(3 * size.width_px);
  for (int y = 0; y < size.height_px; ++y)
    std::fwrite(rgb + row * static_cast<std::size_t>(bottom_up ? size.height_px - 1 - y : y), 1,
                row, f);
  std::fclose(f);
}

}  // namespace camera_bench
