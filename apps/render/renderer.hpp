#pragma once
/// \file
/// Draws the world view with OpenGL 3.3 core: lit meshes (colour, transparency, texture), a
/// floor (colour or texture, grid), a gradient sky and the shadows of a directional light
/// (a shadow map, on bodies and floor; planar floor-only shadows when it is unavailable),
/// multisampled and resolved into the framebuffer drawn into.

#include "gl_math.hpp"
#include "mesh_data.hpp"
#include "msaa_target.hpp"
#include "shadow_map.hpp"
#include "sky.hpp"
#include "view.hpp"

#include <s2sim/image.hpp>

#include <filesystem>
#include <map>
#include <string>
#include <vector>

namespace s2sim::render {

/// One thing to draw this frame.
struct DrawItem {
  int mesh = 0;  ///< from Renderer::upload
  /// A coarser tessellation of the same shape (spheres, cylinders), drawn when the item is
  /// small on screen and for its shadow; -1 = none.
  int coarse_mesh = -1;
  Mat4 model;  ///< mesh to world, scale included
  float color[4] = {0.5f, 0.5f, 0.5f, 1};
  unsigned texture = 0;  ///< from Renderer::texture, 0 = none
  float texture_scale = 1;
  bool casts_shadow = true;
  bool lit = true;           ///< false for markers such as sensor beams
  bool two_sided = false;    ///< mesh files and flat polygons: no back-face culling
  bool highlighted = false;  ///< the selected body: tinted
  int body = 0;              ///< the simulation's body index, for a camera's body-id image
  /// Seen by a camera's depth and body-id images (false: the fire's flames, colour only).
  bool sensed = true;
};

struct RenderSettings {
  bool shadows = true;
  bool grid = true;
  bool sky = true;             ///< gradient sky; false = clear_color
  int msaa_samples = 4;        ///< samples per pixel of the 3-D view; 0 or 1 = no multisampling
  bool shadow_map = true;      ///< shadows on bodies too; false = planar, on the floor only
  bool smooth_shadows = true;  ///< filtered (PCF) shadow-map edges; false = hard
  float floor_half_size_m = 20;
  float clear_color[3] = {0.62f, 0.72f, 0.85f};
  float floor_color[3] = {0.80f, 0.82f, 0.84f};
  unsigned floor_texture = 0;  ///< from Renderer::texture, 0 = the plain colour
  float floor_texture_tile_m = 1;
};

class Renderer {
 public:
  Renderer() = default;
  ~Renderer();
  Renderer(const Renderer&) = delete;
  Renderer& operator=(const Renderer&) = delete;

  /// Compiles the shaders. Needs a current OpenGL 3.3 context (with a stencil buffer).
  /// Throws std::runtime_error with the compiler log if a shader fails.
  void init();
  /// Uploads a mesh and returns its id for DrawItem::mesh.
  int upload(const MeshData& mesh);
  /// Loads an image file once (stb_image) and returns its texture, or 0 with `error` set.
  unsigned texture(const std::filesystem::path& file, std::string& error);
  /// Uploads an rgb8 image (a canvas) into `texture`, made when 0, and returns it; its top
  /// row is the texture's v = 0. 0 for another pixel format.
  unsigned image_texture(const Image& image, unsigned texture);
  /// Frees a texture image_texture made (0: none).
  void release_image_texture(unsigned texture);

  /// Clears `view`'s framebuffer and draws the floor and the items into its rectangle.
  void draw(const std::vector<DrawItem>& items, const View& view, const RenderSettings& settings);

  /// Draws mesh `mesh` (from upload) with the program bound; `floor_mesh()` is the floor's
  /// square, from -1 to 1 in x and y.
  void draw_mesh(int mesh) const { draw_mesh(meshes_[static_cast<std::size_t>(mesh)]); }
  int floor_mesh() const { return floor_mesh_; }

  /// Direction towards the light (unit).
  Vec3f light_direction() const { return light_direction_; }
  /// Whether OpenGL runs on the CPU (Mesa llvmpipe, softpipe, swrast), where every shaded
  /// sample costs CPU time: the viewer then does not multisample unless asked to.
  bool software_rasteriser() const;
  /// Whether shadows use the shadow map (false: the floor-only fallback).
  bool has_shadow_map() const { return shadow_map_.ready(); }
  /// The samples per pixel of the last frame, 0 = none.
  int msaa_samples() const { return msaa_in_use_; }

 private:
  struct GpuMesh {
    unsigned vao = 0, vbo = 0, ebo = 0;
    int index_count = 0;
    Vec3f centre;  ///< bounding sphere in mesh space, for fitting the shadow map
    float radius = 0;
  };
  void draw_mesh(const GpuMesh& mesh) const;
  Mat4 floor_shadow_projection() const;
  /// Renders the depth, seen from the light, of the casters within `focus_radius_m` of
  /// `focus_m`; false when nothing casts there.
  bool render_shadow_map(const std::vector<DrawItem>& items, const Vec3f& focus_m,
                         float focus_radius_m);
  void set_shadow_uniforms(unsigned program) const;

  std::vector<GpuMesh> meshes_;
  std::map<std::filesystem::path, unsigned> textures_;
  std::vector<unsigned> image_textures_;
  unsigned lit_programs_[2] = {0, 0};                 ///< [shadow map]
  unsigned floor_programs_[2][2] = {{0, 0}, {0, 0}};  ///< [shadow map][texture]
  int floor_mesh_ = -1;
  Vec3f light_direction_ = normalized({0.35f, 0.25f, 1.0f});
  std::vector<const DrawItem*> transparent_;  ///< reused every frame
  std::vector<CasterBound> casters_;          ///< reused every frame
  /// The casters' poses this frame and when the shadow map was last drawn (reused buffers).
  std::vector<Mat4> caster_models_, drawn_caster_models_;
  std::vector<int> caster_items_;  ///< indices of this frame's casters in the items
  bool shadow_map_valid_ = false;
  bool shadow_map_tried_ = false;  ///< created on the first frame with shadows
  MsaaTarget msaa_;
  ShadowMap shadow_map_;
  Sky sky_;
  int msaa_in_use_ = 0;
};

}  // namespace s2sim::render
