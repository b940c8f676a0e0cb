#pragma once
/// \file
/// An OpenGL 3.3 core context without a window or a display server: EGL on Mesa's surfaceless
/// platform (a GPU's driver where there is one, llvmpipe otherwise), drawing only into
/// framebuffer objects. Made current per use, on whichever thread uses it, and released after,
/// so that the next use may come from another thread (never two at once).

#include <string>

namespace s2sim::render {

class HeadlessContext {
 public:
  /// Opens an EGL display (the surfaceless platform, else the first EGL device, else the
  /// default display) and creates the context. Throws s2sim::Error (runtime) naming the EGL
  /// call that failed and its error code.
  HeadlessContext();
  ~HeadlessContext();
  HeadlessContext(const HeadlessContext&) = delete;
  HeadlessContext& operator=(const HeadlessContext&) = delete;

  /// Makes the context current on the calling thread; throws s2sim::Error (runtime) when EGL
  /// refuses (it is current on another thread, say).
  void make_current();
  /// Leaves the calling thread without a current context.
  void release();

  /// Which EGL platform was opened ("surfaceless", "device" or "default") and what draws
  /// (GL_RENDERER, GL_VERSION), for messages.
  const std::string& description() const { return description_; }

  /// Current for as long as it lives.
  class Current {
   public:
    explicit Current(HeadlessContext& context) : context_(context) { context_.make_current(); }
    ~Current() { context_.release(); }
    Current(const Current&) = delete;
    Current& operator=(const Current&) = delete;

   private:
    HeadlessContext& context_;
  };

 private:
  void* display_ = nullptr;  ///< EGLDisplay
  void* context_ = nullptr;  ///< EGLContext
  std::string description_;
};

}  // namespace s2sim::render
