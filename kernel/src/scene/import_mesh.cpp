/// \file
/// Mesh geometry of imported robots (STL, OBJ, DAE, ... through assimp). Collision keeps the
/// primitives' analytic contact: a mesh collides as its bounding box, with a warning, and is
/// drawn as the mesh (docs/models/import.md, "Meshes").

#include "scene/import_model.hpp"

#include "scene/attributes.hpp"

#include <assimp/postprocess.h>
#include <assimp/scene.h>
#include <assimp/Importer.hpp>

#include <algorithm>
#include <cmath>
#include <limits>

namespace s2sim::scene::detail {
namespace {

/// Bounds of every vertex of every mesh of the file, node transforms applied.
struct MeshBounds {
  Vec3 lo, hi;
  std::size_t vertices = 0;
};

void accumulate(const aiScene* s, const aiNode* node, const aiMatrix4x4& parent, MeshBounds& b) {
  const aiMatrix4x4 t = parent * node->mTransformation;
  for (unsigned i = 0; i < node->mNumMeshes; ++i) {
    const aiMesh* mesh = s->mMeshes[node->mMeshes[i]];
    for (unsigned v = 0; v < mesh->mNumVertices; ++v) {
      const aiVector3D p = t * mesh->mVertices[v];
      const Vec3 q{p.x, p.y, p.z};
      if (b.vertices == 0) b.lo = b.hi = q;
      b.lo = Vec3{std::min(b.lo.x, q.x), std::min(b.lo.y, q.y), std::min(b.lo.z, q.z)};
      b.hi = Vec3{std::max(b.hi.x, q.x), std::max(b.hi.y, q.y), std::max(b.hi.z, q.z)};
      ++b.vertices;
    }
  }
  for (unsigned c = 0; c < node->mNumChildren; ++c)
    accumulate(s, node->mChildren[c], t, b);
}

}  // namespace

Geom mesh_geom(ImportedModel& model, const std::filesystem::path& file, const Vec3& scale,
               const Pose& pose, const Location& where) {
  Assimp::Importer importer;
  // Collada files carry their own up axis and unit: assimp applies both to the root node.
  const aiScene* s = importer.ReadFile(file.string(), aiProcess_Triangulate);
  if (!s || !s->mRootNode)
    throw Error(ErrorKind::scene, where,
                "cannot read mesh '" + file.generic_string() + "': " + importer.GetErrorString());
  MeshBounds b;
  accumulate(s, s->mRootNode, aiMatrix4x4(), b);
  if (b.vertices == 0)
    throw Error(ErrorKind::scene, where, "mesh '" + file.generic_string() + "' has no vertices");
  const Vec3 lo{b.lo.x * scale.x, b.lo.y * scale.y, b.lo.z * scale.z};
  const Vec3 hi{b.hi.x * scale.x, b.hi.y * scale.y, b.hi.z * scale.z};
  const Vec3 size{std::abs(hi.x - lo.x), std::abs(hi.y - lo.y), std::abs(hi.z - lo.z)};
  const Vec3 centre = (lo + hi) * 0.5;
  Geom g;
  g.shape.type = ShapeType::box;
  // A flat mesh (a plane of triangles) still needs a thickness to collide.
  constexpr double kThinnest_m = 1e-4;
  g.shape.size_m = Vec3{std::max(size.x, kThinnest_m), std::max(size.y, kThinnest_m),
                        std::max(size.z, kThinnest_m)};
  g.pose = Pose{pose * centre, pose.rotation};
  g.where = where;
  g.visual.mesh.file = file;
  g.visual.mesh.scale = scale.x;
  g.visual.mesh.offset_m = pose.position - g.pose.position;
  if (scale.x != scale.y || scale.x != scale.z)
    model.warnings.push_back(where.str() + ": mesh '" + file.filename().string() +
                             "': a non-uniform scale is drawn with its x factor " +
                             format_number(scale.x));
  model.warnings.push_back(where.str() + ": mesh '" + file.filename().string() +
                           "' collides as its bounding box " + format_number(g.shape.size_m.x) +
                           " x " + format_number(g.shape.size_m.y) + " x " +
                           format_number(g.shape.size_m.z) + " m");
  return g;
}

}  // namespace s2sim::scene::detail
