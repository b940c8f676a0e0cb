#include "shadow_map.hpp"

#include "gl.hpp"
#include "gl_program.hpp"

#include <algorithm>
#include <cmath>

namespace s2sim::render {
namespace {

constexpr const char* kDepthVertex = R"(#version 330 core
layout(location = 0) in vec3 a_position;
uniform mat4 u_model;
uniform mat4 u_light_view_projection;
void main() { gl_Position = u_light_view_projection * u_model * vec4(a_position, 1.0); }
)";

constexpr const char* kDepthFragment = R"(#version 330 core
void main() {}
)";

}  // namespace

ShadowMap::~ShadowMap() {
  if (framebuffer_) glDeleteFramebuffers(1, &framebuffer_);
  if (depth_texture_) glDeleteTextures(1, &depth_texture_);
  if (program_) glDeleteProgram(program_);
}

bool ShadowMap::init(int size_px) {
  size_px_ = size_px;
  glGenTextures(1, &depth_texture_);
  glBindTexture(GL_TEXTURE_2D, depth_texture_);
  glTexImage2D(GL_TEXTURE_2D, 0, GL_DEPTH_COMPONENT24, size_px, size_px, 0, GL_DEPTH_COMPONENT,
               GL_UNSIGNED_INT, nullptr);
  // Nearest texel until set_smooth(true): see set_smooth.
  glTexParameteri(GL_TEXTURE_2D, GL_TEXTURE_MIN_FILTER, GL_NEAREST);
  glTexParameteri(GL_TEXTURE_2D, GL_TEXTURE_MAG_FILTER, GL_NEAREST);
  glTexParameteri(GL_TEXTURE_2D, GL_TEXTURE_COMPARE_MODE, GL_COMPARE_REF_TO_TEXTURE);
  glTexParameteri(GL_TEXTURE_2D, GL_TEXTURE_COMPARE_FUNC, GL_LEQUAL);
  // Outside the map nothing casts: the border is the far plane, i.e. lit.
  glTexParameteri(GL_TEXTURE_2D, GL_TEXTURE_WRAP_S, GL_CLAMP_TO_BORDER);
  glTexParameteri(GL_TEXTURE_2D, GL_TEXTURE_WRAP_T, GL_CLAMP_TO_BORDER);
  const float far_border[4] = {1, 1, 1, 1};
  glTexParameterfv(GL_TEXTURE_2D, GL_TEXTURE_BORDER_COLOR, far_border);
  glBindTexture(GL_TEXTURE_2D, 0);

  glGenFramebuffers(1, &framebuffer_);
  glBindFramebuffer(GL_FRAMEBUFFER, framebuffer_);
  glFramebufferTexture2D(GL_FRAMEBUFFER, GL_DEPTH_ATTACHMENT, GL_TEXTURE_2D, depth_texture_, 0);
  glDrawBuffer(GL_NONE);
  glReadBuffer(GL_NONE);
  const bool complete = glCheckFramebufferStatus(GL_FRAMEBUFFER) == GL_FRAMEBUFFER_COMPLETE;
  glBindFramebuffer(GL_FRAMEBUFFER, 0);
  if (!complete) {
    glDeleteFramebuffers(1, &framebuffer_);
    glDeleteTextures(1, &depth_texture_);
    framebuffer_ = depth_texture_ = 0;
    return false;
  }
  program_ = link_program(kDepthVertex, kDepthFragment);
  model_location_ = uniform(program_, "u_model");
  light_vp_location_ = uniform(program_, "u_light_view_projection");
  return true;
}

bool ShadowMap::fit(const CasterBound* casters, int count, const Vec3f& light_direction,
                    float floor_z_m) {
  if (count == 0) return false;
  // The light's frame: z towards the light, x and y across its beam.
  const Vec3f l = light_direction;
  const Vec3f across =
      normalized(cross(std::abs(l.z) < 0.99f ? Vec3f{0, 0, 1} : Vec3f{1, 0, 0}, l));
  const Vec3f up = cross(l, across);
  float x0 = 1e30f, x1 = -1e30f, y0 = 1e30f, y1 = -1e30f, z_near = -1e30f, z_far = 1e30f;
  for (int i = 0; i < count; ++i) {
    const Vec3f& c = casters[i].centre_m;
    const float r = casters[i].radius_m;
    const float x = dot(c, across), y = dot(c, up), z = dot(c, l);
    x0 = std::min(x0, x - r), x1 = std::max(x1, x + r);
    y0 = std::min(y0, y - r), y1 = std::max(y1, y + r);
    z_near = std::max(z_near, z + r);
    // Its shadow travels (height above the floor) / l.z along -l before it meets the floor.
    z_far = std::min(z_far, z - r - std::max(0.0f, c.z + r - floor_z_m) / std::max(0.05f, l.z));
  }
  // Square texels; a margin so PCF taps at the edge stay inside.
  const float side = std::max(x1 - x0, y1 - y0) * 1.02f + 0.02f;
  const float cx = (x0 + x1) / 2, cy = (y0 + y1) / 2;
  texel_m_ = side / static_cast<float>(size_px_);
  Mat4 view;  // rows: across, up, l; the eye looks along -l as OpenGL's does along -z
  view.at(0, 0) = across.x, view.at(0, 1) = across.y, view.at(0, 2) = across.z;
  view.at(1, 0) = up.x, view.at(1, 1) = up.y, view.at(1, 2) = up.z;
  view.at(2, 0) = l.x, view.at(2, 1) = l.y, view.at(2, 2) = l.z;
  const float depth_margin_m = 0.01f;
  // In the view, z = dot(p, l); orthographic() takes distances along -z: near = -z_near.
  light_view_projection_ = orthographic(cx - side / 2, cx + side / 2, cy - side / 2, cy + side / 2,
                                        -z_near - depth_margin_m, -z_far + depth_margin_m) *
                           view;
  Mat4 bias;  // clip space -1..1 to texture space 0..1
  bias.at(0, 0) = bias.at(1, 1) = bias.at(2, 2) = 0.5f;
  bias.at(0, 3) = bias.at(1, 3) = bias.at(2, 3) = 0.5f;
  world_to_texture_ = bias * light_view_projection_;
  return true;
}

void ShadowMap::begin_pass() const {
  glBindFramebuffer(GL_FRAMEBUFFER, framebuffer_);
  glViewport(0, 0, size_px_, size_px_);
  // Depth is written only with the depth test on: a fresh context has it off, and the first
  // map drawn there stayed empty (no shadow on the first frame).
  glEnable(GL_DEPTH_TEST);
  glDepthFunc(GL_LESS);
  glDepthMask(GL_TRUE);
  glClear(GL_DEPTH_BUFFER_BIT);
  glUseProgram(program_);
  glUniformMatrix4fv(light_vp_location_, 1, GL_FALSE, light_view_projection_.m);
  // Depth pushed away from the light by the surface's slope: no self-shadowing stripes.
  glEnable(GL_POLYGON_OFFSET_FILL);
  glPolygonOffset(2.0f, 4.0f);
  glDisable(GL_CULL_FACE);
}

void ShadowMap::set_smooth(bool smooth) {
  if (smooth == smooth_) return;
  smooth_ = smooth;
  const GLint filter = smooth ? GL_LINEAR : GL_NEAREST;
  glBindTexture(GL_TEXTURE_2D, depth_texture_);
  glTexParameteri(GL_TEXTURE_2D, GL_TEXTURE_MIN_FILTER, filter);
  glTexParameteri(GL_TEXTURE_2D, GL_TEXTURE_MAG_FILTER, filter);
  glBindTexture(GL_TEXTURE_2D, 0);
}

void ShadowMap::set_model(const Mat4& model) const {
  glUniformMatrix4fv(model_location_, 1, GL_FALSE, model.m);
}

void ShadowMap::end_pass() const {
  glDisable(GL_POLYGON_OFFSET_FILL);
  glBindFramebuffer(GL_FRAMEBUFFER, 0);
}

}  // namespace s2sim::render
