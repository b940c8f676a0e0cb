#include "renderer.hpp"

#include "gl.hpp"

#include <stb/stb_image.h>

#include <algorithm>
#include <cmath>
#include <stdexcept>

namespace s2sim::viewer {
namespace {

constexpr const char* kLitVertex = R"(#version 330 core
layout(location = 0) in vec3 a_position;
layout(location = 1) in vec3 a_normal;
layout(location = 2) in vec2 a_uv;
uniform mat4 u_model;
uniform mat3 u_normal_matrix;
uniform mat4 u_view_projection;
out vec3 v_world;
out vec3 v_normal;
out vec2 v_uv;
void main() {
  vec4 world = u_model * vec4(a_position, 1.0);
  v_world = world.xyz;
  v_normal = u_normal_matrix * a_normal;
  v_uv = a_uv;
  gl_Position = u_view_projection * world;
}
)";

constexpr const char* kLitFragment = R"(#version 330 core
in vec3 v_world;
in vec3 v_normal;
in vec2 v_uv;
uniform vec4 u_color;
uniform sampler2D u_texture;
uniform bool u_use_texture;
uniform float u_texture_scale;
uniform bool u_lit;
uniform bool u_highlight;
uniform vec3 u_light_direction;
uniform vec3 u_eye;
out vec4 frag_color;

void main() {
  vec4 base = u_color;
  if (u_use_texture) base *= texture(u_texture, v_uv * u_texture_scale);
  if (!u_lit) {
    frag_color = base;
    return;
  }
  vec3 n = normalize(v_normal);
  if (!gl_FrontFacing) n = -n;
  vec3 view = normalize(u_eye - v_world);
  float diffuse = max(dot(n, u_light_direction), 0.0);
  float specular = pow(max(dot(n, normalize(u_light_direction + view)), 0.0), 32.0) * 0.2;
  vec3 color = base.rgb * (0.35 + 0.65 * diffuse) + vec3(specular);
  if (u_highlight) color = mix(color, vec3(1.0, 0.85, 0.2), 0.35);
  frag_color = vec4(color, base.a);
}
)";

// The floor covers most of the screen, so it has its own minimal shader: one varying, the
// grid, and the constant lighting of a horizontal plane. On llvmpipe (no GPU) this is what
// keeps 1280x720 above 60 frames per second.
constexpr const char* kFloorVertex = R"(#version 330 core
layout(location = 0) in vec3 a_position;
uniform mat4 u_model;
uniform mat4 u_view_projection;
out vec2 v_xy;
void main() {
  vec4 world = u_model * vec4(a_position, 1.0);
  v_xy = world.xy;
  gl_Position = u_view_projection * world;
}
)";

constexpr const char* kFloorFragment = R"(#version 330 core
in vec2 v_xy;
uniform vec3 u_color;
uniform bool u_grid;
out vec4 frag_color;
void main() {
  vec3 color = u_color;
  if (u_grid) {
    // Lines every metre (strong) and every 10 cm (faint), anti-aliased with fwidth.
    vec2 w = fwidth(v_xy);
    vec2 d1 = abs(fract(v_xy - 0.5) - 0.5) / w;
    vec2 d01 = abs(fract(v_xy * 10.0 - 0.5) - 0.5) / (w * 10.0);
    float major = 1.0 - min(min(d1.x, d1.y), 1.0);
    float minor = (1.0 - min(min(d01.x, d01.y), 1.0)) * 0.35;
    color = mix(color, vec3(0.35, 0.37, 0.40), max(major * 0.8, minor));
  }
  frag_color = vec4(color, 1.0);
}
)";

unsigned compile(GLenum type, const char* source) {
  const unsigned shader = glCreateShader(type);
  glShaderSource(shader, 1, &source, nullptr);
  glCompileShader(shader);
  GLint ok = 0;
  glGetShaderiv(shader, GL_COMPILE_STATUS, &ok);
  if (!ok) {
    char log[2048];
    glGetShaderInfoLog(shader, sizeof log, nullptr, log);
    throw std::runtime_error(std::string("shader compilation failed: ") + log);
  }
  return shader;
}

unsigned link(const char* vertex, const char* fragment) {
  const unsigned program = glCreateProgram();
  const unsigned vs = compile(GL_VERTEX_SHADER, vertex);
  const unsigned fs = compile(GL_FRAGMENT_SHADER, fragment);
  glAttachShader(program, vs);
  glAttachShader(program, fs);
  glLinkProgram(program);
  glDeleteShader(vs);
  glDeleteShader(fs);
  GLint ok = 0;
  glGetProgramiv(program, GL_LINK_STATUS, &ok);
  if (!ok) {
    char log[2048];
    glGetProgramInfoLog(program, sizeof log, nullptr, log);
    throw std::runtime_error(std::string("shader link failed: ") + log);
  }
  return program;
}

int location(unsigned program, const char* name) {
  return glGetUniformLocation(program, name);
}

/// The inverse transpose of the model's 3x3 part: normals stay normal under non-uniform scale.
void normal_matrix(const Mat4& model, float out[9]) {
  const Mat4 inv = inverse(model);
  for (int r = 0; r < 3; ++r)
    for (int c = 0; c < 3; ++c)
      out[c * 3 + r] = inv.at(c, r);
}

}  // namespace

Renderer::~Renderer() {
  for (const auto& m : meshes_) {
    glDeleteVertexArrays(1, &m.vao);
    glDeleteBuffers(1, &m.vbo);
    glDeleteBuffers(1, &m.ebo);
  }
  for (const auto& [path, t] : textures_)
    if (t != 0) glDeleteTextures(1, &t);
  if (lit_program_) glDeleteProgram(lit_program_);
  if (floor_program_) glDeleteProgram(floor_program_);
}

void Renderer::init() {
  lit_program_ = link(kLitVertex, kLitFragment);
  floor_program_ = link(kFloorVertex, kFloorFragment);
  MeshData floor;
  floor.vertices = {{{-1, -1, 0}, {0, 0, 1}, {0, 0}},
                    {{1, -1, 0}, {0, 0, 1}, {1, 0}},
                    {{1, 1, 0}, {0, 0, 1}, {1, 1}},
                    {{-1, 1, 0}, {0, 0, 1}, {0, 1}}};
  floor.indices = {0, 1, 2, 0, 2, 3};
  floor_mesh_ = upload(floor);
}

int Renderer::upload(const MeshData& mesh) {
  GpuMesh g;
  glGenVertexArrays(1, &g.vao);
  glGenBuffers(1, &g.vbo);
  glGenBuffers(1, &g.ebo);
  glBindVertexArray(g.vao);
  glBindBuffer(GL_ARRAY_BUFFER, g.vbo);
  glBufferData(GL_ARRAY_BUFFER, static_cast<GLsizeiptr>(mesh.vertices.size() * sizeof(Vertex)),
               mesh.vertices.data(), GL_STATIC_DRAW);
  glBindBuffer(GL_ELEMENT_ARRAY_BUFFER, g.ebo);
  glBufferData(GL_ELEMENT_ARRAY_BUFFER,
               static_cast<GLsizeiptr>(mesh.indices.size() * sizeof(unsigned)), mesh.indices.data(),
               GL_STATIC_DRAW);
  glEnableVertexAttribArray(0);
  glVertexAttribPointer(0, 3, GL_FLOAT, GL_FALSE, sizeof(Vertex),
                        reinterpret_cast<void*>(offsetof(Vertex, position)));
  glEnableVertexAttribArray(1);
  glVertexAttribPointer(1, 3, GL_FLOAT, GL_FALSE, sizeof(Vertex),
                        reinterpret_cast<void*>(offsetof(Vertex, normal)));
  glEnableVertexAttribArray(2);
  glVertexAttribPointer(2, 2, GL_FLOAT, GL_FALSE, sizeof(Vertex),
                        reinterpret_cast<void*>(offsetof(Vertex, uv)));
  glBindVertexArray(0);
  g.index_count = static_cast<int>(mesh.indices.size());
  meshes_.push_back(g);
  return static_cast<int>(meshes_.size()) - 1;
}

unsigned Renderer::texture(const std::filesystem::path& file, std::string& error) {
  if (const auto it = textures_.find(file); it != textures_.end()) return it->second;
  int w = 0, h = 0, channels = 0;
  stbi_set_flip_vertically_on_load(1);
  unsigned char* pixels = stbi_load(file.string().c_str(), &w, &h, &channels, 4);
  unsigned t = 0;
  if (pixels == nullptr) {
    error = file.string() + ": cannot read the texture image (" + stbi_failure_reason() + ")";
  } else {
    glGenTextures(1, &t);
    glBindTexture(GL_TEXTURE_2D, t);
    glTexImage2D(GL_TEXTURE_2D, 0, GL_RGBA8, w, h, 0, GL_RGBA, GL_UNSIGNED_BYTE, pixels);
    glGenerateMipmap(GL_TEXTURE_2D);
    glTexParameteri(GL_TEXTURE_2D, GL_TEXTURE_MIN_FILTER, GL_LINEAR_MIPMAP_LINEAR);
    glTexParameteri(GL_TEXTURE_2D, GL_TEXTURE_MAG_FILTER, GL_LINEAR);
    glTexParameteri(GL_TEXTURE_2D, GL_TEXTURE_WRAP_S, GL_REPEAT);
    glTexParameteri(GL_TEXTURE_2D, GL_TEXTURE_WRAP_T, GL_REPEAT);
    stbi_image_free(pixels);
  }
  textures_[file] = t;
  return t;
}

void Renderer::draw_mesh(const GpuMesh& mesh) const {
  glBindVertexArray(mesh.vao);
  glDrawElements(GL_TRIANGLES, mesh.index_count, GL_UNSIGNED_INT, nullptr);
}

Mat4 Renderer::floor_shadow_projection() const {
  // Flattens a point along the light direction L onto the plane z = h:
  // p' = p - L (p.z - h) / L.z. Drawn darkened, that is the point's shadow on the floor.
  const float h = 0.002f;  // above the floor and track polygons, so it wins the depth test
  const Vec3f l = light_direction_;
  Mat4 m;
  m.at(0, 2) = -l.x / l.z;
  m.at(0, 3) = l.x / l.z * h;
  m.at(1, 2) = -l.y / l.z;
  m.at(1, 3) = l.y / l.z * h;
  m.at(2, 2) = 0;
  m.at(2, 3) = h;
  return m;
}

void Renderer::draw(const std::vector<DrawItem>& items, const Camera& camera, const Rect& view,
                    int framebuffer_height_px, const RenderSettings& settings) {
  const int width_px = std::max(1, static_cast<int>(std::lround(view.width)));
  const int height_px = std::max(1, static_cast<int>(std::lround(view.height)));
  glEnable(GL_DEPTH_TEST);
  glDisable(GL_BLEND);
  glEnable(GL_CULL_FACE);
  glClearColor(settings.clear_color[0], settings.clear_color[1], settings.clear_color[2], 1);
  glClearStencil(0);
  glClear(GL_COLOR_BUFFER_BIT | GL_DEPTH_BUFFER_BIT | GL_STENCIL_BUFFER_BIT);
  // OpenGL counts rows from the bottom.
  glViewport(static_cast<int>(std::lround(view.x)),
             framebuffer_height_px - static_cast<int>(std::lround(view.y)) - height_px, width_px,
             height_px);
  const Mat4 view_projection =
      camera.projection(static_cast<float>(width_px) / height_px) * camera.view();
  const Vec3f eye = camera.eye_m();

  // The floor: a plane at z = 0, lit as a horizontal surface.
  glDisable(GL_CULL_FACE);
  glUseProgram(floor_program_);
  const Mat4 floor_model =
      scale_matrix({settings.floor_half_size_m, settings.floor_half_size_m, 1});
  glUniformMatrix4fv(location(floor_program_, "u_model"), 1, GL_FALSE, floor_model.m);
  glUniformMatrix4fv(location(floor_program_, "u_view_projection"), 1, GL_FALSE, view_projection.m);
  const float floor_light = 0.35f + 0.65f * light_direction_.z;
  glUniform3f(location(floor_program_, "u_color"), 0.80f * floor_light, 0.82f * floor_light,
              0.84f * floor_light);
  glUniform1i(location(floor_program_, "u_grid"), settings.grid ? 1 : 0);
  draw_mesh(meshes_[floor_mesh_]);

  glUseProgram(lit_program_);
  glUniformMatrix4fv(location(lit_program_, "u_view_projection"), 1, GL_FALSE, view_projection.m);
  glUniform3f(location(lit_program_, "u_light_direction"), light_direction_.x, light_direction_.y,
              light_direction_.z);
  glUniform3f(location(lit_program_, "u_eye"), eye.x, eye.y, eye.z);
  glUniform1i(location(lit_program_, "u_texture"), 0);
  glActiveTexture(GL_TEXTURE0);

  const int model_loc = location(lit_program_, "u_model");
  const int normal_loc = location(lit_program_, "u_normal_matrix");
  const int color_loc = location(lit_program_, "u_color");
  const int use_texture_loc = location(lit_program_, "u_use_texture");
  const int texture_scale_loc = location(lit_program_, "u_texture_scale");
  const int lit_loc = location(lit_program_, "u_lit");
  const int highlight_loc = location(lit_program_, "u_highlight");
  auto draw_item = [&](const DrawItem& item, const Mat4& model) {
    float normals[9];
    normal_matrix(model, normals);
    glUniformMatrix4fv(model_loc, 1, GL_FALSE, model.m);
    glUniformMatrix3fv(normal_loc, 1, GL_FALSE, normals);
    glUniform4fv(color_loc, 1, item.color);
    glUniform1i(use_texture_loc, item.texture != 0 ? 1 : 0);
    glUniform1f(texture_scale_loc, item.texture_scale);
    glUniform1i(lit_loc, item.lit ? 1 : 0);
    glUniform1i(highlight_loc, item.highlighted ? 1 : 0);
    if (item.texture != 0) glBindTexture(GL_TEXTURE_2D, item.texture);
    draw_mesh(meshes_[item.mesh]);
  };

  // Shadows on the floor: every opaque item flattened along the light, drawn dark and
  // translucent; the stencil darkens each pixel once where shadows overlap. Far cheaper than
  // a shadow map on a machine without a GPU (Mesa llvmpipe), which matters for 60 fps.
  if (settings.shadows) {
    const Mat4 flatten = floor_shadow_projection();
    glEnable(GL_STENCIL_TEST);
    glStencilFunc(GL_EQUAL, 0, 0xff);
    glStencilOp(GL_KEEP, GL_KEEP, GL_INCR);
    glEnable(GL_BLEND);
    glBlendFunc(GL_SRC_ALPHA, GL_ONE_MINUS_SRC_ALPHA);
    glDepthMask(GL_FALSE);
    DrawItem shadow;
    shadow.lit = false;
    shadow.color[0] = shadow.color[1] = shadow.color[2] = 0.05f;
    shadow.color[3] = 0.45f;
    for (const auto& item : items) {
      // Only what stands above the floor casts a shadow on it.
      if (!item.casts_shadow || item.color[3] < 0.5f || item.model.at(2, 3) < 0) continue;
      shadow.mesh = item.coarse_mesh >= 0 ? item.coarse_mesh : item.mesh;
      draw_item(shadow, flatten * item.model);
    }
    glDepthMask(GL_TRUE);
    glDisable(GL_BLEND);
    glDisable(GL_STENCIL_TEST);
  }
  glEnable(GL_CULL_FACE);

  // Pixels per metre at one metre from the eye: an item's size on screen is its largest scale
  // times this over its distance.
  const float pixels_per_m_at_1m = height_px / (2 * std::tan(camera.fov_y_rad / 2));
  auto coarse_enough = [&](const DrawItem& item) {
    if (item.coarse_mesh < 0) return false;
    const Mat4& m = item.model;
    float scale2 = 0;
    for (int c = 0; c < 3; ++c)
      scale2 = std::max(
          scale2, m.at(0, c) * m.at(0, c) + m.at(1, c) * m.at(1, c) + m.at(2, c) * m.at(2, c));
    const Vec3f centre{m.at(0, 3), m.at(1, 3), m.at(2, 3)};
    const float distance2 = std::max(1e-6f, dot(centre - eye, centre - eye));
    // Under about 24 pixels across, 12 segments look as round as 32.
    return scale2 * pixels_per_m_at_1m * pixels_per_m_at_1m < 12.0f * 12.0f * distance2;
  };

  transparent_.clear();
  for (const auto& item : items) {
    if (item.color[3] < 0.999f) {
      transparent_.push_back(&item);
      continue;
    }
    // Open meshes and flat polygons must show both faces.
    if (item.two_sided) glDisable(GL_CULL_FACE);
    if (coarse_enough(item)) {
      DrawItem coarse = item;
      coarse.mesh = item.coarse_mesh;
      draw_item(coarse, item.model);
    } else {
      draw_item(item, item.model);
    }
    if (item.two_sided) glEnable(GL_CULL_FACE);
  }
  // Transparent items back to front, without writing depth, so they blend over each other.
  std::sort(transparent_.begin(), transparent_.end(), [&](const DrawItem* a, const DrawItem* b) {
    const Vec3f pa{a->model.at(0, 3), a->model.at(1, 3), a->model.at(2, 3)};
    const Vec3f pb{b->model.at(0, 3), b->model.at(1, 3), b->model.at(2, 3)};
    return dot(pa - eye, pa - eye) > dot(pb - eye, pb - eye);
  });
  glEnable(GL_BLEND);
  glBlendFunc(GL_SRC_ALPHA, GL_ONE_MINUS_SRC_ALPHA);
  glDepthMask(GL_FALSE);
  glDisable(GL_CULL_FACE);
  for (const DrawItem* item : transparent_)
    draw_item(*item, item->model);
  glDepthMask(GL_TRUE);
  glDisable(GL_BLEND);
  glBindVertexArray(0);
}

}  // namespace s2sim::viewer
