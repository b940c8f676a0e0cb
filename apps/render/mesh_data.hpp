#pragma once
/// \file
/// Triangle meshes on the CPU: unit primitives (box, cylinder, sphere, disc), flat polygons
/// and files read through assimp (STL, 3DS, OBJ, PLY...).

#include "gl_math.hpp"

#include <filesystem>
#include <utility>
#include <vector>

namespace s2sim::render {

struct Vertex {
  float position[3];
  float normal[3];
  float uv[2];
};

struct MeshData {
  std::vector<Vertex> vertices;
  std::vector<unsigned> indices;  ///< triangles
};

/// A 1 x 1 x 1 box centred on the origin.
MeshData unit_box();
/// A 1 x 1 square in the XY plane centred on the origin, normal +Z, for a canvas: texture
/// (0, 0) at its (-X, +Y) corner, u along +X and v along -Y, so that an image's top row, which
/// OpenGL gets first, lies along +Y.
MeshData unit_canvas_square();
/// Radius 1, length 1 along Z, centred on the origin.
MeshData unit_cylinder(int segments = 32);
/// Radius 1.
MeshData unit_sphere(int rings = 16, int segments = 32);
/// A flat polygon in the XY plane (ear clipping; either winding), normal +Z.
MeshData flat_polygon(const std::vector<std::pair<double, double>>& vertices_m);

/// The box around `mesh`'s vertices (lo above hi when it has none).
void vertex_bounds(const MeshData& mesh, Vec3f& lo, Vec3f& hi);

/// Reads a mesh file through assimp, applying `scale` to its vertices. Throws s2sim::Error
/// (kind scene) naming the file when assimp cannot read it.
MeshData load_mesh_file(const std::filesystem::path& file, double scale);

}  // namespace s2sim::render
