#pragma once
/// \file
/// GLSL sources of the world view: lit bodies and the floor, both shadowed through the
/// shadow map when it is in use. Variants are compiled with SHADOW_MAP and FLOOR_TEXTURE
/// defined or not rather than switched by uniforms: llvmpipe runs both sides of a branch, so
/// an unused lookup would still cost every pixel. One linear-compare tap: the texture unit compares
/// the 2x2 nearest texels and blends the results (percentage-closer filtering); more taps cost too
/// much on llvmpipe, where every lookup runs on the CPU for every pixel.

namespace s2sim::render::shaders {

/// Shadow lookup shared by both fragment shaders: 1 = lit, 0 = in shadow. The receiver is
/// moved two and a half texels along its normal (normal offset) so it does not shadow itself.
#define S2SIM_SHADOW_FUNCTION                                                                  \
  "#ifdef SHADOW_MAP\n"                                                                        \
  "uniform sampler2DShadow u_shadow_map;\n"                                                    \
  "uniform mat4 u_shadow_matrix;\n"                                                            \
  "uniform float u_shadow_texel_m;\n"                                                          \
  "float light_reaching(vec3 world, vec3 normal) {\n"                                          \
  "  vec3 p = (u_shadow_matrix * vec4(world + normal * (2.5 * u_shadow_texel_m), 1.0)).xyz;\n" \
  "  return texture(u_shadow_map, p);\n"                                                       \
  "}\n"                                                                                        \
  "#else\n"                                                                                    \
  "float light_reaching(vec3 world, vec3 normal) { return 1.0; }\n"                            \
  "#endif\n"

inline constexpr const char* kLitVertex = R"(#version 330 core
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

inline constexpr const char* kLitFragment =
    "#version 330 core\n"
    "in vec3 v_world;\n"
    "in vec3 v_normal;\n"
    "in vec2 v_uv;\n"
    "uniform vec4 u_color;\n"
    "uniform sampler2D u_texture;\n"
    "uniform bool u_use_texture;\n"
    "uniform float u_texture_scale;\n"
    "uniform bool u_lit;\n"
    "uniform bool u_highlight;\n"
    "uniform vec3 u_light_direction;\n"
    "uniform vec3 u_eye;\n"
    "out vec4 frag_color;\n" S2SIM_SHADOW_FUNCTION R"(
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
  float lit = diffuse > 0.0 ? light_reaching(v_world, n) : 1.0;
  float specular = pow(max(dot(n, normalize(u_light_direction + view)), 0.0), 32.0) * 0.2;
  vec3 color = base.rgb * (0.35 + 0.65 * diffuse * lit) + vec3(specular * lit);
  if (u_highlight) color = mix(color, vec3(1.0, 0.85, 0.2), 0.35);
  frag_color = vec4(color, base.a);
}
)";

// The floor covers most of the screen, so it has its own minimal shader: the grid, an
// optional texture and the constant lighting of a horizontal plane (llvmpipe shades every
// pixel on the CPU).
inline constexpr const char* kFloorVertex = R"(#version 330 core
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

inline constexpr const char* kFloorFragment =
    "#version 330 core\n"
    "in vec2 v_xy;\n"
    "uniform vec3 u_color;\n"
    "uniform vec3 u_grid_color;\n"
    "uniform bool u_grid;\n"
    "uniform sampler2D u_texture;\n"
    "uniform float u_tile_m;\n"
    "uniform float u_light_z;\n"
    "out vec4 frag_color;\n" S2SIM_SHADOW_FUNCTION R"(
void main() {
#ifdef FLOOR_TEXTURE
  vec3 color = texture(u_texture, v_xy / u_tile_m).rgb;
#else
  vec3 color = u_color;
#endif
  color *= 0.35 + 0.65 * u_light_z * light_reaching(vec3(v_xy, 0.0), vec3(0.0, 0.0, 1.0));
  if (u_grid) {
    // Lines every metre (strong) and every 10 cm (faint), anti-aliased with fwidth.
    vec2 w = fwidth(v_xy);
    vec2 d1 = abs(fract(v_xy - 0.5) - 0.5) / w;
    vec2 d01 = abs(fract(v_xy * 10.0 - 0.5) - 0.5) / (w * 10.0);
    float major = 1.0 - min(min(d1.x, d1.y), 1.0);
    float minor = (1.0 - min(min(d01.x, d01.y), 1.0)) * 0.35;
    color = mix(color, u_grid_color, max(major * 0.8, minor));
  }
  frag_color = vec4(color, 1.0);
}
)";

#undef S2SIM_SHADOW_FUNCTION

}  // namespace s2sim::render::shaders
