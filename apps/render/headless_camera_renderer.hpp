#pragma once
/// \file
/// The kernel's camera renderer (s2sim/kernel/camera_renderer.hpp) drawn headless: an EGL
/// context of its own (headless_context.hpp), the scene's drawables built once, the bodies
/// at the poses the kernel passes, the images read back (camera_images.hpp). Needs no
/// window and no display server.

#include <s2sim/kernel/camera_renderer.hpp>

#include <memory>

namespace s2sim::render {

/// A renderer for `sim`'s cameras. Throws s2sim::Error (runtime) naming EGL and its error
/// when no OpenGL context can be made. `sim` must outlive it.
std::unique_ptr<CameraRenderer> make_headless_camera_renderer(const Simulation& sim);

/// For Simulation::set_camera_renderer.
CameraRendererFactory headless_camera_renderer_factory();

}  // namespace s2sim::render
