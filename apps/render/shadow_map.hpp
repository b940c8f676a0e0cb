#pragma once
/// \file
/// A shadow map for the directional light: the depth of everything that casts a shadow, seen
/// from the light through an orthographic box fitted to the casters and to where their shadows
/// can fall on the floor. The lit and floor shaders compare against it (PCF), so shadows fall
/// on bodies as well as on the floor.

#include "gl_math.hpp"

namespace s2sim::render {

/// A sphere bounding one caster in the world frame.
struct CasterBound {
  Vec3f centre_m;
  float radius_m = 0;
};

class ShadowMap {
 public:
  ShadowMap() = default;
  ~ShadowMap();
  ShadowMap(const ShadowMap&) = delete;
  ShadowMap& operator=(const ShadowMap&) = delete;

  /// Creates the depth texture and its framebuffer and the depth-only program. False when the
  /// driver refuses the framebuffer: the renderer then keeps the floor-only planar shadows.
  bool init(int size_px);
  bool ready() const { return framebuffer_ != 0; }

  /// Fits the light's box to the casters (light_direction points towards the light, unit,
  /// with z > 0; `floor_z_m` is the lowest receiver). False when there is nothing to cast.
  bool fit(const CasterBound* casters, int count, const Vec3f& light_direction, float floor_z_m);

  /// Binds the map's framebuffer, clears it and the depth program, sets the viewport; draw the
  /// casters with set_model() before each.
  void begin_pass() const;
  void set_model(const Mat4& model) const;
  /// Unbinds (the caller binds its own framebuffer and viewport again).
  void end_pass() const;

  /// Smooth (linear compare: the texture unit blends the tests of the 4 nearest texels, a 2x2
  /// percentage-closer filter) or hard (the nearest texel) shadow edges. On llvmpipe the
  /// smooth lookup costs about 15 ms of CPU per frame at 960x505 (scenes/pile), the hard one 2.
  void set_smooth(bool smooth);

  /// World to the map's texture coordinates and depth (0..1), for the receivers.
  const Mat4& world_to_texture() const { return world_to_texture_; }
  unsigned texture() const { return depth_texture_; }
  /// World size of one texel, metres: the receivers' normal offset against acne.
  float texel_m() const { return texel_m_; }

 private:
  unsigned framebuffer_ = 0, depth_texture_ = 0, program_ = 0;
  int size_px_ = 0;
  int model_location_ = -1, light_vp_location_ = -1;
  Mat4 light_view_projection_, world_to_texture_;
  float texel_m_ = 0.01f;
  bool smooth_ = false;
};

}  // namespace s2sim::render
