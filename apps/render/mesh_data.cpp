#include "mesh_data.hpp"

#include <s2sim/error.hpp>

#include <s2sim/kernel/mesh_files.hpp>

#include <assimp/postprocess.h>
#include <assimp/scene.h>

#include <algorithm>
#include <assimp/Importer.hpp>
#include <cmath>
#include <numbers>

namespace s2sim::render {
namespace {

void add_quad(MeshData& m, Vec3f a, Vec3f b, Vec3f c, Vec3f d, Vec3f n) {
  const auto base = static_cast<unsigned>(m.vertices.size());
  const Vec3f corners[4] = {a, b, c, d};
  const float uvs[4][2] = {{0, 0}, {1, 0}, {1, 1}, {0, 1}};
  for (int i = 0; i < 4; ++i)
    m.vertices.push_back(
        {{corners[i].x, corners[i].y, corners[i].z}, {n.x, n.y, n.z}, {uvs[i][0], uvs[i][1]}});
  for (unsigned i : {0u, 1u, 2u, 0u, 2u, 3u})
    m.indices.push_back(base + i);
}

}  // namespace

MeshData unit_box() {
  MeshData m;
  const float h = 0.5f;
  add_quad(m, {h, -h, -h}, {h, h, -h}, {h, h, h}, {h, -h, h}, {1, 0, 0});
  add_quad(m, {-h, h, -h}, {-h, -h, -h}, {-h, -h, h}, {-h, h, h}, {-1, 0, 0});
  add_quad(m, {h, h, -h}, {-h, h, -h}, {-h, h, h}, {h, h, h}, {0, 1, 0});
  add_quad(m, {-h, -h, -h}, {h, -h, -h}, {h, -h, h}, {-h, -h, h}, {0, -1, 0});
  add_quad(m, {-h, -h, h}, {h, -h, h}, {h, h, h}, {-h, h, h}, {0, 0, 1});
  add_quad(m, {-h, h, -h}, {h, h, -h}, {h, -h, -h}, {-h, -h, -h}, {0, 0, -1});
  return m;
}

MeshData unit_canvas_square() {
  MeshData m;
  const float h = 0.5f;
  m.vertices.push_back({{-h, h, 0}, {0, 0, 1}, {0, 0}});
  m.vertices.push_back({{h, h, 0}, {0, 0, 1}, {1, 0}});
  m.vertices.push_back({{h, -h, 0}, {0, 0, 1}, {1, 1}});
  m.vertices.push_back({{-h, -h, 0}, {0, 0, 1}, {0, 1}});
  m.indices = {0, 2, 1, 0, 3, 2};  // counter-clockwise seen from +Z
  return m;
}

MeshData unit_cylinder(int segments) {
  MeshData m;
  const float two_pi = 2 * std::numbers::pi_v<float>;
  for (int i = 0; i < segments; ++i) {
    const float a0 = two_pi * i / segments, a1 = two_pi * (i + 1) / segments;
    const Vec3f p0{std::cos(a0), std::sin(a0), 0}, p1{std::cos(a1), std::sin(a1), 0};
    // Side quad with per-vertex normals so the side looks round.
    const auto base = static_cast<unsigned>(m.vertices.size());
    const float u0 = static_cast<float>(i) / segments, u1 = static_cast<float>(i + 1) / segments;
    m.vertices.push_back({{p0.x, p0.y, -0.5f}, {p0.x, p0.y, 0}, {u0, 0}});
    m.vertices.push_back({{p1.x, p1.y, -0.5f}, {p1.x, p1.y, 0}, {u1, 0}});
    m.vertices.push_back({{p1.x, p1.y, 0.5f}, {p1.x, p1.y, 0}, {u1, 1}});
    m.vertices.push_back({{p0.x, p0.y, 0.5f}, {p0.x, p0.y, 0}, {u0, 1}});
    for (unsigned k : {0u, 1u, 2u, 0u, 2u, 3u})
      m.indices.push_back(base + k);
    // Caps as fans around the centre.
    for (float z : {0.5f, -0.5f}) {
      const auto c = static_cast<unsigned>(m.vertices.size());
      const float nz = z > 0 ? 1.0f : -1.0f;
      m.vertices.push_back({{0, 0, z}, {0, 0, nz}, {0.5f, 0.5f}});
      m.vertices.push_back({{p0.x, p0.y, z}, {0, 0, nz}, {0.5f + p0.x / 2, 0.5f + p0.y / 2}});
      m.vertices.push_back({{p1.x, p1.y, z}, {0, 0, nz}, {0.5f + p1.x / 2, 0.5f + p1.y / 2}});
      if (z > 0)
        m.indices.insert(m.indices.end(), {c, c + 1, c + 2});
      else
        m.indices.insert(m.indices.end(), {c, c + 2, c + 1});
    }
  }
  return m;
}

MeshData unit_sphere(int rings, int segments) {
  MeshData m;
  const float pi = std::numbers::pi_v<float>;
  for (int r = 0; r <= rings; ++r) {
    const float theta = pi * r / rings;
    for (int s = 0; s <= segments; ++s) {
      const float phi = 2 * pi * s / segments;
      const Vec3f n{std::sin(theta) * std::cos(phi), std::sin(theta) * std::sin(phi),
                    std::cos(theta)};
      m.vertices.push_back({{n.x, n.y, n.z},
                            {n.x, n.y, n.z},
                            {static_cast<float>(s) / segments, static_cast<float>(r) / rings}});
    }
  }
  for (int r = 0; r < rings; ++r)
    for (int s = 0; s < segments; ++s) {
      const auto a = static_cast<unsigned>(r * (segments + 1) + s);
      const auto b = a + static_cast<unsigned>(segments + 1);
      m.indices.insert(m.indices.end(), {a, b, a + 1, a + 1, b, b + 1});
    }
  return m;
}

MeshData flat_polygon(const std::vector<std::pair<double, double>>& vertices_m) {
  MeshData m;
  const std::size_t n = vertices_m.size();
  if (n < 3) return m;
  for (const auto& [x, y] : vertices_m)
    m.vertices.push_back({{static_cast<float>(x), static_cast<float>(y), 0},
                          {0, 0, 1},
                          {static_cast<float>(x), static_cast<float>(y)}});
  double area2 = 0;
  for (std::size_t i = 0; i < n; ++i) {
    const auto& [x0, y0] = vertices_m[i];
    const auto& [x1, y1] = vertices_m[(i + 1) % n];
    area2 += x0 * y1 - x1 * y0;
  }
  const double orientation = area2 >= 0 ? 1 : -1;
  std::vector<unsigned> remaining;
  for (unsigned i = 0; i < n; ++i)
    remaining.push_back(i);
  auto cross_z = [&](unsigned a, unsigned b, unsigned c) {
    const auto& [ax, ay] = vertices_m[a];
    const auto& [bx, by] = vertices_m[b];
    const auto& [cx, cy] = vertices_m[c];
    return ((bx - ax) * (cy - ay) - (by - ay) * (cx - ax)) * orientation;
  };
  // Ear clipping: track polygons are small, so O(n^3) is fine; a degenerate polygon falls
  // back on a fan after a full pass without an ear.
  while (remaining.size() > 3) {
    bool clipped = false;
    for (std::size_t i = 0; i < remaining.size() && !clipped; ++i) {
      const unsigned a = remaining[(i + remaining.size() - 1) % remaining.size()];
      const unsigned b = remaining[i];
      const unsigned c = remaining[(i + 1) % remaining.size()];
      if (cross_z(a, b, c) <= 0) continue;
      bool contains = false;
      for (unsigned p : remaining) {
        if (p == a || p == b || p == c) continue;
        if (cross_z(a, b, p) >= 0 && cross_z(b, c, p) >= 0 && cross_z(c, a, p) >= 0) {
          contains = true;
          break;
        }
      }
      if (contains) continue;
      m.indices.insert(m.indices.end(), {a, b, c});
      remaining.erase(remaining.begin() + static_cast<long>(i));
      clipped = true;
    }
    if (!clipped) break;
  }
  for (std::size_t i = 1; i + 1 < remaining.size(); ++i)
    m.indices.insert(m.indices.end(), {remaining[0], remaining[i], remaining[i + 1]});
  // Both faces up: make every triangle counter-clockwise seen from +Z.
  if (orientation < 0)
    for (std::size_t i = 0; i + 2 < m.indices.size(); i += 3)
      std::swap(m.indices[i + 1], m.indices[i + 2]);
  return m;
}

void vertex_bounds(const MeshData& mesh, Vec3f& lo, Vec3f& hi) {
  lo = {1e30f, 1e30f, 1e30f};
  hi = {-1e30f, -1e30f, -1e30f};
  for (const Vertex& v : mesh.vertices) {
    lo = {std::min(lo.x, v.position[0]), std::min(lo.y, v.position[1]),
          std::min(lo.z, v.position[2])};
    hi = {std::max(hi.x, v.position[0]), std::max(hi.y, v.position[1]),
          std::max(hi.z, v.position[2])};
  }
}

MeshData load_mesh_file(const std::filesystem::path& file, double scale) {
  Assimp::Importer importer;
  configure_mesh_importer(importer);
  const aiScene* scene = importer.ReadFile(
      file.string(), aiProcess_Triangulate | aiProcess_GenSmoothNormals |
                         aiProcess_JoinIdenticalVertices | aiProcess_PreTransformVertices);
  if (scene == nullptr || scene->mNumMeshes == 0)
    throw Error(ErrorKind::scene, Location{file.string(), "", ""},
                std::string("cannot read the mesh: ") + importer.GetErrorString());
  MeshData m;
  const auto s = static_cast<float>(scale);
  for (unsigned k = 0; k < scene->mNumMeshes; ++k) {
    const aiMesh* mesh = scene->mMeshes[k];
    const auto base = static_cast<unsigned>(m.vertices.size());
    for (unsigned i = 0; i < mesh->mNumVertices; ++i) {
      const aiVector3D& p = mesh->mVertices[i];
      const aiVector3D n = mesh->HasNormals() ? mesh->mNormals[i] : aiVector3D(0, 0, 1);
      const aiVector3D uv =
          mesh->HasTextureCoords(0) ? mesh->mTextureCoords[0][i] : aiVector3D(0, 0, 0);
      m.vertices.push_back({{p.x * s, p.y * s, p.z * s}, {n.x, n.y, n.z}, {uv.x, uv.y}});
    }
    for (unsigned f = 0; f < mesh->mNumFaces; ++f) {
      const aiFace& face = mesh->mFaces[f];
      if (face.mNumIndices != 3) continue;  // points and lines left by Triangulate
      for (unsigned i = 0; i < 3; ++i)
        m.indices.push_back(base + face.mIndices[i]);
    }
  }
  return m;
}

}  // namespace s2sim::render
