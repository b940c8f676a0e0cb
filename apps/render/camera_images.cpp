#include "camera_images.hpp"

#include "gl.hpp"
#include "gl_program.hpp"

#include <s2sim/error.hpp>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <cstring>
#include <limits>
#include <string>

namespace s2sim::render {
namespace {

// Depth and ids in one flat pass. The depth is written as the eye-space distance along the
// optical axis into an R32F attachment rather than recovered from the depth buffer: the
// depth buffer holds a hyperbolic function of the distance whose precision falls with the
// square of the distance (and OpenGL 3.3 maps it to -1..1, losing half of a float's bits),
// while the eye-space z interpolated per fragment is exact for planes (it is affine in the
// position, and perspective-correct interpolation reproduces affine functions), to a float's
// 1e-7 relative. The depth buffer (32-bit float) only decides which surface is nearest.
constexpr const char* kFlatVertex = R"(#version 330 core
layout(location = 0) in vec3 a_position;
uniform mat4 u_model;
uniform mat4 u_view;
uniform mat4 u_view_projection;
out float v_depth;
void main() {
  vec4 world = u_model * vec4(a_position, 1.0);
  v_depth = -(u_view * world).z;
  gl_Position = u_view_projection * world;
}
)";

constexpr const char* kFlatFragment = R"(#version 330 core
in float v_depth;
uniform uint u_body;
layout(location = 0) out float o_depth;
layout(location = 1) out uint o_body;
void main() {
  o_depth = v_depth;
  o_body = u_body;
}
)";

unsigned renderbuffer(GLenum format, int width_px, int height_px) {
  unsigned id = 0;
  glGenRenderbuffers(1, &id);
  glBindRenderbuffer(GL_RENDERBUFFER, id);
  glRenderbufferStorage(GL_RENDERBUFFER, format, width_px, height_px);
  return id;
}

void check_complete(const char* what, int width_px, int height_px) {
  const GLenum status = glCheckFramebufferStatus(GL_FRAMEBUFFER);
  if (status == GL_FRAMEBUFFER_COMPLETE) return;
  char code[16];
  std::snprintf(code, sizeof code, "0x%04X", static_cast<unsigned>(status));
  throw Error(ErrorKind::runtime, std::string("the OpenGL driver refused the cameras' ") + what +
                                      " framebuffer of " + std::to_string(width_px) + " x " +
                                      std::to_string(height_px) + " pixels (status " + code + ")");
}

/// The kernel checks the images against the shot; so does this, which writes into them.
void check_image(const CameraShot& shot, const Image* image, PixelFormat format) {
  if (image == nullptr) return;
  if (image->width_px != shot.width_px || image->height_px != shot.height_px ||
      image->format != format || image->data == nullptr ||
      image->stride_bytes < shot.width_px * bytes_per_pixel(format))
    throw Error(ErrorKind::runtime, "a camera image is not " + std::to_string(shot.width_px) +
                                        " x " + std::to_string(shot.height_px) +
                                        " pixels of format " +
                                        std::to_string(static_cast<int>(format)) + " as its shot");
}

/// Copies `height_px` rows of `row_bytes` from `rows` (bottom first) into `image` (top first).
void copy_flipped(const void* rows, std::size_t row_bytes, int height_px, Image& image) {
  const auto* bytes = static_cast<const std::uint8_t*>(rows);
  for (int y = 0; y < height_px; ++y)
    std::memcpy(image.row(height_px - 1 - y), bytes + static_cast<std::size_t>(y) * row_bytes,
                row_bytes);
}

}  // namespace

View camera_view(const CameraShot& shot) {
  View v;
  const Pose world_to_camera = shot.pose.inverse();
  // OpenGL's eye from the camera frame: x and z flip (a half turn about y).
  const double flip[3] = {-1, 1, -1};
  for (int r = 0; r < 3; ++r) {
    for (int c = 0; c < 3; ++c)
      v.view.at(r, c) = static_cast<float>(flip[r] * world_to_camera.rotation.m[r][c]);
    const double t[3] = {world_to_camera.position.x, world_to_camera.position.y,
                         world_to_camera.position.z};
    v.view.at(r, 3) = static_cast<float>(flip[r] * t[r]);
  }
  const double aspect = static_cast<double>(shot.width_px) / shot.height_px;
  const double f = 1 / std::tan(shot.vertical_fov_rad / 2);
  const double n = shot.near_m, far = shot.far_m;
  v.projection.at(0, 0) = static_cast<float>(f / aspect);
  v.projection.at(1, 1) = static_cast<float>(f);
  v.projection.at(2, 2) = static_cast<float>((far + n) / (n - far));
  v.projection.at(2, 3) = static_cast<float>(2 * far * n / (n - far));
  v.projection.at(3, 2) = -1;
  v.projection.at(3, 3) = 0;
  v.eye_m = to_f(shot.pose.position);
  v.fov_y_rad = static_cast<float>(shot.vertical_fov_rad);
  // Shadows from the casters near the first 20 m of the line of sight.
  const Vec3 forward = shot.pose.rotation * Vec3{0, 0, 1};
  const double range_m = std::min(shot.far_m, 20.0);
  v.focus_m = to_f(shot.pose.position + forward * (range_m / 2));
  v.focus_radius_m = static_cast<float>(std::max(3.0, range_m));
  v.width_px = shot.width_px;
  v.height_px = shot.height_px;
  return v;
}

CameraImages::~CameraImages() {
  release_targets();
  if (flat_program_) glDeleteProgram(flat_program_);
}

void CameraImages::release_targets() {
  for (unsigned* fb : {&colour_framebuffer_, &sensor_framebuffer_})
    if (*fb) glDeleteFramebuffers(1, fb);
  for (unsigned* rb : {&colour_, &colour_depth_, &linear_depth_, &ids_, &sensor_depth_})
    if (*rb) glDeleteRenderbuffers(1, rb);
  colour_framebuffer_ = sensor_framebuffer_ = 0;
  colour_ = colour_depth_ = linear_depth_ = ids_ = sensor_depth_ = 0;
  width_px_ = height_px_ = 0;
}

void CameraImages::make_targets(int width_px, int height_px) {
  if (width_px == width_px_ && height_px == height_px_) return;
  release_targets();
  colour_ = renderbuffer(GL_RGBA8, width_px, height_px);
  colour_depth_ = renderbuffer(GL_DEPTH24_STENCIL8, width_px, height_px);
  glGenFramebuffers(1, &colour_framebuffer_);
  glBindFramebuffer(GL_FRAMEBUFFER, colour_framebuffer_);
  glFramebufferRenderbuffer(GL_FRAMEBUFFER, GL_COLOR_ATTACHMENT0, GL_RENDERBUFFER, colour_);
  glFramebufferRenderbuffer(GL_FRAMEBUFFER, GL_DEPTH_STENCIL_ATTACHMENT, GL_RENDERBUFFER,
                            colour_depth_);
  check_complete("colour", width_px, height_px);

  linear_depth_ = renderbuffer(GL_R32F, width_px, height_px);
  ids_ = renderbuffer(GL_R16UI, width_px, height_px);
  sensor_depth_ = renderbuffer(GL_DEPTH_COMPONENT32F, width_px, height_px);
  glGenFramebuffers(1, &sensor_framebuffer_);
  glBindFramebuffer(GL_FRAMEBUFFER, sensor_framebuffer_);
  glFramebufferRenderbuffer(GL_FRAMEBUFFER, GL_COLOR_ATTACHMENT0, GL_RENDERBUFFER, linear_depth_);
  glFramebufferRenderbuffer(GL_FRAMEBUFFER, GL_COLOR_ATTACHMENT1, GL_RENDERBUFFER, ids_);
  glFramebufferRenderbuffer(GL_FRAMEBUFFER, GL_DEPTH_ATTACHMENT, GL_RENDERBUFFER, sensor_depth_);
  const GLenum both[2] = {GL_COLOR_ATTACHMENT0, GL_COLOR_ATTACHMENT1};
  glDrawBuffers(2, both);
  check_complete("depth and body id", width_px, height_px);
  glBindFramebuffer(GL_FRAMEBUFFER, 0);
  glBindRenderbuffer(GL_RENDERBUFFER, 0);
  width_px_ = width_px;
  height_px_ = height_px;
  const auto pixels = static_cast<std::size_t>(width_px) * static_cast<std::size_t>(height_px);
  rgb_rows_.resize(pixels * 3);
  depth_rows_.resize(pixels);
  id_rows_.resize(pixels);
}

void CameraImages::render(Renderer& renderer, const std::vector<DrawItem>& items,
                          const CameraShot& shot, RenderSettings settings, Image* rgb, Image* depth,
                          Image* body_ids) {
  if (!rgb && !depth && !body_ids) return;
  check_image(shot, rgb, PixelFormat::rgb8);
  check_image(shot, depth, PixelFormat::float32);
  check_image(shot, body_ids, PixelFormat::uint16);
  if (flat_program_ == 0) {
    flat_program_ = link_program(kFlatVertex, kFlatFragment);
    model_location_ = uniform(flat_program_, "u_model");
    view_location_ = uniform(flat_program_, "u_view");
    view_projection_location_ = uniform(flat_program_, "u_view_projection");
    body_location_ = uniform(flat_program_, "u_body");
  }
  make_targets(shot.width_px, shot.height_px);
  const View view = camera_view(shot);
  // The floor reaches as far as the camera sees (the viewer's stops at 20 m).
  settings.floor_half_size_m = std::max(
      settings.floor_half_size_m,
      static_cast<float>(std::hypot(shot.pose.position.x, shot.pose.position.y) + shot.far_m));
  if (rgb) draw_colour(renderer, items, view, settings, *rgb);
  if (depth || body_ids)
    draw_depth_and_ids(renderer, items, view, settings.floor_half_size_m, depth, body_ids);
  glBindFramebuffer(GL_FRAMEBUFFER, 0);
  if (const GLenum error = glGetError(); error != GL_NO_ERROR) {
    char code[16];
    std::snprintf(code, sizeof code, "0x%04X", static_cast<unsigned>(error));
    throw Error(ErrorKind::runtime, std::string("OpenGL failed drawing a camera's images (error ") +
                                        code +
                                        (error == GL_OUT_OF_MEMORY ? ", out of memory" : "") + ")");
  }
}

void CameraImages::draw_colour(Renderer& renderer, const std::vector<DrawItem>& items,
                               const View& view, RenderSettings& settings, Image& rgb) {
  // One sample per pixel: a pixel is a surface's when its centre is inside it, as a pinhole
  // camera's model says.
  settings.msaa_samples = 0;
  View into = view;
  into.framebuffer = colour_framebuffer_;
  renderer.draw(items, into, settings);
  glBindFramebuffer(GL_READ_FRAMEBUFFER, colour_framebuffer_);
  glReadBuffer(GL_COLOR_ATTACHMENT0);
  glPixelStorei(GL_PACK_ALIGNMENT, 1);
  glReadPixels(0, 0, width_px_, height_px_, GL_RGB, GL_UNSIGNED_BYTE, rgb_rows_.data());
  copy_flipped(rgb_rows_.data(), static_cast<std::size_t>(width_px_) * 3, height_px_, rgb);
}

void CameraImages::draw_depth_and_ids(Renderer& renderer, const std::vector<DrawItem>& items,
                                      const View& view, float floor_half_size_m, Image* depth,
                                      Image* body_ids) {
  glBindFramebuffer(GL_FRAMEBUFFER, sensor_framebuffer_);
  glViewport(0, 0, width_px_, height_px_);
  glDisable(GL_SCISSOR_TEST);
  glDisable(GL_BLEND);
  glDisable(GL_STENCIL_TEST);
  glDisable(GL_CULL_FACE);  // the nearest surface, whichever way it faces
  glEnable(GL_DEPTH_TEST);
  glDepthFunc(GL_LESS);
  glDepthMask(GL_TRUE);
  // Depth 0 marks "nothing" (every surface drawn is beyond the near plane); read as +inf.
  const float no_depth[4] = {0, 0, 0, 0};
  const GLuint no_body[4] = {kNoBodyId, 0, 0, 0};
  const float far_plane = 1;
  glClearBufferfv(GL_COLOR, 0, no_depth);
  glClearBufferuiv(GL_COLOR, 1, no_body);
  glClearBufferfv(GL_DEPTH, 0, &far_plane);

  glUseProgram(flat_program_);
  const Mat4 view_projection = view.projection * view.view;
  glUniformMatrix4fv(view_location_, 1, GL_FALSE, view.view.m);
  glUniformMatrix4fv(view_projection_location_, 1, GL_FALSE, view_projection.m);
  const Mat4 floor_model = scale_matrix({floor_half_size_m, floor_half_size_m, 1});
  glUniformMatrix4fv(model_location_, 1, GL_FALSE, floor_model.m);
  glUniform1ui(body_location_, 0);
  renderer.draw_mesh(renderer.floor_mesh());
  for (const DrawItem& item : items) {
    if (!item.sensed || !(item.color[3] > 0)) continue;
    glUniformMatrix4fv(model_location_, 1, GL_FALSE, item.model.m);
    glUniform1ui(body_location_, static_cast<GLuint>(std::clamp(item.body, 0, 0xFFFE)));
    renderer.draw_mesh(item.mesh);
  }
  glBindVertexArray(0);

  glBindFramebuffer(GL_READ_FRAMEBUFFER, sensor_framebuffer_);
  glPixelStorei(GL_PACK_ALIGNMENT, 1);
  if (depth) {
    glReadBuffer(GL_COLOR_ATTACHMENT0);
    glReadPixels(0, 0, width_px_, height_px_, GL_RED, GL_FLOAT, depth_rows_.data());
    for (float& d : depth_rows_)
      if (!(d > 0)) d = std::numeric_limits<float>::infinity();
    copy_flipped(depth_rows_.data(), static_cast<std::size_t>(width_px_) * sizeof(float),
                 height_px_, *depth);
  }
  if (body_ids) {
    glReadBuffer(GL_COLOR_ATTACHMENT1);
    glReadPixels(0, 0, width_px_, height_px_, GL_RED_INTEGER, GL_UNSIGNED_SHORT, id_rows_.data());
    copy_flipped(id_rows_.data(), static_cast<std::size_t>(width_px_) * sizeof(std::uint16_t),
                 height_px_, *body_ids);
  }
}

}  // namespace s2sim::render
