#pragma once
/// \file
/// The ray query on the shared collision::ShapeTable: the first surface along a ray among the
/// ground plane z = 0, SimTwo's four wall planes (Settings::world_walls), static obstacles and
/// every body's geoms (robot solids, shells, tyres, things). Used by sensors (through
/// `StepContext::cast_ray`) and, later, picking. The caster is the caller's: it owns the
/// placement of the shapes at the tick's poses and every cache of the query, so a cast is a
/// non-const call (the kernel owns one caster; a cast never allocates).
///
/// Broad phase, all of it built at load:
/// - obstacles sit in a StaticGrid, walked cell by cell along the ray with early exit once a
///   hit is nearer than the cell (a few obstacles are simply scanned);
/// - moving geoms are placed lazily on the first cast after `invalidate()` (once per tick),
///   kept sorted by their boxes' lower x (insertion sort: nearly sorted from the previous
///   tick); a cast scans only the geoms whose x range can meet the ray's;
/// - in small scenes, rays sharing an origin (a ranger's fan) use a per-origin bucketing of
///   every geom by the azimuth sectors its box covers (fan culling, ray_fan.cpp), kept from
///   tick to tick while the origin and the moving geoms stay within a margin of where they
///   were when it was built (the sectors are computed from margin-padded boxes, so reuse is
///   exact).
/// The query's boxes are the table's exact ones grown by 1e-9 m against round-off in the slab
/// tests; the exact tests are those of ray_primitives.hpp in each geom's frame.

#include "collision/placement.hpp"
#include "collision/shape_table.hpp"
#include "collision/static_grid.hpp"

#include <s2sim/component.hpp>

#include <cstdint>
#include <vector>

namespace s2sim::collision {

class RayCaster {
 public:
  /// `poses` is the kernel's per-tick body pose buffer (0 = world, scene body i = i + 1); it
  /// and `table` must outlive the caster; `poses` holds at least one pose per table body.
  RayCaster(const ShapeTable& table, const Pose* poses);

  /// The body poses changed: the moving geoms are placed again on the next cast.
  /// Takes shape `shape` (a deleted scene obstacle) out of every cast, or puts it back.
  void set_shape_parked(std::int32_t shape, bool parked) {
    parked_shape_.at(static_cast<std::size_t>(shape)) = parked ? 1 : 0;
  }
  /// Shape `shape` changed its primitive (ShapeTable::reshape).
  void reshaped(std::int32_t shape) {
    placement_.reshaped(table_, shape);
    invalidate();
  }
  void invalidate() {
    moving_dirty_ = true;
    fan_active_ = false;
    has_last_origin_ = false;
  }

  /// The first entry into a collision surface along `origin + s·direction` (direction need
  /// not be unit; it is normalised), s in [0, max_distance] (a surface at max_distance, to
  /// 1e-12 relative, counts). Geoms of `ignore_body` (> 0) are skipped; 0 or -1 skip nothing
  /// (the world is never ignored). Never allocates.
  RayHit cast(const Vec3& origin, const Vec3& direction, double max_distance,
              std::int32_t ignore_body);

  /// The same answer without any broad phase (every geom tested): the reference of the tests.
  RayHit cast_brute_force(const Vec3& origin, const Vec3& direction, double max_distance,
                          std::int32_t ignore_body);

  /// The `WorldView::cast_ray` callback; `kernel` is the kernel's (non-const) RayCaster, which
  /// the SDK passes as `const void*`.
  static RayHit callback(const void* kernel, const Vec3& origin, const Vec3& direction,
                         double max_distance, std::int32_t ignore_body);

  std::size_t static_geom_count() const { return table_.statics().size(); }
  std::size_t moving_geom_count() const { return table_.moving().size(); }
  /// How many times rays sharing an origin built the fan culling (tests, benchmarks).
  std::size_t fan_builds() const { return fan_builds_; }

 private:
  void update_moving();
  /// Exact test of shape `s`; updates `best` when nearer.
  bool test_shape(std::int32_t s, const Vec3& o, const Vec3& d, double t_max, RayHit& best) const;
  /// Ground and walls.
  void test_planes(const Vec3& o, const Vec3& d, double t_max, RayHit& best) const;
  /// The static obstacles, scanned or through the grid.
  void cast_statics(const Vec3& o, const Vec3& d, const Vec3& inv, double max_distance,
                    RayHit& best);
  /// The moving geoms, by the sweep along x.
  void cast_moving(const Vec3& o, const Vec3& d, const Vec3& inv, double max_distance,
                   std::int32_t ignore_body, RayHit& best);
  /// Fan culling (ray_fan.cpp): sorts every geom into the azimuth sectors its margin-padded
  /// box covers as seen from `o`.
  void build_fan(const Vec3& o);
  /// Makes the fan serve origin `o` this tick: the kept one when still valid, else rebuilt.
  void prepare_fan(const Vec3& o);
  /// Whether this ray takes the fan (from the second ray from one origin in a tick).
  bool use_fan(const Vec3& o, const Vec3& d);
  /// The cast through the fan of the current origin (after the planes).
  void cast_fan(const Vec3& o, const Vec3& d, double max_distance, std::int32_t ignore_body,
                RayHit& best) const;

  const ShapeTable& table_;
  const Pose* poses_;
  const std::int32_t* statics_;  ///< table_.statics()
  const std::int32_t* moving_;   ///< table_.moving()
  std::size_t n_static_ = 0, n_moving_ = 0;

  // The shapes at this tick's poses, their boxes padded, by table index.
  Placement placement_;
  bool moving_dirty_ = true;
  std::vector<char> parked_shape_;  ///< per shape: left out of every cast

  // Static obstacles: packed boxes (lo.x, hi.x, lo.y, hi.y, lo.z, hi.z), the grid and its
  // mailbox (the last cast that tested each static shape).
  std::vector<double> static_box_;
  StaticGrid grid_;
  std::vector<std::uint32_t> stamp_;
  std::uint32_t cast_id_ = 0;

  // Moving sweep: positions in moving() sorted by their boxes' lo.x.
  std::vector<std::int32_t> order_;
  std::vector<double> order_lo_x_;  ///< lo.x in that order (binary search)
  /// The rest of the boxes in the same order, packed (the sweep reads only these): hi.x,
  /// lo.y, hi.y, lo.z, hi.z per geom.
  std::vector<double> order_box_;
  double max_width_x_ = 0;

  // Fan culling, for rays that share an origin (a ranger's, a sonar's): from the second ray
  // from one origin in a tick, the geoms are bucketed by the azimuth sectors (seen from that
  // origin) their boxes cover, and a ray visits only its sector's. Small scenes only (the
  // static grid serves big ones); storage reserved at load. Fan ids: the statics, then the
  // moving geoms (+ n_static_).
  static constexpr int kFanSectors = 64;
  bool fan_enabled_ = false;
  /// fan_valid_: a fan was built (from fan_origin_, moving boxes in fan_box_); fan_active_:
  /// this tick's rays from active_origin_ take it (from the second ray from that origin, as
  /// without reuse: which rays take the fan never depends on earlier ticks).
  bool fan_valid_ = false, fan_active_ = false, has_last_origin_ = false;
  Vec3 fan_origin_, active_origin_, last_origin_;
  std::vector<std::int32_t> fan_shape_;  ///< table index per fan id
  /// Every geom's current box by fan id, packed in the order the fan tests them: lo.z, hi.z,
  /// lo.x, hi.x, lo.y, hi.y.
  std::vector<double> fan_geom_box_;
  std::vector<double> fan_box_;  ///< per moving geom at the build: lo.x, hi.x, lo.y, hi.y
  std::size_t fan_builds_ = 0;
  std::vector<std::int32_t> fan_start_;             ///< kFanSectors + 1 offsets into fan_items_
  std::vector<std::int32_t> fan_items_;             ///< fan ids
  std::vector<std::int32_t> fan_first_, fan_last_;  ///< per fan id, its sector range
};

}  // namespace s2sim::collision
