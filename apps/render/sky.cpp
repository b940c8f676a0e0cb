#include "sky.hpp"

#include "gl.hpp"
#include "gl_program.hpp"

namespace s2sim::render {
namespace {

// One triangle covering the viewport; each corner's world direction comes from unprojecting
// it onto the far plane, and directions are linear across the screen, so they interpolate.
constexpr const char* kSkyVertex = R"(#version 330 core
uniform mat4 u_inverse_view_projection;
uniform vec3 u_eye;
out vec3 v_direction;
void main() {
  vec2 corner = vec2(gl_VertexID == 1 ? 3.0 : -1.0, gl_VertexID == 2 ? 3.0 : -1.0);
  vec4 far_point = u_inverse_view_projection * vec4(corner, 1.0, 1.0);
  v_direction = far_point.xyz / far_point.w - u_eye;
  gl_Position = vec4(corner, 1.0, 1.0);  // at the far plane
}
)";

constexpr const char* kSkyFragment = R"(#version 330 core
in vec3 v_direction;
out vec4 frag_color;
void main() {
  float elevation = normalize(v_direction).z;
  const vec3 zenith = vec3(0.25, 0.45, 0.78);
  const vec3 horizon = vec3(0.78, 0.86, 0.95);
  const vec3 ground_haze = vec3(0.60, 0.63, 0.66);
  vec3 color = elevation >= 0.0 ? mix(horizon, zenith, pow(elevation, 0.6))
                                : mix(horizon, ground_haze, min(1.0, -elevation * 8.0));
  frag_color = vec4(color, 1.0);
}
)";

}  // namespace

Sky::~Sky() {
  if (program_) glDeleteProgram(program_);
  if (vao_) glDeleteVertexArrays(1, &vao_);
}

void Sky::init() {
  program_ = link_program(kSkyVertex, kSkyFragment);
  inverse_location_ = uniform(program_, "u_inverse_view_projection");
  eye_location_ = uniform(program_, "u_eye");
  glGenVertexArrays(1, &vao_);  // core profile: a draw needs a vertex array, even empty
}

void Sky::draw(const Mat4& view_projection, const Vec3f& eye_m) const {
  const Mat4 inv = inverse(view_projection);
  glUseProgram(program_);
  glUniformMatrix4fv(inverse_location_, 1, GL_FALSE, inv.m);
  glUniform3f(eye_location_, eye_m.x, eye_m.y, eye_m.z);
  glDepthFunc(GL_LEQUAL);  // the cleared depth is exactly the far plane
  glDepthMask(GL_FALSE);
  glDisable(GL_CULL_FACE);
  glBindVertexArray(vao_);
  glDrawArrays(GL_TRIANGLES, 0, 3);
  glDepthMask(GL_TRUE);
  glDepthFunc(GL_LESS);
}

}  // namespace s2sim::render
