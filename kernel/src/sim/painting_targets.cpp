// The scene's painting targets (ConfigureContext::painting_targets): each `<painting_target/>`
// geom's mesh read through assimp, its triangles placed in the body frame as the viewer draws
// the mesh (apps/viewer/scene_drawables.cpp): the geom's position plus the mesh offset, the
// geom's rotation, the file's vertices times the mesh scale.
#include "scene/limits.hpp"
#include "sim/simulation_impl.hpp"

#include <s2sim/kernel/mesh_files.hpp>

#include <assimp/postprocess.h>
#include <assimp/scene.h>
#include <assimp/Importer.hpp>

#include <string>

namespace s2sim {

namespace {

/// The triangles of `g`'s mesh, in the frame `g.pose` is given in. Throws naming the geom's
/// element when the file cannot be read or has too many triangles.
std::vector<Vec3> mesh_triangles(const scene::Geom& g) {
  const scene::Mesh& mesh = g.visual.mesh;
  Assimp::Importer importer;
  configure_mesh_importer(importer);
  const aiScene* s =
      importer.ReadFile(mesh.file.string(), aiProcess_Triangulate | aiProcess_PreTransformVertices);
  if (s == nullptr || s->mNumMeshes == 0)
    throw Error(ErrorKind::scene, g.where,
                "painting target: cannot read mesh '" + mesh.file.generic_string() +
                    "': " + importer.GetErrorString());
  std::vector<Vec3> out;
  for (unsigned k = 0; k < s->mNumMeshes; ++k) {
    const aiMesh* m = s->mMeshes[k];
    for (unsigned f = 0; f < m->mNumFaces; ++f) {
      const aiFace& face = m->mFaces[f];
      if (face.mNumIndices != 3) continue;  // points and lines left by Triangulate
      if (out.size() / 3 >= static_cast<std::size_t>(scene::limits::kMaxPaintTriangles))
        throw Error(ErrorKind::scene, g.where,
                    "painting target: mesh '" + mesh.file.generic_string() + "' has more than " +
                        std::to_string(scene::limits::kMaxPaintTriangles) + " triangles");
      for (unsigned i = 0; i < 3; ++i) {
        const aiVector3D& v = m->mVertices[face.mIndices[i]];
        const Vec3 local{v.x * mesh.scale, v.y * mesh.scale, v.z * mesh.scale};
        out.push_back(g.pose.position + mesh.offset_m + g.pose.rotation * local);
      }
    }
  }
  return out;
}

}  // namespace

const std::vector<PaintingTarget>& Simulation::Impl::painting_targets() {
  if (painting_targets_read) return *painting_targets_read;
  std::vector<PaintingTarget> targets;
  auto add = [&](const scene::Geom& g, const std::string& id, int body) {
    if (!g.visual.painting_target) return;
    if (g.visual.mesh.file.empty()) {
      warnings.push_back(g.where.str() + ": <painting_target/> without a <mesh>: nothing to paint");
      return;
    }
    PaintingTarget t;
    t.id = id;
    t.body = BodyHandle{body};
    t.vertices_m = mesh_triangles(g);
    if (t.vertices_m.empty()) {
      warnings.push_back(g.where.str() + ": painting target mesh '" +
                         g.visual.mesh.file.generic_string() + "' has no triangle");
      return;
    }
    targets.push_back(std::move(t));
  };
  // SimTwo's order first: its targets are things.
  for (int b : scene.things)
    for (const auto& g : scene.bodies[static_cast<std::size_t>(b)].geoms)
      add(g, scene.bodies[static_cast<std::size_t>(b)].id, b + 1);
  for (const auto& r : scene.robots)
    for (int b : r.bodies)
      for (const auto& g : scene.bodies[static_cast<std::size_t>(b)].geoms)
        add(g, scene.bodies[static_cast<std::size_t>(b)].id, b + 1);
  for (const auto& g : scene.obstacles)
    add(g, g.id, 0);
  painting_targets_read = std::move(targets);
  return *painting_targets_read;
}

}  // namespace s2sim
