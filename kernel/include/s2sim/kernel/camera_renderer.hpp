#pragma once
/// \file
/// What draws a simulation's cameras. The kernel holds no OpenGL: the program that runs a
/// simulation gives it a factory (s2sim-run, s2sim-view and the Python module give the
/// headless renderer of `s2sim::render`), and the first camera frame makes the renderer.

#include <s2sim/image.hpp>
#include <s2sim/math.hpp>

#include <functional>
#include <memory>

namespace s2sim {

class Simulation;

/// Draws the scene of the simulation it was made for.
class CameraRenderer {
 public:
  virtual ~CameraRenderer() = default;
  /// Draws every body at `body_poses` (the simulation's body indices, `body_count` of them)
  /// from `shot` into the images given (null: not wanted), as `StepContext::render_camera`
  /// documents them. Throws s2sim::Error when it cannot.
  virtual void render(const CameraShot& shot, const Pose* body_poses, int body_count, Image* rgb,
                      Image* depth, Image* body_ids) = 0;
};

/// Makes the renderer for a simulation, once, at its first camera frame; throws s2sim::Error
/// saying why when it cannot (no display driver, say).
using CameraRendererFactory = std::function<std::unique_ptr<CameraRenderer>(const Simulation&)>;

}  // namespace s2sim
