#pragma once
/// \file
/// The contact layer: at every substep, places the scene's collision shapes (the shared
/// collision::ShapeTable) at the substep's poses, asks the contact query for the points where
/// they touch each other, the ground and SimTwo's walls, and turns them into forces with the
/// force law and the contact points' memory from step to step (which it owns). Applied to the
/// multibody model as a substep force.

#include "collision/contact_query.hpp"
#include "collision/placement.hpp"
#include "collision/shape_table.hpp"
#include "contact/contact_force.hpp"
#include "contact/stop_graph.hpp"
#include "model/multibody.hpp"
#include "model/substep_forces.hpp"

#include <s2sim/component.hpp>
#include <s2sim/kernel/scene.hpp>

#include <cstdint>
#include <memory>
#include <vector>

namespace s2sim::common {
class StateLayout;
}

namespace s2sim::contact {

class ContactWorld final : public model::SubstepForces {
 public:
  /// `shapes`: the scene's collision table, which must outlive the contact world.
  /// `apparent_mass_kg` per kernel body (0 = world, ignored): the mass a force at the body's
  /// centre of mass meets, which sets each contact's stiffness.
  ContactWorld(const collision::ShapeTable& shapes, const scene::Scene& scene,
               const std::vector<double>& apparent_mass_kg, const ForceLawSettings& law = {});

  /// Per kernel body, its mobility with its joints free (model::Multibody::contact_mobility):
  /// a jointed body's effective mass at a point then counts the whole tree it drags (a wheel's
  /// sideways push turns the robot, not the wheel alone about its diameter). Bodies without
  /// one keep their apparent mass and their own inertia.
  void set_mobility(const std::vector<model::Multibody::Mobility>& mobility);

  /// Where the belt speeds live (the kernel's input array), read at every substep.
  void set_inputs(const double* inputs) { inputs_ = inputs; }
  /// The input holding the surface speed of the belt solid `body` (kernel body index): the
  /// caller exposes one per shape table surface marked `belt`.
  void set_belt_speed_input(std::int32_t body, std::int32_t input);

  /// Per kernel body, whether the multibody solves the friction of its points on static
  /// surfaces (model::Multibody::solves_contact_friction): with a friction list, those points'
  /// friction goes there, solved with the axes, and their reported force includes it after the
  /// substep.
  void set_solved_friction(const std::vector<char>& solved_per_body);
  /// Parks or frees kernel body `body` (a thing deleted, or a spare body no thing holds): a
  /// parked body touches nothing, the ground and the walls included.
  void set_parked(std::int32_t body, bool parked);
  /// A free body's new mass properties (a thing added while running): its mass, centre of
  /// mass (body frame), inertia about it (body axes), whether it falls, and whether it is held
  /// where it is (an obstacle added while running: it yields to nothing, and meets neither
  /// the world's shapes nor another such body).
  void set_free_body(std::int32_t body, double mass_kg, const Vec3& com_m, const Mat3& inertia,
                     bool gravity, bool fixed = false);
  /// A jointed body's new mass properties (its mass changed while running): the mass a push
  /// at it meets (model::Multibody::apparent_mass_kg), its centre of mass (body frame) and
  /// inertia about it (body axes). Its tree's mobility comes again through set_mobility.
  void set_jointed_body(std::int32_t body, double apparent_mass_kg, const Vec3& com_m,
                        const Mat3& inertia);
  /// Takes static shape `shape` (a scene obstacle) out of contact, or puts it back.
  void set_shape_parked(std::int32_t shape, bool parked) {
    parked_shape_.at(static_cast<std::size_t>(shape)) = parked ? 1 : 0;
  }
  /// Shape `shape` changed its primitive (collision::ShapeTable::reshape).
  void reshaped(std::int32_t shape) { placement_.reshaped(table_, shape); }
  /// Shape `shape` changed its surface (collision::ShapeTable::set_surface): its restitution
  /// and the table of surface pairs again (allocates).
  void surface_changed(std::int32_t shape);
  /// The most points a substep can hold (room of every per-substep list).
  std::int32_t point_capacity() const { return static_cast<std::int32_t>(reserve_); }

  void compute(const Pose* poses, const Twist* twists, double step_s, Wrench* wrenches,
               model::FrictionPoints* friction = nullptr) override;
  void end_substep() override;

  // Part by part (model::SubstepForces; contact_parts.cpp): each part finds and computes the
  // points on its own bodies (against the ground, the walls and its own bodies) on its own
  // thread, with its own memory of them, when no two parts' bodies touch or come within a
  // step of touching; the contact list is then merged in compute()'s order.
  bool split(const std::vector<int>& part_of_body, int parts) override;
  bool begin_parts(bool placed, const Pose* poses, const Twist* twists, double step_s) override;
  void compute_part(int part, const Pose* poses, const Twist* twists, double step_s,
                    Wrench* wrenches, model::FrictionPoints* friction = nullptr) override;
  void end_parts() override;
  void place_part(int part, const Pose* poses, const Twist* twists, double step_s) override;
  bool fence_parts() override;
  bool part_inside_fence(int part) const override;
  void end_parts_ahead(std::int64_t substeps) override;

  /// Contacts of the last substep, in compute()'s order. When the parts computed them, their
  /// lists are merged here, on the first call after (a run nobody reads the list of never
  /// merges): call between substeps, from one thread.
  const ContactInfo* contacts() const {
    merge_parts();
    return info_.data();
  }
  const std::int32_t* contact_count() const {
    merge_parts();
    return &info_count_;
  }
  /// How many substeps the parts found their own pairs in (their shapes' boxes apart: the
  /// calling thread then found none), since load; for tests and profiling.
  std::int64_t substeps_with_own_pairs() const { return own_pairs_substeps_; }
  /// Part `part`'s share of the last substep's contacts, in compute()'s order, with `count`
  /// pointed at its size: every contact on the part's bodies (those its components may read,
  /// sim/component_parts.hpp), unmerged; the whole list when the last substep was computed
  /// whole (the contact list may then hold other parts' contacts too). Safe while the other
  /// parts compute theirs: it is the part's own lane, or the whole list nobody writes then.
  const ContactInfo* part_contacts(int part, const std::int32_t*& count) const;
  const collision::ShapeTable& shapes() const { return table_; }
  /// Where the shapes were at the last substep.
  const collision::Placement& placement() const { return placement_; }

  /// Forgets every contact (back to t = 0).
  void reset();
  /// Registers the state segments (snapshots), both variable: `contact/memory`, the contact
  /// points' memory in key order, 10 numbers per point (its key's bits, then its PointState),
  /// and
  /// `contact/points`, the last substep's contacts (what the touch sensors and the contact
  /// signals read before the next one), 12 numbers per ContactInfo.
  void declare_state(common::StateLayout& layout);

 private:
  struct Memory {
    std::uint64_t key;
    PointState state;
  };
  /// A pair's points rank after every plane point (a plane point's rank: its shape's place in
  /// the table's moving shapes).
  static constexpr std::uint64_t kPairRank = std::uint64_t{1} << 62;
  struct Found {
    std::int32_t shape_a, other;
    bool plane;  ///< `other` is the ground or a wall
    ContactPoint point;
    std::uint64_t rank;  ///< its place in compute()'s order (the contact list's)
  };
  /// One part's share (one for the serial run): its bodies, its shapes and the memory of the
  /// points whose first shape is its own. A cache line apart: each part's thread writes its own.
  struct alignas(64) Lane {
    std::vector<std::int32_t> bodies;  ///< kernel bodies, ascending
    std::vector<std::int32_t> moving;  ///< moving shapes, in the table's order
    std::vector<Memory> memory, next_memory;
    std::size_t cursor = 0;          ///< where remembered() last stopped
    std::size_t pair_run_begin = 0;  ///< next_memory: where the pairs' points begin
    // Part by part only:
    std::vector<Found> found;
    std::vector<ContactInfo> info;
    std::vector<std::uint64_t> info_rank;
    std::int32_t info_count = 0;  // info.size(), for part_contacts()
    StopGraph stops;
    /// Its own pair search (its moving shapes and the static ones; its own narrow phase's
    /// buffers), and the box around its moving shapes as last placed.
    std::unique_ptr<collision::ContactQuery> query;
    collision::Aabb bound;
    collision::Aabb fence;  ///< the region its moving shapes keep to when running ahead
    /// Its friction points of the substep computed part by part, until place_part() took
    /// their forces into `info`.
    model::FrictionPoints* friction = nullptr;
  };
  /// Adds the solved friction of `friction`'s points to their entries of `infos`.
  static void take_friction(const model::FrictionPoints& friction, std::vector<ContactInfo>& infos);
  /// `lane`: part by part, the part's lane, whose lists take the results; null: the whole
  /// substep's lists (info_, stops_), each point's memory its first shape's lane.
  void add_point(Lane* lane, const Found& f, const Pose* poses, const Twist* twists, double step_s,
                 Wrench* wrenches);
  /// The substep computed whole: its friction points (null: friction as forces).
  model::FrictionPoints* friction_ = nullptr;
  std::vector<char> solved_friction_;  // per body: set_solved_friction()
  /// The points of moving shape `s` against the ground and the walls, appended to `out`.
  void plane_points(std::int32_t s, std::vector<Found>& out);
  /// The force of each of `found`, in order (`plane_count` first against the planes), then
  /// the stops, and the memory sorted.
  void forces(Lane* lane, const std::vector<Found>& found, std::size_t plane_count,
              const Pose* poses, const Twist* twists, double step_s, Wrench* wrenches);
  /// pair_points_into() of every overlapping pair of the scene, into found_.
  bool pair_points_into_found(bool within_lanes);
  /// The points of each of `pairs` (i < j, increasing) that may touch, appended to `out` in
  /// rank order; `within_lanes`: stops (false) at the first pair of two lanes' bodies with
  /// points.
  bool pair_points_into(collision::ContactQuery& query,
                        const std::vector<std::pair<std::int32_t, std::int32_t>>& pairs,
                        std::vector<Found>& out, bool within_lanes);
  /// The points of a pair (a must move), with stable feature ids: how many were written.
  int pair_points(collision::ContactQuery& query, std::int32_t ia, std::int32_t ib,
                  collision::ContactPoint* points);
  /// A pair's point's rank: pairs in increasing (i, j), then the point's index.
  std::uint64_t pair_rank(std::int32_t i, std::int32_t j, int k) const {
    return kPairRank +
           (static_cast<std::uint64_t>(i) * static_cast<std::uint64_t>(table_.size()) +
            static_cast<std::uint64_t>(j)) *
               collision::kMaxPointsPerPair +
           static_cast<std::uint64_t>(k);
  }
  /// Each lane's bound (after place()), and whether no two lanes' bounds overlap.
  void bound_lane(Lane& lane);
  bool lanes_apart() const;
  /// Each shape of `lane` (null: every moving shape) and each of its bodies' rotations at the
  /// substep's poses.
  void place(Lane* lane, const Pose* poses, const Twist* twists, double step_s);
  /// Room in every list of `lane` for the scene's points (at load: stepping allocates nothing).
  void reserve(Lane& lane) const;
  /// Calls take(lane, index) for every element of the lanes' runs (each `size(lane)` long and
  /// sorted by `less(lane, index, lane, index)`), merged in that order (no allocation).
  template <class Size, class Less, class Take>
  void merge_lanes(Size size, Less less, Take take) const {
    std::fill(merge_at_.begin(), merge_at_.end(), 0);
    for (;;) {
      std::size_t from = lanes_.size();
      for (std::size_t l = 0; l < lanes_.size(); ++l)
        if (merge_at_[l] < size(l) &&
            (from == lanes_.size() || less(l, merge_at_[l], from, merge_at_[from])))
          from = l;
      if (from == lanes_.size()) return;
      take(from, merge_at_[from]++);
    }
  }
  Lane& lane_of(std::int32_t shape) {
    return lanes_[static_cast<std::size_t>(lane_of_shape_[static_cast<std::size_t>(shape)])];
  }
  bool excluded(std::int32_t body_a, std::int32_t body_b) const;
  /// Adds the body's inverse effective mass at `point` along three directions.
  void inverse_masses(std::int32_t body, const Vec3& point, const Pose* poses,
                      const Vec3* directions, double* inverse_mass) const;
  /// The combined surfaces of shape `shape_a` and shape `other` (a static plane when
  /// `other_is_plane`): from the table built at load, else combined now into `scratch`.
  const PairMaterial& pair_material(std::size_t shape_a, std::size_t other, bool other_is_plane,
                                    PairMaterial& scratch) const;
  /// Builds material_of_ and pair_materials_ (at load).
  void tabulate_materials();
  /// Groups the shapes by island for the broad phase (at load, after the exclusions).
  void group_islands(const scene::Scene& scene);
  void match_features(std::int32_t shape_a, std::int32_t shape_b, ContactPoint* points, int count);
  /// The first point `lane` remembers whose key is not below `key` (its memory's end if none),
  /// found forward from the last one asked for: the points come in nearly increasing key order.
  static std::vector<Memory>::const_iterator remembered(Lane& lane, std::uint64_t key);
  /// Sorts the lane's next memory (its plane run, then its pair run, each nearly sorted) into
  /// its memory.
  static void keep_sorted_memory(Lane& lane);

  // Speculative stops and the resting contacts they push on, solved together at the end of
  // the substep (stop_graph.hpp).
  StopGraph stops_;

  const collision::ShapeTable& table_;
  std::vector<double> restitution_beta_;        // per shape
  std::vector<std::int32_t> belt_speed_input_;  // per shape: kernel input of the belt's speed
  std::vector<double> apparent_mass_kg_;
  std::vector<Vec3> com_m_;                    // per body, body frame
  std::vector<Mat3> inverse_inertia_;          // per body, about the COM, body axes
  std::vector<char> diagonal_inertia_;         // per body: inverse_inertia_ has no off-diagonal
  std::vector<double> inverse_apparent_mass_;  // per body, 1 / apparent_mass_kg_
  std::vector<model::Multibody::Mobility> mobility_;  // per body (root 0: none), set_mobility()
  std::vector<char> fixed_to_world_;                  // per body: jointed to the world
  std::vector<char> parked_;                          // per body: touches nothing (set_parked)
  std::vector<char> planes_skipped_;                  // per body: fixed to the world or parked
  std::vector<char> held_;                            // per body: held where it is (fixed)
  std::vector<char> parked_shape_;                    // per shape: a deleted scene obstacle
  std::vector<char> jointless_;                       // per body: no joint at all (0: the world)
  std::vector<double> falls_m_s2_;                    // per body: gravity if jointless, else 0
  std::vector<std::uint64_t> joined_pairs_;           // sorted body pairs that never collide
  double default_mu_ = 0.95;
  // Surfaces combined once per pair of distinct surfaces (plus each against the planes):
  // pair_materials_[material_of_[a] * (material_count_ + 1) + material_of_[b]], column
  // material_count_ for a plane. Empty when the scene has too many distinct surfaces.
  std::vector<std::int32_t> material_of_;  // per shape
  std::vector<PairMaterial> pair_materials_;
  std::size_t material_count_ = 0;
  ForceLawSettings law_;
  const double* inputs_ = nullptr;

  // Per substep (reserved at load).
  std::vector<Mat3> to_body_;  // per body: its rotation transposed (world to body axes)
  collision::Placement placement_;
  collision::ContactQuery query_;
  std::vector<Lane> lanes_;
  std::vector<std::int32_t> lane_of_shape_;    // per shape (0 for static shapes)
  mutable std::vector<std::size_t> merge_at_;  // merge_lanes()'s cursor per lane
  /// The lanes' lists into info_ when the last substep's contacts are theirs (end_parts()).
  void merge_parts() const;
  mutable bool in_lanes_ = false;  // the last substep's contacts are the lanes', unmerged
  // The lanes' lists hold the last substep's contacts (it ran part by part), merged or not.
  bool lanes_hold_last_ = false;
  std::vector<std::int32_t> island_of_shape_;  // group_islands(): per shape its island, -1 static
  bool lanes_search_ = false;  // every lane with moving shapes searches its own pairs by islands
  bool own_pairs_ = false;     // this substep, each lane finds its own pairs (begin_parts)
  std::int64_t own_pairs_substeps_ = 0;
  std::vector<std::uint64_t> plane_rank_;  // per moving shape: its place in table_.moving()
  mutable std::vector<ContactInfo> info_;  // merged on demand (contacts())
  mutable std::int32_t info_count_ = 0;
  std::vector<Found>
      found_;  // the substep's points in the order of their forces (by parts: pairs')
  std::vector<std::int32_t> touching_points_;  // per body, this substep (0 between substeps)
  std::size_t reserve_ = 0;                    // per list, at load
};

}  // namespace s2sim::contact
