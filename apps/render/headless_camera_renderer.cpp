#include "headless_camera_renderer.hpp"

#include "camera_images.hpp"
#include "gl.hpp"
#include "headless_context.hpp"
#include "renderer.hpp"
#include "scene_drawables.hpp"
#include "scene_look.hpp"

#include <s2sim/error.hpp>
#include <s2sim/kernel/simulation.hpp>

#include <cstdio>
#include <stdexcept>
#include <string>
#include <vector>

namespace s2sim::render {
namespace {

void print_warnings(const std::vector<std::string>& warnings) {
  for (const std::string& w : warnings)
    std::fprintf(stderr, "s2sim: cameras: warning: %s\n", w.c_str());
}

class HeadlessCameraRenderer final : public CameraRenderer {
 public:
  explicit HeadlessCameraRenderer(const Simulation& sim) : sim_(sim) {
    HeadlessContext::Current current(context_);
    try {
      gl_ = std::make_unique<Gl>();
      gl_->renderer.init();
    } catch (const std::runtime_error& e) {  // a shader the driver does not compile
      gl_.reset();
      throw Error(ErrorKind::runtime, std::string("the cameras' renderer (") +
                                          context_.description() + "): " + e.what());
    }
    std::vector<std::string> warnings, notes;
    gl_->drawables.build(sim.scene(), gl_->renderer, warnings);
    apply_scene_look(sim.scene().folder, true, gl_->renderer, gl_->settings, warnings, notes);
    // The world view's full look: the shadow map with smooth edges (multisampling is off
    // in camera images, camera_images.cpp).
    gl_->settings.shadow_map = true;
    gl_->settings.smooth_shadows = true;
    print_warnings(warnings);
    // An error of the build (a texture too large, say) costs its look only; each shot's own
    // errors are reported (camera_images.cpp).
    for (int i = 0; i < 32 && glGetError() != GL_NO_ERROR; ++i) {
    }
  }

  ~HeadlessCameraRenderer() override {
    // The OpenGL objects go with the context current.
    try {
      HeadlessContext::Current current(context_);
      gl_.reset();
    } catch (const Error&) {
      // The context is gone with its objects.
    }
  }

  void render(const CameraShot& shot, const Pose* body_poses, int body_count, Image* rgb,
              Image* depth, Image* body_ids) override {
    HeadlessContext::Current current(context_);
    warnings_.clear();
    gl_->drawables.take_meshes(sim_, gl_->renderer, warnings_);
    gl_->drawables.take_canvases(sim_, gl_->renderer);
    print_warnings(warnings_);
    gl_->drawables.update(sim_, body_poses, body_count, gl_->settings.floor_half_size_m);
    gl_->images.render(gl_->renderer, gl_->drawables.items(false, false, -1), shot, gl_->settings,
                       rgb, depth, body_ids);
  }

 private:
  /// What lives in the context (destroyed with it current).
  struct Gl {
    Renderer renderer;
    SceneDrawables drawables;
    CameraImages images;
    RenderSettings settings;
  };
  const Simulation& sim_;
  HeadlessContext context_;
  std::unique_ptr<Gl> gl_;
  std::vector<std::string> warnings_;  ///< reused every shot
};

}  // namespace

std::unique_ptr<CameraRenderer> make_headless_camera_renderer(const Simulation& sim) {
  return std::make_unique<HeadlessCameraRenderer>(sim);
}

CameraRendererFactory headless_camera_renderer_factory() {
  return [](const Simulation& sim) { return make_headless_camera_renderer(sim); };
}

}  // namespace s2sim::render
