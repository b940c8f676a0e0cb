/// \file
/// Convex hulls through qhull's reentrant library: triangulated facets (`Qt`), each turned
/// outward and kept with its plane.

#include "scene/convex_hull.hpp"

extern "C" {
#include <libqhull_r/qhull_ra.h>
}

#include <cstdio>
#include <cstdlib>
#include <map>

namespace s2sim::scene {

std::shared_ptr<const ConvexHull> convex_hull(const std::vector<Vec3>& points, std::string& why) {
  if (points.size() < 4) {
    why = "fewer than 4 vertices";
    return nullptr;
  }
  std::vector<coordT> coords;
  coords.reserve(points.size() * 3);
  for (const Vec3& p : points) {
    coords.push_back(p.x);
    coords.push_back(p.y);
    coords.push_back(p.z);
  }
  char* message = nullptr;
  std::size_t message_size = 0;
  FILE* err = open_memstream(&message, &message_size);
  qhT qh_storage;
  qhT* qh = &qh_storage;
  qh_zero(qh, err);
  char options[] = "qhull Qt";
  const int code = qh_new_qhull(qh, 3, static_cast<int>(points.size()), coords.data(), False,
                                options, nullptr, err);
  auto hull = std::make_shared<ConvexHull>();
  if (code == 0) {
    std::map<int, int> index;  // qhull point id -> hull vertex
    facetT* facet;
    FORALLfacets {
      std::array<int, 3> tri{};
      int k = 0;
      vertexT *vertex, **vertexp;
      FOREACHvertex_(facet->vertices) {
        if (k == 3) break;
        const int id = qh_pointid(qh, vertex->point);
        auto [it, added] = index.emplace(id, static_cast<int>(hull->vertices.size()));
        if (added) hull->vertices.push_back(points[static_cast<std::size_t>(id)]);
        tri[static_cast<std::size_t>(k++)] = it->second;
      }
      if (k != 3) continue;
      const Vec3 n{facet->normal[0], facet->normal[1], facet->normal[2]};
      const Vec3& a = hull->vertices[static_cast<std::size_t>(tri[0])];
      const Vec3& b = hull->vertices[static_cast<std::size_t>(tri[1])];
      const Vec3& c = hull->vertices[static_cast<std::size_t>(tri[2])];
      if (dot(cross(b - a, c - a), n) < 0) std::swap(tri[1], tri[2]);
      hull->triangles.push_back(tri);
      // qhull's plane: dot(normal, p) + offset = 0, the normal outward.
      hull->faces.push_back({n, -facet->offset});
    }
  }
  qh_freeqhull(qh, !qh_ALL);
  int still_long = 0, total_long = 0;
  qh_memfreeshort(qh, &still_long, &total_long);
  std::fclose(err);
  if (code != 0 || hull->triangles.size() < 4) {
    why = message && message_size > 0 ? std::string(message, message_size) : "qhull failed";
    // qhull's first line says it (e.g. "QH6154 qhull precision error: initial simplex is flat").
    if (const auto end = why.find('\n'); end != std::string::npos) why.resize(end);
    std::free(message);
    return nullptr;
  }
  std::free(message);
  return hull;
}

}  // namespace s2sim::scene
