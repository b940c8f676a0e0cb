#pragma once
/// \file
/// A gradient sky: from a pale horizon to a deeper blue overhead, and a hazy grey below the
/// horizon (past the floor's edge). Drawn after the opaque geometry at the far plane with the
/// depth test, so only the pixels nothing covers are shaded.

#include "gl_math.hpp"

namespace s2sim::render {

class Sky {
 public:
  Sky() = default;
  ~Sky();
  Sky(const Sky&) = delete;
  Sky& operator=(const Sky&) = delete;

  /// Needs a current OpenGL 3.3 context; throws std::runtime_error if the shader fails.
  void init();
  /// Draws over every pixel still at the far plane of the bound framebuffer's viewport.
  void draw(const Mat4& view_projection, const Vec3f& eye_m) const;

 private:
  unsigned program_ = 0, vao_ = 0;
  int inverse_location_ = -1, eye_location_ = -1;
};

}  // namespace s2sim::render
