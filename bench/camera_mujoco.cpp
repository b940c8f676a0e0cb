// MuJoCo 2.2's offscreen renderer in the camera benchmark (camera_bench.cpp): an EGL context
// made here (surfaceless Mesa, as S2Sim's renderer opens it; MuJoCo's fixed-function
// rendering needs a compatibility profile), mjr_makeContext on it, mjr_render into the
// offscreen buffer and mjr_readPixels back, the depth buffer linearised into metres as S2Sim's
// depth images are.
#include "camera_bench.hpp"

#include <EGL/egl.h>
#include <EGL/eglext.h>
#include <mujoco/mujoco.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <stdexcept>
#include <string>
#include <vector>

namespace camera_bench {
namespace {

std::string egl_failed(const char* call) {
  char code[16];
  std::snprintf(code, sizeof code, "0x%04X", static_cast<unsigned>(eglGetError()));
  return std::string(call) + " failed (EGL error " + code + ")";
}

/// An EGL display and a desktop-OpenGL compatibility context, current on this thread, with no
/// surface (MuJoCo draws into its own framebuffer object).
class EglContext {
 public:
  EglContext() {
    auto get_platform_display = reinterpret_cast<PFNEGLGETPLATFORMDISPLAYEXTPROC>(
        eglGetProcAddress("eglGetPlatformDisplayEXT"));
    if (get_platform_display)
      display_ = get_platform_display(EGL_PLATFORM_SURFACELESS_MESA, EGL_DEFAULT_DISPLAY, nullptr);
    if (display_ == EGL_NO_DISPLAY) display_ = eglGetDisplay(EGL_DEFAULT_DISPLAY);
    if (display_ == EGL_NO_DISPLAY) throw std::runtime_error(egl_failed("eglGetDisplay"));
    EGLint major = 0, minor = 0;
    if (!eglInitialize(display_, &major, &minor))
      throw std::runtime_error(egl_failed("eglInitialize"));
    const EGLint config_attributes[] = {EGL_SURFACE_TYPE,
                                        EGL_PBUFFER_BIT,
                                        EGL_RENDERABLE_TYPE,
                                        EGL_OPENGL_BIT,
                                        EGL_RED_SIZE,
                                        8,
                                        EGL_GREEN_SIZE,
                                        8,
                                        EGL_BLUE_SIZE,
                                        8,
                                        EGL_DEPTH_SIZE,
                                        24,
                                        EGL_NONE};
    EGLConfig config = nullptr;
    EGLint count = 0;
    if (!eglChooseConfig(display_, config_attributes, &config, 1, &count) || count < 1)
      throw std::runtime_error(egl_failed("eglChooseConfig"));
    if (!eglBindAPI(EGL_OPENGL_API)) throw std::runtime_error(egl_failed("eglBindAPI"));
    const EGLint context_attributes[] = {EGL_CONTEXT_OPENGL_PROFILE_MASK,
                                         EGL_CONTEXT_OPENGL_COMPATIBILITY_PROFILE_BIT, EGL_NONE};
    context_ = eglCreateContext(display_, config, EGL_NO_CONTEXT, context_attributes);
    if (context_ == EGL_NO_CONTEXT) throw std::runtime_error(egl_failed("eglCreateContext"));
    if (!eglMakeCurrent(display_, EGL_NO_SURFACE, EGL_NO_SURFACE, context_))
      throw std::runtime_error(egl_failed("eglMakeCurrent (surfaceless)"));
  }
  ~EglContext() {
    eglMakeCurrent(display_, EGL_NO_SURFACE, EGL_NO_SURFACE, EGL_NO_CONTEXT);
    if (context_ != EGL_NO_CONTEXT) eglDestroyContext(display_, context_);
    eglTerminate(display_);
  }
  EglContext(const EglContext&) = delete;
  EglContext& operator=(const EglContext&) = delete;

 private:
  EGLDisplay display_ = EGL_NO_DISPLAY;
  EGLContext context_ = EGL_NO_CONTEXT;
};

}  // namespace

std::vector<Result> mujoco_fps(const std::string& mjcf, const View& view,
                               const std::vector<Size>& sizes, double seconds, int repeats,
                               double settle_s, const std::string& images_path) {
  char error[1000] = "";
  mjModel* m = mj_loadXML(mjcf.c_str(), nullptr, error, sizeof error);
  if (m == nullptr) throw std::runtime_error(mjcf + ": " + error);
  mjData* d = mj_makeData(m);
  const auto steps = static_cast<long>(std::lround(settle_s / m->opt.timestep));
  for (long i = 0; i < steps; ++i)
    mj_step(m, d);
  mj_forward(m, d);

  int largest_w = 1, largest_h = 1;
  for (const Size& s : sizes) {
    largest_w = std::max(largest_w, s.width_px);
    largest_h = std::max(largest_h, s.height_px);
  }
  m->vis.global.offwidth = largest_w;
  m->vis.global.offheight = largest_h;
  m->vis.global.fovy = static_cast<float>(view.vertical_fov_deg);
  m->vis.quality.offsamples = 0;  // S2Sim's camera images are not multisampled either
  m->vis.map.znear = static_cast<float>(view.near_m / m->stat.extent);
  m->vis.map.zfar = static_cast<float>(view.far_m / m->stat.extent);

  std::vector<Result> results;
  {
    EglContext egl;
    mjvScene scene;
    mjrContext context;
    mjvOption option;
    mjvCamera camera;
    mjv_defaultScene(&scene);
    mjr_defaultContext(&context);
    mjv_defaultOption(&option);
    mjv_defaultCamera(&camera);
    mjv_makeScene(m, &scene, 2000);
    mjr_makeContext(m, &context, mjFONTSCALE_100);
    mjr_setBuffer(mjFB_OFFSCREEN, &context);
    if (context.currentBuffer != mjFB_OFFSCREEN)
      throw std::runtime_error("MuJoCo: the offscreen framebuffer is not available");
    // The free camera at the view's eye, looking at its target.
    const double dx = view.target[0] - view.eye[0], dy = view.target[1] - view.eye[1],
                 dz = view.target[2] - view.eye[2];
    const double distance = std::sqrt(dx * dx + dy * dy + dz * dz);
    camera.type = mjCAMERA_FREE;
    for (int k = 0; k < 3; ++k)
      camera.lookat[k] = view.target[k];
    camera.distance = distance;
    camera.azimuth = std::atan2(dy, dx) * 180 / 3.14159265358979323846;
    camera.elevation = std::asin(dz / distance) * 180 / 3.14159265358979323846;

    const double extent = m->stat.extent, znear = m->vis.map.znear * extent,
                 zfar = m->vis.map.zfar * extent;
    for (const Size& size : sizes)
      for (const bool depth_only : {false, true}) {
        const mjrRect viewport{0, 0, size.width_px, size.height_px};
        std::vector<unsigned char> rgb(3 * static_cast<std::size_t>(size.width_px) *
                                       static_cast<std::size_t>(size.height_px));
        std::vector<float> depth(static_cast<std::size_t>(size.width_px) *
                                 static_cast<std::size_t>(size.height_px));
        auto frame = [&] {
          mjv_updateScene(m, d, &option, nullptr, &camera, mjCAT_ALL, &scene);
          mjr_render(viewport, &scene, &context);
          if (depth_only) {
            mjr_readPixels(nullptr, depth.data(), viewport, &context);
            for (float& z : depth)  // window depth to metres along the optical axis
              z = static_cast<float>(znear * zfar / (zfar - z * (zfar - znear)));
          } else {
            mjr_readPixels(rgb.data(), nullptr, viewport, &context);
          }
        };
        results.push_back(time_frames(size, depth_only, seconds, repeats, frame));
        if (!images_path.empty() && !depth_only)
          write_ppm(images_path + "-" + std::to_string(size.width_px) + ".ppm", rgb.data(), size,
                    true);
      }
    mjr_freeContext(&context);
    mjv_freeScene(&scene);
  }
  mj_deleteData(d);
  mj_deleteModel(m);
  return results;
}

}  // namespace camera_bench
