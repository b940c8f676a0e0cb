#pragma once
/// \file
/// The speculative stops of a substep solved together with the resting contacts they push on
/// (docs/models/contact.md, "Stops through resting contacts"). A stop (a point caught before it
/// touches, or the second half of such an impact) asks for a change of its closing speed; a
/// box stopped on a box that rests on the ground pushes that box into the ground, which a
/// penalty spring alone would let sink by the stopped momentum (millimetres at 1 ms). Here the
/// resting contacts of jointless bodies reached from a stop through other such contacts take
/// part: they may not close faster than they already do. Each group of rows joined through
/// their bodies is solved as it would be alone: exactly (an active set over the rows' Delassus
/// matrix) up to kExactRows rows, else by projected Gauss–Seidel on the bodies' velocity
/// changes, rows in the order they were added (deterministic), sweeping until it converges.

#include <s2sim/component.hpp>
#include <s2sim/math.hpp>

#include <cstdint>
#include <vector>

namespace s2sim::contact {

/// What the stops need to know of each kernel body (index 0, the world, cannot move).
struct BodyInertiaView {
  const double* inverse_mass = nullptr;   ///< 1 / apparent mass, per body
  const Mat3* inverse_inertia = nullptr;  ///< about the COM, body axes, per body
  const Mat3* to_body = nullptr;          ///< world to body axes (rotation transposed), per body
  const Vec3* com_m = nullptr;            ///< body frame, per body
  const Pose* poses = nullptr;            ///< per body, this substep
  /// Per body, the downward acceleration the step's kick will add besides the contact forces
  /// (gravity, for jointless bodies; 0 where other loads and joints decide).
  const double* falls_m_s2 = nullptr;
};

class StopGraph {
 public:
  /// Groups of up to this many rows are solved exactly; larger ones (a pile's settled heap)
  /// by projected Gauss–Seidel.
  static constexpr int kExactRows = 24;

  /// Capacity for `bodies` kernel bodies (index 0 the world) and about `rows` points.
  void reserve(std::size_t bodies, std::size_t rows);
  /// Forgets the last substep's rows.
  void clear();

  /// A stop of body_a against body_b at `point_m` (normal from b to a): the point's separating
  /// speed is to grow by `wanted_change_m_s` (its closing speed to drop by it), by a pushing
  /// impulse only.
  void add_stop(std::int32_t body_a, std::int32_t body_b, const Vec3& point_m, const Vec3& normal,
                double wanted_change_m_s);
  /// A touching point between two jointless bodies (or one and a static shape), reported as
  /// contact `info` (its point and normal are read from there), closing at `closing_m_s`
  /// (negative when separating): it takes part if a stop reaches it, and then may close no
  /// faster than max(closing, 0). `held`: deeper than the hold depth, it takes part whether a
  /// stop reaches it or not, and may not close at all. `memory`: the caller's index of the
  /// point's memory, handed back by resting_forces(); `last_impulse_N_s`: what the point took
  /// last step, where the solve starts from (a load held from step to step needs few sweeps).
  /// `recovery_m_s`: a held point overlapping deeply is to separate at this speed (no faster:
  /// an impulse only makes up what the forces of the step leave short of it).
  void add_resting(std::int32_t body_a, std::int32_t body_b, double closing_m_s, bool held,
                   std::int32_t info, std::int32_t memory, double last_impulse_N_s,
                   double recovery_m_s = 0) {
    resting_.push_back(
        {body_a, body_b, info, memory, closing_m_s, last_impulse_N_s, recovery_m_s, held, 0});
    held_count_ += held ? 1 : 0;
  }

  /// Nothing to solve: no stop and no held point.
  bool empty() const { return rows_.empty() && held_count_ == 0; }

  /// Solves the stops, the held points and the resting points the stops reach, and adds
  /// their impulses / step_s to `wrenches` (and the resting rows' to `info[...].force_N`).
  void solve(const BodyInertiaView& bodies, double step_s, Wrench* wrenches, ContactInfo* info);

  /// After solve(): f(memory, force_N) for each resting point that took an impulse, its force.
  template <class F>
  void resting_forces(double step_s, F&& f) const {
    for (const Row& r : rows_)
      if (r.info >= 0 && r.impulse_N_s > 0) f(r.memory, r.impulse_N_s / step_s);
  }

 private:
  struct Row {
    std::int32_t body_a, body_b;
    Vec3 point_m, normal;
    double wanted_m_s;  ///< the smallest change of separating speed it accepts
    std::int32_t info;  ///< -1 for a stop
    std::int32_t memory;
    // Set by solve():
    Vec3 lever_a, lever_b;  ///< r × n in body axes
    Vec3 turn_a, turn_b;    ///< I⁻¹ (r × n): angular velocity change per unit impulse
    double mass_kg = 0;     ///< 1 / (the row's own inverse mass)
    double impulse_N_s = 0;
  };
  struct Resting {
    std::int32_t body_a, body_b, info, memory;
    double closing_m_s, last_impulse_N_s, recovery_m_s;
    bool held;
    char taken;
  };
  /// Appends the held points, then the resting points a stop reaches (through other reached
  /// points) to the stops; returns how many rows take part.
  std::size_t reach(const ContactInfo* info);
  void take(Resting& r, const ContactInfo* info);
  /// Groups the first `count` rows by the bodies that join them: order_ lists the rows group
  /// by group (each in row order, groups by their first row), group g spanning
  /// [group_begin_[g], group_begin_[g + 1]). Returns the number of groups.
  std::size_t group_rows(std::size_t count);
  std::int32_t root(std::int32_t body);
  /// The change of r's separating speed that the velocity changes so far give.
  double change_of(const Row& r) const;
  /// Adds an impulse of r's (its bodies' velocity changes).
  void push(const Row& r, double impulse_N_s, const BodyInertiaView& bodies);
  /// The rows order_[first, last) of one group solved exactly (an active set over their
  /// Delassus matrix) from the velocity changes so far; false, changing nothing, when the group
  /// has more rows than kExactRows or the active set does not settle.
  bool solve_group_exactly(const BodyInertiaView& bodies, const std::size_t* first,
                           const std::size_t* last);

  std::vector<Row> rows_;         // stops (in order), then held, then reached resting points
  std::vector<Resting> resting_;  // candidates, in order
  std::size_t held_count_ = 0;
  std::vector<char> reached_;         // per body: 1 reached by a stop, 2 its velocity change begun
  std::vector<Vec3> linear_;          // per body: velocity change, world
  std::vector<Vec3> angular_;         // per body: angular velocity change, body axes
  std::vector<std::int32_t> parent_;  // per body: union–find parent (-1: a root)
  std::vector<std::int32_t> group_of_root_;  // per body: its group while grouping (-1: none)
  std::vector<std::int32_t> row_group_;      // per row
  std::vector<std::size_t> order_, group_begin_;

  // solve_group_exactly's scratch, sized by reserve(): the Delassus matrix and its active
  // block, the right sides (all rows, then packed), the packed solution, the impulses, the
  // active flags and the active rows' list.
  std::vector<double> delassus_, block_, exact_b_, exact_pb_, exact_px_, exact_impulse_;
  std::vector<int> active_, active_list_;
};

}  // namespace s2sim::contact
