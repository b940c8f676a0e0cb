#include "renderer.hpp"

#include "gl.hpp"
#include "gl_program.hpp"
#include "world_shaders.hpp"

#include <stb/stb_image.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <string>

namespace s2sim::render {
namespace {

// Texels a side: 2048 with smooth shadows (a GPU, or screenshots); 1024, 4x cheaper to clear
// and fill, for the fast mode of a software rasteriser.
constexpr int kSmoothShadowMapSize_px = 2048;
constexpr int kFastShadowMapSize_px = 1024;

int location(unsigned program, const char* name) {
  return uniform(program, name);
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
  for (unsigned t : image_textures_)
    glDeleteTextures(1, &t);
  for (int shadow = 0; shadow < 2; ++shadow) {
    if (lit_programs_[shadow]) glDeleteProgram(lit_programs_[shadow]);
    for (unsigned program : floor_programs_[shadow])
      if (program) glDeleteProgram(program);
  }
}

void Renderer::init() {
  for (int shadow = 0; shadow < 2; ++shadow) {
    const std::string defines = shadow ? "#define SHADOW_MAP\n" : "";
    lit_programs_[shadow] =
        link_program(shaders::kLitVertex, shaders::kLitFragment, defines.c_str());
    for (int texture = 0; texture < 2; ++texture)
      floor_programs_[shadow][texture] =
          link_program(shaders::kFloorVertex, shaders::kFloorFragment,
                       (defines + (texture ? "#define FLOOR_TEXTURE\n" : "")).c_str());
  }
  sky_.init();
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
  // Bounding sphere: the box's centre and its farthest vertex.
  Vec3f lo, hi;
  vertex_bounds(mesh, lo, hi);
  if (!mesh.vertices.empty()) {
    g.centre = (lo + hi) * 0.5f;
    for (const Vertex& v : mesh.vertices) {
      const Vec3f d = Vec3f{v.position[0], v.position[1], v.position[2]} - g.centre;
      g.radius = std::max(g.radius, std::sqrt(dot(d, d)));
    }
  }
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

unsigned Renderer::image_texture(const Image& image, unsigned texture) {
  if (image.format != PixelFormat::rgb8 || image.data == nullptr) return 0;
  glPixelStorei(GL_UNPACK_ALIGNMENT, 1);
  glPixelStorei(GL_UNPACK_ROW_LENGTH, image.stride_bytes / 3);
  if (texture == 0) {
    glGenTextures(1, &texture);
    image_textures_.push_back(texture);
    glBindTexture(GL_TEXTURE_2D, texture);
    glTexImage2D(GL_TEXTURE_2D, 0, GL_RGB8, image.width_px, image.height_px, 0, GL_RGB,
                 GL_UNSIGNED_BYTE, image.data);
    glTexParameteri(GL_TEXTURE_2D, GL_TEXTURE_MIN_FILTER, GL_LINEAR_MIPMAP_LINEAR);
    glTexParameteri(GL_TEXTURE_2D, GL_TEXTURE_MAG_FILTER, GL_LINEAR);
    glTexParameteri(GL_TEXTURE_2D, GL_TEXTURE_WRAP_S, GL_CLAMP_TO_EDGE);
    glTexParameteri(GL_TEXTURE_2D, GL_TEXTURE_WRAP_T, GL_CLAMP_TO_EDGE);
  } else {
    glBindTexture(GL_TEXTURE_2D, texture);
    glTexSubImage2D(GL_TEXTURE_2D, 0, 0, 0, image.width_px, image.height_px, GL_RGB,
                    GL_UNSIGNED_BYTE, image.data);
  }
  glGenerateMipmap(GL_TEXTURE_2D);
  glPixelStorei(GL_UNPACK_ROW_LENGTH, 0);
  glPixelStorei(GL_UNPACK_ALIGNMENT, 4);
  return texture;
}

void Renderer::release_image_texture(unsigned texture) {
  const auto it = std::find(image_textures_.begin(), image_textures_.end(), texture);
  if (texture == 0 || it == image_textures_.end()) return;
  glDeleteTextures(1, &texture);
  image_textures_.erase(it);
}

bool Renderer::software_rasteriser() const {
  const auto* renderer = reinterpret_cast<const char*>(glGetString(GL_RENDERER));
  const std::string name = renderer ? renderer : "";
  for (const char* software : {"llvmpipe", "softpipe", "swrast", "Software"})
    if (name.find(software) != std::string::npos) return true;
  return false;
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

bool Renderer::render_shadow_map(const std::vector<DrawItem>& items, const Vec3f& focus_m,
                                 float focus_radius_m) {
  // The casters near the point looked at: texels stay small when bodies are spread far.
  caster_items_.clear();
  caster_models_.clear();
  casters_.clear();
  for (std::size_t i = 0; i < items.size(); ++i) {
    const DrawItem& item = items[i];
    if (!item.casts_shadow || item.color[3] < 0.5f) continue;
    const GpuMesh& mesh = meshes_[item.mesh];
    const Mat4& m = item.model;
    float scale2 = 0;  // the largest axis scale, squared
    for (int c = 0; c < 3; ++c)
      scale2 = std::max(
          scale2, m.at(0, c) * m.at(0, c) + m.at(1, c) * m.at(1, c) + m.at(2, c) * m.at(2, c));
    const CasterBound bound{m.transform_point(mesh.centre), mesh.radius * std::sqrt(scale2)};
    const Vec3f d = bound.centre_m - focus_m;
    if (std::sqrt(dot(d, d)) - bound.radius_m > focus_radius_m) continue;
    caster_items_.push_back(static_cast<int>(i));
    caster_models_.push_back(m);
    casters_.push_back(bound);
  }
  // Nothing moved since the map was drawn (paused, or bodies at rest): keep it.
  if (shadow_map_valid_ && caster_models_.size() == drawn_caster_models_.size()) {
    bool same = true;
    for (std::size_t i = 0; same && i < caster_models_.size(); ++i)
      for (int k = 0; same && k < 16; ++k)
        same = std::abs(caster_models_[i].m[k] - drawn_caster_models_[i].m[k]) < 1e-5f;
    if (same) return true;
  }
  std::swap(caster_models_, drawn_caster_models_);
  shadow_map_valid_ = false;
  if (!shadow_map_.fit(casters_.data(), static_cast<int>(casters_.size()), light_direction_, 0))
    return false;
  shadow_map_.begin_pass();
  for (int i : caster_items_) {
    const DrawItem& item = items[static_cast<std::size_t>(i)];
    shadow_map_.set_model(item.model);
    draw_mesh(meshes_[item.coarse_mesh >= 0 ? item.coarse_mesh : item.mesh]);
  }
  shadow_map_.end_pass();
  shadow_map_valid_ = true;
  return true;
}

void Renderer::set_shadow_uniforms(unsigned program) const {
  glUniform1i(location(program, "u_shadow_map"), 1);
  glUniformMatrix4fv(location(program, "u_shadow_matrix"), 1, GL_FALSE,
                     shadow_map_.world_to_texture().m);
  glUniform1f(location(program, "u_shadow_texel_m"), shadow_map_.texel_m());
}

void Renderer::draw(const std::vector<DrawItem>& items, const View& view,
                    const RenderSettings& settings) {
  const int width_px = std::max(1, view.width_px);
  const int height_px = std::max(1, view.height_px);
  const int x_px = view.x_px;
  const int y_px = view.y_px;
  glDisable(GL_SCISSOR_TEST);

  // The light's depth first: it has its own framebuffer and viewport.
  if (settings.shadows && settings.shadow_map && !shadow_map_tried_) {
    shadow_map_tried_ = true;
    if (!shadow_map_.init(settings.smooth_shadows ? kSmoothShadowMapSize_px
                                                  : kFastShadowMapSize_px))
      std::fprintf(stderr,
                   "s2sim: the driver refused the shadow map's framebuffer; shadows fall on "
                   "the floor only\n");
  }
  if (shadow_map_.ready()) shadow_map_.set_smooth(settings.smooth_shadows);
  const bool use_shadow_map = settings.shadows && settings.shadow_map && shadow_map_.ready() &&
                              render_shadow_map(items, view.focus_m, view.focus_radius_m);

  glBindFramebuffer(GL_FRAMEBUFFER, view.framebuffer);
  glClearColor(settings.clear_color[0], settings.clear_color[1], settings.clear_color[2], 1);
  glClearStencil(0);
  glDepthMask(GL_TRUE);
  glClear(GL_COLOR_BUFFER_BIT | GL_DEPTH_BUFFER_BIT | GL_STENCIL_BUFFER_BIT);
  const bool multisampled =
      settings.msaa_samples >= 2 && msaa_.bind(width_px, height_px, settings.msaa_samples);
  msaa_in_use_ = multisampled ? msaa_.samples() : 0;
  if (multisampled) {
    glViewport(0, 0, width_px, height_px);
    glClear(GL_COLOR_BUFFER_BIT | GL_DEPTH_BUFFER_BIT | GL_STENCIL_BUFFER_BIT);
  } else {
    glViewport(x_px, y_px, width_px, height_px);
  }
  glEnable(GL_DEPTH_TEST);
  glDepthFunc(GL_LESS);
  glDisable(GL_BLEND);
  const Mat4 view_projection = view.projection * view.view;
  const Vec3f eye = view.eye_m;
  glActiveTexture(GL_TEXTURE1);
  glBindTexture(GL_TEXTURE_2D, use_shadow_map ? shadow_map_.texture() : 0);
  glActiveTexture(GL_TEXTURE0);

  // The floor: a plane at z = 0, lit as a horizontal surface.
  glDisable(GL_CULL_FACE);
  const unsigned floor_program = floor_programs_[use_shadow_map][settings.floor_texture != 0];
  glUseProgram(floor_program);
  const Mat4 floor_model =
      scale_matrix({settings.floor_half_size_m, settings.floor_half_size_m, 1});
  glUniformMatrix4fv(location(floor_program, "u_model"), 1, GL_FALSE, floor_model.m);
  glUniformMatrix4fv(location(floor_program, "u_view_projection"), 1, GL_FALSE, view_projection.m);
  const float* fc = settings.floor_color;
  glUniform3f(location(floor_program, "u_color"), fc[0], fc[1], fc[2]);
  // Grid lines that show on the floor: dark on a light floor, light blue (SimTwo's) on a dark one.
  const bool dark_floor =
      settings.floor_texture == 0 && 0.299f * fc[0] + 0.587f * fc[1] + 0.114f * fc[2] < 0.45f;
  if (dark_floor)
    glUniform3f(location(floor_program, "u_grid_color"), 0.55f, 0.70f, 0.90f);
  else
    glUniform3f(location(floor_program, "u_grid_color"), 0.35f, 0.37f, 0.40f);
  glUniform1i(location(floor_program, "u_grid"), settings.grid ? 1 : 0);
  glUniform1i(location(floor_program, "u_texture"), 0);
  glUniform1f(location(floor_program, "u_tile_m"), settings.floor_texture_tile_m);
  glUniform1f(location(floor_program, "u_light_z"), light_direction_.z);
  if (use_shadow_map) set_shadow_uniforms(floor_program);
  if (settings.floor_texture != 0) glBindTexture(GL_TEXTURE_2D, settings.floor_texture);
  draw_mesh(meshes_[floor_mesh_]);

  const unsigned lit_program = lit_programs_[use_shadow_map];
  glUseProgram(lit_program);
  glUniformMatrix4fv(location(lit_program, "u_view_projection"), 1, GL_FALSE, view_projection.m);
  glUniform3f(location(lit_program, "u_light_direction"), light_direction_.x, light_direction_.y,
              light_direction_.z);
  glUniform3f(location(lit_program, "u_eye"), eye.x, eye.y, eye.z);
  glUniform1i(location(lit_program, "u_texture"), 0);
  if (use_shadow_map) set_shadow_uniforms(lit_program);

  const int model_loc = location(lit_program, "u_model");
  const int normal_loc = location(lit_program, "u_normal_matrix");
  const int color_loc = location(lit_program, "u_color");
  const int use_texture_loc = location(lit_program, "u_use_texture");
  const int texture_scale_loc = location(lit_program, "u_texture_scale");
  const int lit_loc = location(lit_program, "u_lit");
  const int highlight_loc = location(lit_program, "u_highlight");
  auto draw_item = [&](const DrawItem& item, const Mat4& model, int mesh) {
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
    draw_mesh(meshes_[mesh]);
  };

  // Without the shadow map: every opaque item flattened along the light onto the floor, drawn
  // dark and translucent; the stencil darkens each pixel once where shadows overlap.
  if (settings.shadows && !use_shadow_map) {
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
      draw_item(shadow, flatten * item.model, item.coarse_mesh >= 0 ? item.coarse_mesh : item.mesh);
    }
    glDepthMask(GL_TRUE);
    glDisable(GL_BLEND);
    glDisable(GL_STENCIL_TEST);
  }
  glEnable(GL_CULL_FACE);

  // Pixels per metre at one metre from the eye: an item's size on screen is its largest scale
  // times this over its distance.
  const float pixels_per_m_at_1m = height_px / (2 * std::tan(view.fov_y_rad / 2));
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
    draw_item(item, item.model, coarse_enough(item) ? item.coarse_mesh : item.mesh);
    if (item.two_sided) glEnable(GL_CULL_FACE);
  }
  // The sky where nothing opaque was drawn (before the transparent items, which blend over it).
  if (settings.sky) sky_.draw(view_projection, eye);

  // Transparent items back to front, without writing depth, so they blend over each other.
  std::sort(transparent_.begin(), transparent_.end(), [&](const DrawItem* a, const DrawItem* b) {
    const Vec3f pa{a->model.at(0, 3), a->model.at(1, 3), a->model.at(2, 3)};
    const Vec3f pb{b->model.at(0, 3), b->model.at(1, 3), b->model.at(2, 3)};
    return dot(pa - eye, pa - eye) > dot(pb - eye, pb - eye);
  });
  if (!transparent_.empty()) {
    glUseProgram(lit_program);
    glEnable(GL_BLEND);
    glBlendFunc(GL_SRC_ALPHA, GL_ONE_MINUS_SRC_ALPHA);
    glDepthMask(GL_FALSE);
    glDisable(GL_CULL_FACE);
    for (const DrawItem* item : transparent_)
      draw_item(*item, item->model, item->mesh);
    glDepthMask(GL_TRUE);
    glDisable(GL_BLEND);
  }
  glBindVertexArray(0);
  glActiveTexture(GL_TEXTURE1);
  glBindTexture(GL_TEXTURE_2D, 0);
  glActiveTexture(GL_TEXTURE0);
  if (multisampled) msaa_.resolve_into(view.framebuffer, x_px, y_px);
}

}  // namespace s2sim::render
