#pragma once
/// \file
/// A camera renderer for tests of what reads a camera's image: it fills the colour image with
/// a gradient whose every pixel says where it is (red across, green down, blue constant), so
/// a reader's scaling and orientation can be checked; depth 2 m, body id 7.

#include <s2sim/kernel/simulation.hpp>

#include <cstdint>
#include <memory>

namespace s2sim::test {

/// The colour the gradient renderer gives pixel (x, y) of a `w` × `h` image.
struct GradientColour {
  static std::uint8_t red(int x, int w) { return static_cast<std::uint8_t>(255 * x / (w - 1)); }
  static std::uint8_t green(int y, int h) { return static_cast<std::uint8_t>(255 * y / (h - 1)); }
  static constexpr std::uint8_t kBlue = 60;
};

class GradientRenderer final : public CameraRenderer {
 public:
  void render(const CameraShot&, const Pose*, int, Image* rgb, Image* depth, Image* ids) override {
    for (int y = 0; rgb && y < rgb->height_px; ++y)
      for (int x = 0; x < rgb->width_px; ++x) {
        std::uint8_t* px = rgb->row(y) + 3 * x;
        px[0] = GradientColour::red(x, rgb->width_px);
        px[1] = GradientColour::green(y, rgb->height_px);
        px[2] = GradientColour::kBlue;
      }
    for (int y = 0; depth && y < depth->height_px; ++y)
      for (int x = 0; x < depth->width_px; ++x)
        reinterpret_cast<float*>(depth->row(y))[x] = 2.0f;
    for (int y = 0; ids && y < ids->height_px; ++y)
      for (int x = 0; x < ids->width_px; ++x)
        reinterpret_cast<std::uint16_t*>(ids->row(y))[x] = 7;
  }
};

/// Gives `sim` a GradientRenderer.
inline void render_gradients(Simulation& sim) {
  sim.set_camera_renderer([](const Simulation&) -> std::unique_ptr<CameraRenderer> {
    return std::make_unique<GradientRenderer>();
  });
}

}  // namespace s2sim::test
