#pragma once
/// \file
/// The render library's vector and matrix names (apps/render/gl_math.hpp), used by the
/// viewer unqualified.

#include "gl_math.hpp"

namespace s2sim::viewer {

using render::cross;
using render::dot;
using render::inverse;
using render::look_at;
using render::Mat4;
using render::normalized;
using render::perspective;
using render::scale_matrix;
using render::to_f;
using render::to_mat4;
using render::translation;
using render::Vec3f;
using render::Vec4f;

}  // namespace s2sim::viewer
