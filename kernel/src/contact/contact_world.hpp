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
#include "model/substep_forces.hpp"

#include <s2sim/component.hpp>
#include <s2sim/kernel/scene.hpp>

#include <cstdint>
#include <memory>
#include <vector>

namespace s2sim::sim {
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

  /// Where the belt speeds live (the kernel's input array), read at every substep.
  void set_inputs(const double* inputs) { inputs_ = inputs; }
  /// The input holding the surface speed of the belt solid `body` (kernel body index): the
  /// caller exposes one per shape table surface marked `belt`.
  void set_belt_speed_input(std::int32_t body, std::int32_t input);

  void compute(const Pose* poses, const Twist* twists, double step_s, Wrench* wrenches) override;

  /// Deals the contacts to the multibody's parts (MultibodyIslands, `parts` > 1): a shape's
  /// contacts with the planes and the static shapes go to its body's part, a pair's to its
  /// bodies' part. `part_of_body` per kernel body. A substep where two parts' bodies meet (a
  /// pair across parts) is computed whole, serially; either way the forces, the memory and the
  /// contact list are compute()'s to the bit (contacts are gathered in its order).
  void split_by_parts(const std::vector<int>& part_of_body, int parts);
  bool begin_parts(const Pose* poses, const Twist* twists, double step_s, Wrench* wrenches,
                   bool bodies_unmoved) override;
  void part(int part) override;
  void place_part(int part, const Pose* poses) override;
  void end_parts() override;

  /// Contacts of the last substep.
  const ContactInfo* contacts() const { return info_.data(); }
  const std::int32_t* contact_count() const { return &info_count_; }
  const collision::ShapeTable& shapes() const { return table_; }
  /// Where the shapes were at the last substep.
  const collision::Placement& placement() const { return placement_; }

  /// Forgets every contact (back to t = 0).
  void reset();
  /// Registers the state segments (snapshots), both variable: `contact/memory`, the contact
  /// points' memory, 8 numbers per point (its key's bits, then its PointState), and
  /// `contact/points`, the last substep's contacts (what the touch sensors and the contact
  /// signals read before the next one), 12 numbers per ContactInfo.
  void declare_state(sim::StateLayout& layout);

 private:
  struct Memory {
    std::uint64_t key;
    PointState state;
  };
  /// Where contacts are written: the whole substep's lists, or one part's with each contact's
  /// place in the whole order (`order`: the shape's index in moving() for a plane contact, the
  /// pair's index past them for a pair's).
  struct Sink {
    std::vector<Memory>& memory;
    std::vector<ContactInfo>& info;
    std::vector<std::int32_t>* order;
    std::size_t& cursor;  // where remembered() last stopped
  };
  /// One part's contacts of the substep (split_by_parts).
  struct PartContacts {
    std::vector<std::int32_t> moving;  // the part's indices into table_.moving()
    std::vector<std::int32_t> shapes;  // and those shapes
    std::vector<std::int32_t> bodies;  // the part's kernel bodies
    std::vector<std::int32_t> pairs;   // this substep: the part's indices into the pair list
    std::vector<Memory> memory;
    std::vector<ContactInfo> info;
    std::vector<std::int32_t> order;
    std::vector<Memory> sorted;  // memory by key
    std::size_t cursor = 0;
    std::unique_ptr<collision::FclPairs> fcl;  // the narrow phase's buffers, the part's own
  };
  /// The substep's placement, the pair list and the wrenches' reset; then contacts.
  void place(const Pose* poses);
  /// Every contact of the substep in order (compute()'s work after place()).
  void whole_contacts(const Pose* poses, const Twist* twists, double step_s, Wrench* wrenches);
  /// Moving shape `s`'s points on the planes, then the pair `pair` (an index into the pair
  /// list)'s points.
  void plane_contacts(Sink& sink, std::int32_t order, std::int32_t s, const Pose* poses,
                      const Twist* twists, double step_s, Wrench* wrenches);
  void pair_contacts(Sink& sink, std::int32_t order, std::int32_t pair, collision::FclPairs* fcl,
                     const Pose* poses, const Twist* twists, double step_s, Wrench* wrenches);
  /// Deals this substep's pairs to the parts; false when a pair lies across two parts.
  bool deal_pairs();
  void add_point(Sink& sink, std::int32_t order, std::int32_t shape_a, std::int32_t other,
                 bool other_is_plane, const ContactPoint& p, const Pose* poses, const Twist* twists,
                 double step_s, Wrench* wrenches);
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
  void match_features(std::int32_t shape_a, std::int32_t shape_b, ContactPoint* points, int count,
                      std::size_t& cursor) const;
  /// The first remembered point whose key is not below `key` (memory_.end() if none), found
  /// forward from `cursor`, the last one asked for: the points come in nearly increasing key
  /// order.
  std::vector<Memory>::const_iterator remembered(std::uint64_t key, std::size_t& cursor) const;
  /// Sorts `runs` (its plane run, then its pair run, each nearly sorted) into `sorted`.
  static void sort_memory(std::vector<Memory>& runs, std::size_t pair_run_begin,
                          std::vector<Memory>& sorted);

  const collision::ShapeTable& table_;
  std::vector<double> restitution_beta_;        // per shape
  std::vector<std::int32_t> belt_speed_input_;  // per shape: kernel input of the belt's speed
  std::vector<double> apparent_mass_kg_;
  std::vector<Vec3> com_m_;                    // per body, body frame
  std::vector<Mat3> inverse_inertia_;          // per body, about the COM, body axes
  std::vector<char> diagonal_inertia_;         // per body: inverse_inertia_ has no off-diagonal
  std::vector<double> inverse_apparent_mass_;  // per body, 1 / apparent_mass_kg_
  std::vector<char> fixed_to_world_;           // per body: jointed to the world
  std::vector<std::uint64_t> joined_pairs_;    // sorted body pairs that never collide
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
  const std::vector<std::pair<std::int32_t, std::int32_t>>* pairs_ = nullptr;  // place()'s
  std::vector<Memory> memory_, next_memory_;
  std::size_t memory_cursor_ = 0;  // the whole substep's Sink::cursor
  std::vector<ContactInfo> info_;
  std::int32_t info_count_ = 0;
  // By parts (split_by_parts): the parts, the part of each kernel body, and begin_parts()'
  // arguments for part().
  std::vector<PartContacts> parts_;
  std::vector<std::int32_t> part_of_body_;
  std::vector<std::size_t> merge_next_;  // end_parts(): per part, its next contact
  bool placed_by_parts_ = false;         // the last pool run placed the shapes ahead
  const Pose* part_poses_ = nullptr;
  const Twist* part_twists_ = nullptr;
  double part_step_s_ = 0;
  Wrench* part_wrenches_ = nullptr;
};

}  // namespace s2sim::contact
