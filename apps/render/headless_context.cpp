#include "headless_context.hpp"

#include "gl.hpp"

#include <s2sim/error.hpp>

#include <EGL/egl.h>
#include <EGL/eglext.h>

#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <string>
#include <vector>

namespace s2sim::render {
namespace {

std::string egl_error_text(EGLint code) {
  struct Name {
    EGLint code;
    const char* name;
  };
  static constexpr Name kNames[] = {
      {EGL_SUCCESS, "EGL_SUCCESS"},
      {EGL_NOT_INITIALIZED, "EGL_NOT_INITIALIZED"},
      {EGL_BAD_ACCESS, "EGL_BAD_ACCESS"},
      {EGL_BAD_ALLOC, "EGL_BAD_ALLOC"},
      {EGL_BAD_ATTRIBUTE, "EGL_BAD_ATTRIBUTE"},
      {EGL_BAD_CONFIG, "EGL_BAD_CONFIG"},
      {EGL_BAD_CONTEXT, "EGL_BAD_CONTEXT"},
      {EGL_BAD_CURRENT_SURFACE, "EGL_BAD_CURRENT_SURFACE"},
      {EGL_BAD_DISPLAY, "EGL_BAD_DISPLAY"},
      {EGL_BAD_MATCH, "EGL_BAD_MATCH"},
      {EGL_BAD_NATIVE_PIXMAP, "EGL_BAD_NATIVE_PIXMAP"},
      {EGL_BAD_NATIVE_WINDOW, "EGL_BAD_NATIVE_WINDOW"},
      {EGL_BAD_PARAMETER, "EGL_BAD_PARAMETER"},
      {EGL_BAD_SURFACE, "EGL_BAD_SURFACE"},
      {EGL_CONTEXT_LOST, "EGL_CONTEXT_LOST"},
  };
  const char* name = "an unknown EGL error";
  for (const Name& n : kNames)
    if (n.code == code) name = n.name;
  char code_text[16];
  std::snprintf(code_text, sizeof code_text, "0x%04X", static_cast<unsigned>(code));
  return std::string(name) + ", " + code_text;
}

/// "`call` failed (EGL_..., 0x....)" with the thread's last EGL error.
std::string failed(const char* call) {
  return std::string(call) + " failed (" + egl_error_text(eglGetError()) + ")";
}

bool has_extension(const char* extensions, const char* name) {
  if (extensions == nullptr) return false;
  const std::size_t n = std::strlen(name);
  for (const char* p = extensions; (p = std::strstr(p, name)) != nullptr; p += n)
    if ((p == extensions || p[-1] == ' ') && (p[n] == ' ' || p[n] == '\0')) return true;
  return false;
}

/// An initialised display of one platform, or EGL_NO_DISPLAY with `why` set.
EGLDisplay open_display(const std::string& platform, std::string& why) {
  const char* client = eglQueryString(EGL_NO_DISPLAY, EGL_EXTENSIONS);
  const auto get_platform_display = reinterpret_cast<PFNEGLGETPLATFORMDISPLAYEXTPROC>(
      eglGetProcAddress("eglGetPlatformDisplayEXT"));
  EGLDisplay display = EGL_NO_DISPLAY;
  if (platform == "surfaceless") {
    if (!has_extension(client, "EGL_MESA_platform_surfaceless") || !get_platform_display) {
      why = "EGL has no EGL_MESA_platform_surfaceless";
      return EGL_NO_DISPLAY;
    }
    display = get_platform_display(EGL_PLATFORM_SURFACELESS_MESA, EGL_DEFAULT_DISPLAY, nullptr);
    if (display == EGL_NO_DISPLAY) why = failed("eglGetPlatformDisplayEXT(surfaceless)");
  } else if (platform == "device") {
    const auto query_devices =
        reinterpret_cast<PFNEGLQUERYDEVICESEXTPROC>(eglGetProcAddress("eglQueryDevicesEXT"));
    if (!has_extension(client, "EGL_EXT_platform_device") || !query_devices ||
        !get_platform_display) {
      why = "EGL has no EGL_EXT_platform_device";
      return EGL_NO_DISPLAY;
    }
    EGLDeviceEXT device = nullptr;
    EGLint count = 0;
    if (!query_devices(1, &device, &count)) {
      why = failed("eglQueryDevicesEXT");
      return EGL_NO_DISPLAY;
    }
    if (count < 1) {
      why = "eglQueryDevicesEXT found no device";
      return EGL_NO_DISPLAY;
    }
    display = get_platform_display(EGL_PLATFORM_DEVICE_EXT, device, nullptr);
    if (display == EGL_NO_DISPLAY) why = failed("eglGetPlatformDisplayEXT(device)");
  } else {
    display = eglGetDisplay(EGL_DEFAULT_DISPLAY);
    if (display == EGL_NO_DISPLAY) why = failed("eglGetDisplay(EGL_DEFAULT_DISPLAY)");
  }
  if (display == EGL_NO_DISPLAY) return EGL_NO_DISPLAY;
  // Not terminated when the context goes: the display is the same object for every context
  // of the process (another simulation's renderer may still draw with it).
  EGLint major = 0, minor = 0;
  if (!eglInitialize(display, &major, &minor)) {
    why = failed("eglInitialize");
    return EGL_NO_DISPLAY;
  }
  return display;
}

/// A desktop OpenGL 3.3 core context on `display`, or EGL_NO_CONTEXT with `why` set.
EGLContext create_context(EGLDisplay display, std::string& why) {
  const char* extensions = eglQueryString(display, EGL_EXTENSIONS);
  if (!has_extension(extensions, "EGL_KHR_surfaceless_context")) {
    why = "the display has no EGL_KHR_surfaceless_context (a context without a surface)";
    return EGL_NO_CONTEXT;
  }
  if (!eglBindAPI(EGL_OPENGL_API)) {
    why = failed("eglBindAPI(EGL_OPENGL_API)");
    return EGL_NO_CONTEXT;
  }
  // Framebuffer objects only: the config's surfaces do not matter, so any config that
  // renders desktop OpenGL (or none, where the display allows it).
  EGLConfig config = EGL_NO_CONFIG_KHR;
  if (!has_extension(extensions, "EGL_KHR_no_config_context")) {
    const EGLint wanted[] = {EGL_SURFACE_TYPE, 0, EGL_RENDERABLE_TYPE, EGL_OPENGL_BIT, EGL_NONE};
    EGLint count = 0;
    if (!eglChooseConfig(display, wanted, &config, 1, &count)) {
      why = failed("eglChooseConfig");
      return EGL_NO_CONTEXT;
    }
    if (count < 1) {
      why = "eglChooseConfig found no config for desktop OpenGL";
      return EGL_NO_CONTEXT;
    }
  }
  const EGLint attributes[] = {EGL_CONTEXT_MAJOR_VERSION,
                               3,
                               EGL_CONTEXT_MINOR_VERSION,
                               3,
                               EGL_CONTEXT_OPENGL_PROFILE_MASK,
                               EGL_CONTEXT_OPENGL_CORE_PROFILE_BIT,
                               EGL_NONE};
  EGLContext context = eglCreateContext(display, config, EGL_NO_CONTEXT, attributes);
  if (context == EGL_NO_CONTEXT) why = failed("eglCreateContext(OpenGL 3.3 core)");
  return context;
}

}  // namespace

HeadlessContext::HeadlessContext() {
  // S2SIM_EGL_PLATFORM=surfaceless, device or default tries that platform alone.
  std::vector<std::string> platforms = {"surfaceless", "device", "default"};
  if (const char* chosen = std::getenv("S2SIM_EGL_PLATFORM"); chosen && *chosen) {
    const std::string name = chosen;
    if (name != "surfaceless" && name != "device" && name != "default")
      throw Error(ErrorKind::runtime, "S2SIM_EGL_PLATFORM=" + name +
                                          ": the EGL platform must be surfaceless, device or "
                                          "default");
    platforms = {name};
  }
  std::string reasons;
  for (const std::string& platform : platforms) {
    std::string why;
    const EGLDisplay display = open_display(platform, why);
    const EGLContext context =
        display != EGL_NO_DISPLAY ? create_context(display, why) : EGL_NO_CONTEXT;
    if (context != EGL_NO_CONTEXT) {
      display_ = display;
      context_ = context;
      description_ = "EGL " + platform;
      break;
    }
    reasons += (reasons.empty() ? "" : "; ") + platform + ": " + why;
  }
  if (context_ == nullptr)
    throw Error(ErrorKind::runtime,
                "no OpenGL context to draw the cameras: EGL could not give an OpenGL 3.3 core "
                "context on any platform (" +
                    reasons +
                    "); Mesa's EGL draws without a display (Debian: libegl1, libegl-mesa0, "
                    "libgl1-mesa-dri)");
  make_current();
  const auto* renderer = reinterpret_cast<const char*>(glGetString(GL_RENDERER));
  const auto* version = reinterpret_cast<const char*>(glGetString(GL_VERSION));
  description_ +=
      std::string(", ") + (renderer ? renderer : "?") + ", OpenGL " + (version ? version : "?");
  release();
}

HeadlessContext::~HeadlessContext() {
  if (context_ == nullptr) return;
  eglMakeCurrent(display_, EGL_NO_SURFACE, EGL_NO_SURFACE, EGL_NO_CONTEXT);
  eglDestroyContext(display_, context_);
}

void HeadlessContext::make_current() {
  if (!eglMakeCurrent(display_, EGL_NO_SURFACE, EGL_NO_SURFACE, context_))
    throw Error(ErrorKind::runtime, "the cameras' OpenGL context: " + failed("eglMakeCurrent") +
                                        " (" + description_ + ")");
}

void HeadlessContext::release() {
  eglMakeCurrent(display_, EGL_NO_SURFACE, EGL_NO_SURFACE, EGL_NO_CONTEXT);
}

}  // namespace s2sim::render
