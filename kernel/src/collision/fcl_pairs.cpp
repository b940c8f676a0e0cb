// The only translation unit that sees FCL and Eigen.
#include "collision/fcl_pairs.hpp"

#include <fcl/narrowphase/detail/gjk_solver_libccd.h>
#include <fcl/narrowphase/detail/primitive_shape_algorithm/box_box.h>

#include <s2sim/kernel/scene.hpp>

#include <unordered_map>
#include <vector>

namespace s2sim::collision {
namespace {

fcl::Transform3d to_fcl(const Pose& p) {
  fcl::Transform3d t = fcl::Transform3d::Identity();
  fcl::Matrix3d r;
  for (int i = 0; i < 3; ++i)
    for (int j = 0; j < 3; ++j)
      r(i, j) = p.rotation.m[i][j];
  t.linear() = r;
  t.translation() = fcl::Vector3d(p.position.x, p.position.y, p.position.z);
  return t;
}

Vec3 from_fcl(const fcl::Vector3d& v) {
  return {v.x(), v.y(), v.z()};
}

}  // namespace

struct FclPairs::Impl {
  fcl::detail::GJKSolver_libccd<double> solver;
  std::vector<fcl::ContactPoint<double>> points;  // reused: capacity kept between calls
  std::unordered_map<const scene::ConvexHull*, std::unique_ptr<fcl::Convexd>> convex;
};

void FclPairs::prepare(const std::vector<Shape>& shapes) {
  for (const Shape& s : shapes) {
    if (s.kind != ShapeKind::convex || impl_->convex.count(s.hull)) continue;
    auto vertices = std::make_shared<std::vector<fcl::Vector3d>>();
    for (const Vec3& v : s.hull->vertices)
      vertices->emplace_back(v.x, v.y, v.z);
    auto faces = std::make_shared<std::vector<int>>();
    for (const auto& t : s.hull->triangles) {
      faces->push_back(3);
      faces->insert(faces->end(), t.begin(), t.end());
    }
    impl_->convex.emplace(s.hull, std::make_unique<fcl::Convexd>(
                                      vertices, static_cast<int>(s.hull->triangles.size()), faces));
  }
}

FclPairs::FclPairs() : impl_(std::make_unique<Impl>()) {
  impl_->points.reserve(8);
}
FclPairs::~FclPairs() = default;

int FclPairs::collide(const Shape& a, const Pose& pose_a, const Shape& b, const Pose& pose_b,
                      ContactPoint* out, double margin_m) {
  auto& points = impl_->points;
  points.clear();
  const fcl::Transform3d ta = to_fcl(pose_a), tb = to_fcl(pose_b);
  auto box = [](const Shape& s) {
    return fcl::Boxd(2 * s.half_extents_m.x, 2 * s.half_extents_m.y, 2 * s.half_extents_m.z);
  };
  auto cylinder = [](const Shape& s) { return fcl::Cylinderd(s.radius_m, 2 * s.half_length_m); };
  auto sphere = [](const Shape& s) { return fcl::Sphered(s.radius_m); };
  auto convex = [&](const Shape& s) -> const fcl::Convexd& { return *impl_->convex.at(s.hull); };
  double grown = 0;  // b's box grown by this on every side: depths come out that much deeper
  if (a.kind == ShapeKind::box && b.kind == ShapeKind::box) {
    fcl::Vector3d normal;
    double depth = 0;
    int code = 0;
    grown = margin_m;
    const Vec3 b_side = (b.half_extents_m + Vec3{grown, grown, grown}) * 2.0;
    fcl::detail::boxBox2(
        fcl::Vector3d(2 * a.half_extents_m.x, 2 * a.half_extents_m.y, 2 * a.half_extents_m.z), ta,
        fcl::Vector3d(b_side.x, b_side.y, b_side.z), tb, normal, &depth, &code, 4, points);
    if (code == 0) points.clear();
  } else {
    auto dispatch = [&](const auto& sa) {
      bool hit = false;
      switch (b.kind) {
        case ShapeKind::box:
          hit = impl_->solver.shapeIntersect(sa, ta, box(b), tb, &points);
          break;
        case ShapeKind::cylinder:
          hit = impl_->solver.shapeIntersect(sa, ta, cylinder(b), tb, &points);
          break;
        case ShapeKind::sphere:
          hit = impl_->solver.shapeIntersect(sa, ta, sphere(b), tb, &points);
          break;
        case ShapeKind::convex:
          hit = impl_->solver.shapeIntersect(sa, ta, convex(b), tb, &points);
          break;
      }
      if (!hit) points.clear();
    };
    switch (a.kind) {
      case ShapeKind::box:
        dispatch(box(a));
        break;
      case ShapeKind::cylinder:
        dispatch(cylinder(a));
        break;
      case ShapeKind::sphere:
        dispatch(sphere(a));
        break;
      case ShapeKind::convex:
        dispatch(convex(a));
        break;
    }
  }
  // FCL: normal from a to b, position midway through the overlap (a's surface point is the
  // same whether b was grown or not).
  int n = 0;
  for (const auto& p : points) {
    if (n == 4) break;
    if (!(p.penetration_depth > 0)) continue;
    const Vec3 normal_ab = from_fcl(p.normal);
    out[n] = {from_fcl(p.pos) + normal_ab * (0.5 * p.penetration_depth), -normal_ab,
              p.penetration_depth - grown, n};
    ++n;
  }
  return n;
}

}  // namespace s2sim::collision
