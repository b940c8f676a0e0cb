#pragma once
/// \file
/// A camera renderer for tests of what cameras ask for (camera_renderer.hpp): it records each
/// shot and fills the images it is given with constants: colour 100, depth 2 m, body id 7.

#include <s2sim/kernel/simulation.hpp>

#include <cstring>
#include <memory>
#include <vector>

namespace s2sim::test {

class RecordingRenderer final : public CameraRenderer {
 public:
  explicit RecordingRenderer(std::vector<CameraShot>& shots) : shots_(shots) {}
  void render(const CameraShot& shot, const Pose*, int, Image* rgb, Image* depth,
              Image* ids) override {
    shots_.push_back(shot);
    if (rgb) std::memset(rgb->data, 100, rgb->size_bytes());
    for (int y = 0; depth && y < depth->height_px; ++y)
      for (int x = 0; x < depth->width_px; ++x)
        reinterpret_cast<float*>(depth->row(y))[x] = 2.0f;
    for (int y = 0; ids && y < ids->height_px; ++y)
      for (int x = 0; x < ids->width_px; ++x)
        reinterpret_cast<std::uint16_t*>(ids->row(y))[x] = 7;
  }

 private:
  std::vector<CameraShot>& shots_;
};

/// Gives `sim` a RecordingRenderer that appends to `shots`.
inline void record_shots(Simulation& sim, std::vector<CameraShot>& shots) {
  sim.set_camera_renderer([&shots](const Simulation&) -> std::unique_ptr<CameraRenderer> {
    return std::make_unique<RecordingRenderer>(shots);
  });
}

}  // namespace s2sim::test
