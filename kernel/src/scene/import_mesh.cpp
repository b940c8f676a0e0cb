/// \file
/// Mesh geometry of imported robots (STL, OBJ, DAE, ... through assimp): a mesh collides as
/// its convex hull, as in MuJoCo, and is drawn as the mesh (docs/models/import.md, "Meshes").

#include "scene/import_model.hpp"

#include <s2sim/kernel/mesh_files.hpp>

#include "scene/attributes.hpp"
#include "scene/convex_hull.hpp"

#include <assimp/config.h>
#include <assimp/postprocess.h>
#include <assimp/scene.h>
#include <assimp/Importer.hpp>

#include <algorithm>
#include <cmath>
#include <limits>

namespace s2sim {

void configure_mesh_importer(Assimp::Importer& importer) {
  importer.SetPropertyBool(AI_CONFIG_IMPORT_COLLADA_IGNORE_UP_DIRECTION, true);
}

}  // namespace s2sim

namespace s2sim::scene::detail {
namespace {

/// Every vertex of every mesh of the file, node transforms applied.
void gather(const aiScene* s, const aiNode* node, const aiMatrix4x4& parent,
            std::vector<Vec3>& out) {
  const aiMatrix4x4 t = parent * node->mTransformation;
  for (unsigned i = 0; i < node->mNumMeshes; ++i) {
    const aiMesh* mesh = s->mMeshes[node->mMeshes[i]];
    for (unsigned v = 0; v < mesh->mNumVertices; ++v) {
      const aiVector3D p = t * mesh->mVertices[v];
      out.push_back(Vec3{p.x, p.y, p.z});
    }
  }
  for (unsigned c = 0; c < node->mNumChildren; ++c)
    gather(s, node->mChildren[c], t, out);
}

}  // namespace

Geom hull_geom(ImportedModel& model, const std::vector<Vec3>& vertices, const Pose& pose,
               const std::string& mesh_name, const Location& where) {
  Vec3 lo = vertices.front(), hi = lo;
  for (const Vec3& q : vertices) {
    lo = Vec3{std::min(lo.x, q.x), std::min(lo.y, q.y), std::min(lo.z, q.z)};
    hi = Vec3{std::max(hi.x, q.x), std::max(hi.y, q.y), std::max(hi.z, q.z)};
  }
  const Vec3 centre = (lo + hi) * 0.5;
  Geom g;
  g.where = where;
  // The geom frame at the centre of the mesh's box: the hull's vertices about it.
  g.pose = Pose{pose * centre, pose.rotation};
  std::vector<Vec3> centred;
  centred.reserve(vertices.size());
  for (const Vec3& v : vertices)
    centred.push_back(v - centre);
  std::string why;
  g.shape.hull = convex_hull(centred, why);
  // A flat mesh (a plane of triangles) still needs a thickness to collide.
  constexpr double kThinnest_m = 1e-4;
  g.shape.size_m = Vec3{std::max(hi.x - lo.x, kThinnest_m), std::max(hi.y - lo.y, kThinnest_m),
                        std::max(hi.z - lo.z, kThinnest_m)};
  if (g.shape.hull) {
    g.shape.type = ShapeType::convex;
  } else {
    g.shape.type = ShapeType::box;
    model.warnings.push_back(
        where.str() + ": mesh '" + mesh_name + "' has no convex hull (" + why +
        "); it collides as its bounding box " + format_number(g.shape.size_m.x) + " x " +
        format_number(g.shape.size_m.y) + " x " + format_number(g.shape.size_m.z) + " m");
  }
  return g;
}

Geom mesh_geom(ImportedModel& model, const std::filesystem::path& file, const Vec3& scale,
               const Pose& pose, const Location& where) {
  Assimp::Importer importer;
  configure_mesh_importer(importer);
  const aiScene* s = importer.ReadFile(file.string(), aiProcess_Triangulate);
  if (!s || !s->mRootNode)
    throw Error(ErrorKind::scene, where,
                "cannot read mesh '" + file.generic_string() + "': " + importer.GetErrorString());
  std::vector<Vec3> vertices;
  gather(s, s->mRootNode, aiMatrix4x4(), vertices);
  if (vertices.empty())
    throw Error(ErrorKind::scene, where, "mesh '" + file.generic_string() + "' has no vertices");
  for (Vec3& v : vertices)
    v = Vec3{v.x * scale.x, v.y * scale.y, v.z * scale.z};
  Geom g = hull_geom(model, vertices, pose, file.filename().string(), where);
  g.visual.mesh.file = file;
  g.visual.mesh.scale = scale.x;
  g.visual.mesh.offset_m = pose.position - g.pose.position;
  if (scale.x != scale.y || scale.x != scale.z)
    model.warnings.push_back(where.str() + ": mesh '" + file.filename().string() +
                             "': a non-uniform scale is drawn with its x factor " +
                             format_number(scale.x) + " (it collides with all three)");
  return g;
}

}  // namespace s2sim::scene::detail
