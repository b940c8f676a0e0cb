#pragma once
/// \file
/// Ray casting against every collision shape of a scene: the ground plane z = 0, SimTwo's four
/// wall planes (Settings::world_walls), static obstacles and every body's geoms (robot solids,
/// shells, tyres, things). Used by sensors (through `StepContext::cast_ray`) and, later, picking.
///
/// Broad phase, all of it built at load so that a cast never allocates:
/// - obstacles sit in a uniform 2-D grid over their XY bounds (CSR cell lists), walked cell by
///   cell along the ray (Amanatides–Woo) with early exit once a hit is nearer than the cell;
/// - moving geoms get world AABBs recomputed lazily on the first cast after `invalidate()`
///   (once per tick), kept sorted by their lower x (insertion sort: nearly sorted from the
///   previous tick); a cast scans only the geoms whose x range can meet the ray's.
/// - in small scenes, rays sharing an origin (a ranger's fan) use a per-tick, per-origin
///   bucketing of every geom by the azimuth sectors its box covers (fan culling), kept from
///   tick to tick while the origin and the moving geoms stay within a margin of where they
///   were when it was built (the sectors are computed from margin-padded boxes, so reuse is
///   exact).
/// The exact tests are the analytic ones of primitives.hpp in each geom's frame.

#include <s2sim/component.hpp>
#include <s2sim/kernel/scene.hpp>

#include <cstdint>
#include <vector>

namespace s2sim::raycast {

class RayCaster {
 public:
  /// `poses` is the kernel's per-tick body pose buffer (0 = world, scene body i = i + 1); it
  /// must outlive the caster and hold at least scene.bodies.size() + 1 poses.
  RayCaster(const scene::Scene& scene, const Pose* poses);

  /// The body poses changed: the moving geoms' world boxes are recomputed on the next cast.
  void invalidate() {
    moving_dirty_ = true;
    fan_active_ = false;
    has_last_origin_ = false;
  }

  /// The first entry into a collision surface along `origin + s·direction` (direction need
  /// not be unit; it is normalised), s in [0, max_distance] (a surface at max_distance, to
  /// 1e-12 relative, counts). Geoms of `ignore_body` (> 0) are
  /// skipped; 0 or -1 skip nothing (the world is never ignored). Never allocates.
  RayHit cast(const Vec3& origin, const Vec3& direction, double max_distance,
              std::int32_t ignore_body) const;

  /// The same answer without any broad phase (every geom tested): the reference of the tests.
  RayHit cast_brute_force(const Vec3& origin, const Vec3& direction, double max_distance,
                          std::int32_t ignore_body) const;

  /// The `WorldView::cast_ray` callback; `kernel` is a `const RayCaster*`.
  static RayHit callback(const void* kernel, const Vec3& origin, const Vec3& direction,
                         double max_distance, std::int32_t ignore_body);

  std::size_t static_geom_count() const { return statics_.size(); }
  std::size_t moving_geom_count() const { return moving_.size(); }
  /// How many times rays sharing an origin built the fan culling (tests, benchmarks).
  std::size_t fan_builds() const { return fan_builds_; }

 private:
  struct GeomEntry {
    std::int32_t body = 0;  ///< 0 for obstacles
    scene::ShapeType type = scene::ShapeType::box;
    Vec3 half;               ///< box half extents
    double radius = 0;       ///< sphere, cylinder
    double half_length = 0;  ///< cylinder
    std::uint32_t material = 0;
    Pose local;                   ///< geom frame in its body frame (obstacles: world)
    bool local_identity = false;  ///< the geom frame is the body frame (most solids)
    Pose world;                   ///< current world pose
    Vec3 lo, hi;                  ///< current world AABB
  };

  void add_geom(const scene::Geom& g, std::int32_t body);
  void update_moving() const;
  static void compute_aabb(GeomEntry& e);
  /// Exact test of one geom; updates `best` when nearer.
  static bool test_geom(const GeomEntry& e, const Vec3& o, const Vec3& d, double t_max,
                        RayHit& best);
  /// Ground and walls.
  void test_planes(const Vec3& o, const Vec3& d, double t_max, RayHit& best) const;
  /// Normalises a ray's direction into `unit` and clips `max_distance` to the world's reach;
  /// false for a zero direction or a negative distance (no hit).
  bool prepare(const Vec3& direction, double& max_distance, Vec3& unit) const;
  /// Fan culling: sorts every geom into the azimuth sectors its margin-padded box covers as
  /// seen from `o`.
  void build_fan(const Vec3& o) const;
  /// Makes the fan serve origin `o` this tick: the kept one when still valid, else rebuilt.
  void prepare_fan(const Vec3& o) const;
  /// The cast through the fan of the current origin (after the planes).
  void cast_fan(const Vec3& o, const Vec3& d, double max_distance, std::int32_t ignore_body,
                RayHit& best) const;

  const Pose* poses_;
  bool walls_ = true;
  double wall_distance_ = 12;

  std::vector<GeomEntry> statics_;
  std::vector<double>
      static_box_;  ///< their world boxes packed: lo.x, hi.x, lo.y, hi.y, lo.z, hi.z
  mutable std::vector<GeomEntry> moving_;
  // Static grid (XY), CSR.
  double grid_x0_ = 0, grid_y0_ = 0, cell_ = 1;
  int nx_ = 0, ny_ = 0;
  std::vector<std::int32_t> cell_start_, cell_items_;
  mutable std::vector<std::uint32_t> stamp_;  ///< mailbox: last cast that tested a static geom
  mutable std::uint32_t cast_id_ = 0;
  // Moving sweep.
  mutable std::vector<std::int32_t> order_;  ///< moving geoms sorted by lo.x
  mutable std::vector<double> order_lo_x_;   ///< lo.x in that order (binary search)
  /// The rest of the boxes in the same order, packed (the sweep reads only these): hi.x,
  /// lo.y, hi.y, lo.z, hi.z per geom.
  mutable std::vector<double> order_box_;
  mutable double max_width_x_ = 0;
  mutable bool moving_dirty_ = true;
  // Fan culling, for rays that share an origin (a ranger's, a sonar's): from the second ray
  // from one origin in a tick, the geoms are bucketed by the azimuth sectors (seen from that
  // origin) their boxes cover, and a ray visits only its sector's. Small scenes only (the
  // static grid serves big ones); storage reserved at load.
  static constexpr int kFanSectors = 64;
  bool fan_enabled_ = false;
  /// fan_valid_: a fan was built (from fan_origin_, moving boxes in fan_box_); fan_active_:
  /// this tick's rays from active_origin_ take it (from the second ray from that origin, as
  /// without reuse: which rays take the fan never depends on earlier ticks).
  mutable bool fan_valid_ = false, fan_active_ = false, has_last_origin_ = false;
  mutable Vec3 fan_origin_, active_origin_, last_origin_;
  /// Every geom's current world box by fan id (statics, then moving + S), packed in the order
  /// the fan tests them: lo.z, hi.z, lo.x, hi.x, lo.y, hi.y.
  mutable std::vector<double> fan_geom_box_;
  mutable std::vector<double> fan_box_;  ///< per moving geom at the build: lo.x, hi.x, lo.y, hi.y
  mutable std::size_t fan_builds_ = 0;
  mutable std::vector<std::int32_t> fan_start_;  ///< kFanSectors + 1 offsets into fan_items_
  mutable std::vector<std::int32_t> fan_items_;  ///< geom ids: statics, then moving + S
  mutable std::vector<std::int32_t> fan_first_, fan_last_;  ///< per geom, its sector range
};

}  // namespace s2sim::raycast
