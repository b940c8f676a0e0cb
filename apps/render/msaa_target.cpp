#include "msaa_target.hpp"

#include "gl.hpp"

#include <algorithm>

namespace s2sim::render {

MsaaTarget::~MsaaTarget() {
  release();
}

void MsaaTarget::release() {
  if (framebuffer_) glDeleteFramebuffers(1, &framebuffer_);
  if (color_) glDeleteRenderbuffers(1, &color_);
  if (depth_stencil_) glDeleteRenderbuffers(1, &depth_stencil_);
  framebuffer_ = color_ = depth_stencil_ = 0;
}

bool MsaaTarget::bind(int width_px, int height_px, int samples) {
  if (width_px != width_px_ || height_px != height_px_ || samples != samples_) {
    release();
    width_px_ = width_px;
    height_px_ = height_px;
    samples_ = samples;
    failed_ = false;
    GLint max_samples = 0;
    glGetIntegerv(GL_MAX_SAMPLES, &max_samples);
    const int n = std::min(samples, static_cast<int>(max_samples));
    if (n < 2) {
      failed_ = true;
      return false;
    }
    glGenRenderbuffers(1, &color_);
    glBindRenderbuffer(GL_RENDERBUFFER, color_);
    glRenderbufferStorageMultisample(GL_RENDERBUFFER, n, GL_RGBA8, width_px, height_px);
    glGenRenderbuffers(1, &depth_stencil_);
    glBindRenderbuffer(GL_RENDERBUFFER, depth_stencil_);
    glRenderbufferStorageMultisample(GL_RENDERBUFFER, n, GL_DEPTH24_STENCIL8, width_px, height_px);
    glGenFramebuffers(1, &framebuffer_);
    glBindFramebuffer(GL_FRAMEBUFFER, framebuffer_);
    glFramebufferRenderbuffer(GL_FRAMEBUFFER, GL_COLOR_ATTACHMENT0, GL_RENDERBUFFER, color_);
    glFramebufferRenderbuffer(GL_FRAMEBUFFER, GL_DEPTH_STENCIL_ATTACHMENT, GL_RENDERBUFFER,
                              depth_stencil_);
    if (glCheckFramebufferStatus(GL_FRAMEBUFFER) != GL_FRAMEBUFFER_COMPLETE) {
      glBindFramebuffer(GL_FRAMEBUFFER, 0);
      release();
      failed_ = true;
      return false;
    }
    glBindRenderbuffer(GL_RENDERBUFFER, color_);
    glGetRenderbufferParameteriv(GL_RENDERBUFFER, GL_RENDERBUFFER_SAMPLES, &max_samples);
    actual_samples_ = max_samples;
  }
  if (failed_) return false;
  glBindFramebuffer(GL_FRAMEBUFFER, framebuffer_);
  return true;
}

void MsaaTarget::resolve_into(unsigned framebuffer, int x_px, int y_px) const {
  glBindFramebuffer(GL_READ_FRAMEBUFFER, framebuffer_);
  glBindFramebuffer(GL_DRAW_FRAMEBUFFER, framebuffer);
  glBlitFramebuffer(0, 0, width_px_, height_px_, x_px, y_px, x_px + width_px_, y_px + height_px_,
                    GL_COLOR_BUFFER_BIT, GL_NEAREST);
  glBindFramebuffer(GL_FRAMEBUFFER, framebuffer);
}

}  // namespace s2sim::render
