#pragma once
/// \file
/// The camera benchmark's shared parts (camera_bench.cpp, camera_mujoco.cpp): image sizes, a
/// view from an eye at a target, and the frames-per-second timing.

#include <chrono>
#include <cstdio>
#include <ctime>
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
  bool depth = false;           ///< depth only (else colour only)
  long frames = 0;              ///< in the best repeat
  double ms_per_frame = 0;      ///< wall time, the best repeat
  double cpu_ms_per_frame = 0;  ///< the process's CPU time (every thread: llvmpipe's too)
};

/// The process's CPU time in seconds, every thread counted.
inline double process_cpu_s() {
  timespec t{};
  clock_gettime(CLOCK_PROCESS_CPUTIME_ID, &t);
  return static_cast<double>(t.tv_sec) + 1e-9 * static_cast<double>(t.tv_nsec);
}

/// Calls `frame` three times unmeasured, then `repeats` times for `seconds` of wall time each
/// (10 frames at least): the repeat of the least wall time per frame.
template <class Frame>
Result time_frames(Size size, bool depth, double seconds, int repeats, Frame&& frame) {
  using Clock = std::chrono::steady_clock;
  for (int i = 0; i < 3; ++i)
    frame();
  Result best;
  for (int repeat = 0; repeat < repeats; ++repeat) {
    Result r;
    r.size = size;
    r.depth = depth;
    const auto start = Clock::now();
    const double cpu_start = process_cpu_s();
    double elapsed = 0;
    while (r.frames < 10 || elapsed < seconds) {
      frame();
      ++r.frames;
      elapsed = std::chrono::duration<double>(Clock::now() - start).count();
    }
    r.ms_per_frame = 1e3 * elapsed / static_cast<double>(r.frames);
    r.cpu_ms_per_frame = 1e3 * (process_cpu_s() - cpu_start) / static_cast<double>(r.frames);
    if (repeat == 0 || r.ms_per_frame < best.ms_per_frame) best = r;
  }
  return best;
}

/// Writes `rgb` (3 bytes a pixel, rows of `width_px`) as a binary PPM, the bottom row first
/// when `bottom_up`; for looking at what each engine drew (--images).
void write_ppm(const std::string& path, const unsigned char* rgb, Size size, bool bottom_up);

/// MuJoCo's offscreen frames of the MJCF file `mjcf` after `settle_s` of stepping, colour then
/// depth at each size (camera_mujoco.cpp); the colour frames written to
/// `images_path`-<width>.ppm unless it is empty. Throws std::runtime_error saying why it cannot.
std::vector<Result> mujoco_fps(const std::string& mjcf, const View& view,
                               const std::vector<Size>& sizes, double seconds, int repeats,
                               double settle_s, const std::string& images_path);

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
