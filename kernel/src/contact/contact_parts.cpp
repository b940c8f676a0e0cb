// The contact layer part by part (contact_world.hpp, model::SubstepForces): the island-parallel
// step's parts each find and compute the points on their own bodies, on their own threads.
//
// Bit for bit compute()'s results: a point's force depends only on the point, its memory and
// the counts of touching points on its bodies, all of which a part holds whole when no pair of
// shapes joins two parts; each body's wrench sums its points in compute()'s order; the stops
// are solved per connected group of bodies (stop_graph.hpp), so a part's groups come out as
// in the scene-wide solve; the contact list is merged back into compute()'s order by rank.
#include "contact/contact_world.hpp"

#include "common/assert.hpp"

#include <algorithm>
#include <cmath>

namespace s2sim::contact {

bool ContactWorld::split(const std::vector<int>& part_of_body, int parts) {
  if (parts < 2) return false;
  S2SIM_ASSERT(part_of_body.size() == apparent_mass_kg_.size(), "a part for every body");
  std::vector<Memory> memory;  // what the lanes remembered, dealt again below
  for (const Lane& lane : lanes_)
    memory.insert(memory.end(), lane.memory.begin(), lane.memory.end());
  std::sort(memory.begin(), memory.end(),
            [](const Memory& x, const Memory& y) { return x.key < y.key; });
  lanes_.clear();
  lanes_.resize(static_cast<std::size_t>(parts));
  merge_at_.assign(lanes_.size(), 0);
  for (std::size_t b = 1; b < part_of_body.size(); ++b) {
    const int p = part_of_body[b];
    S2SIM_ASSERT(p >= 0 && p < parts, "a body's part out of range");
    lanes_[static_cast<std::size_t>(p)].bodies.push_back(static_cast<std::int32_t>(b));
  }
  const auto& body = table_.bodies();
  for (std::size_t s = 0; s < body.size(); ++s)  // a static shape's (body 0) is never read
    lane_of_shape_[s] = body[s] == 0 ? 0 : part_of_body[static_cast<std::size_t>(body[s])];
  for (const std::int32_t s : table_.moving())
    lane_of(s).moving.push_back(s);
  for (Lane& lane : lanes_)
    reserve(lane);
  for (const Memory& m : memory)
    lane_of(static_cast<std::int32_t>(m.key >> 40)).memory.push_back(m);
  // Each lane's own pair search: its moving shapes by island, the static ones, the others'
  // left out. Used in the substeps when no two lanes' boxes overlap (begin_parts()), and only
  // when every lane's search goes by islands (a grid would hold every shape).
  lanes_search_ = query_.by_islands();
  for (std::size_t l = 0; l < lanes_.size() && lanes_search_; ++l) {
    Lane& lane = lanes_[l];
    if (lane.moving.empty()) continue;
    std::vector<std::int32_t> labels = island_of_shape_;
    for (std::size_t s = 0; s < labels.size(); ++s)
      if (body[s] != 0 && lane_of_shape_[s] != static_cast<std::int32_t>(l))
        labels[s] = collision::IslandBroadPhase::kAbsent;
    lane.query = std::make_unique<collision::ContactQuery>(table_);
    lane.query->group_by_islands(labels, [&](std::int32_t i, std::int32_t j) {
      return !excluded(body[static_cast<std::size_t>(i)], body[static_cast<std::size_t>(j)]);
    });
    lanes_search_ = lane.query->by_islands();
  }
  if (lanes_search_)
    for (Lane& lane : lanes_)
      bound_lane(lane);
  return true;
}

bool ContactWorld::begin_parts(bool placed, const Pose* poses, const Twist* twists, double step_s) {
  if (lanes_.size() < 2) return false;
  if (!placed) place(nullptr, poses, twists, step_s);
  found_.clear();
  // No two parts' shapes' boxes overlap (their margins cover the step): no pair joins two
  // parts, and each part finds its own (compute_part()), so that this thread reads none of the
  // parts' shapes.
  own_pairs_ = lanes_search_ && lanes_apart();
  if (own_pairs_) {
    ++own_pairs_substeps_;
    return true;
  }
  // Else the scene's pairs here, into found_, which the parts then read for their own (nothing
  // of the lanes is written here: a line this thread writes costs the part's thread a trip
  // between the cores). False when two parts' bodies touch, or may within the step: the whole
  // substep then runs on this thread (compute()).
  return pair_points_into_found(true);
}

void ContactWorld::compute_part(int part, const Pose* poses, const Twist* twists, double step_s,
                                Wrench* wrenches, model::FrictionPoints* friction) {
  Lane& lane = lanes_[static_cast<std::size_t>(part)];
  lane.friction = friction;
  if (friction) friction->count = 0;
  for (const std::int32_t b : lane.bodies)
    wrenches[b] = Wrench{};
  lane.next_memory.clear();
  lane.info.clear();
  lane.info_rank.clear();
  lane.stops.clear();
  lane.cursor = 0;
  lane.found.clear();
  const std::int32_t* body = table_.bodies().data();
  for (const std::int32_t s : lane.moving)
    if (!planes_skipped_[body[s]]) plane_points(s, lane.found);
  const std::size_t plane_count = lane.found.size();
  if (own_pairs_) {  // its own pairs (begin_parts()), in rank order
    if (!lane.moving.empty())
      pair_points_into(*lane.query, lane.query->overlapping_pairs_searched(placement_), lane.found,
                       false);
    lane.cursor = 0;  // the pairs' feature matching read the memory: forces() reads it again
  } else {
    for (const Found& f : found_)  // the pairs begin_parts() found, in rank order
      if (lane_of_shape_[static_cast<std::size_t>(f.shape_a)] == part) lane.found.push_back(f);
  }
  forces(&lane, lane.found, plane_count, poses, twists, step_s, wrenches);
  lane.info_count = static_cast<std::int32_t>(lane.info.size());
}

void ContactWorld::end_parts() {
  // The contact list stays in the lanes until someone reads it (contacts()): moving every
  // part's contacts to the calling thread at every substep cost the parallel step a
  // microsecond of serial work.
  in_lanes_ = lanes_hold_last_ = true;
}

void ContactWorld::merge_parts() const {
  if (!in_lanes_) return;
  in_lanes_ = false;
  // The lanes' contacts, each list in rank order, merged: compute()'s contact list.
  info_.clear();
  merge_lanes([&](std::size_t l) { return lanes_[l].info.size(); },
              [&](std::size_t l, std::size_t i, std::size_t k, std::size_t j) {
                return lanes_[l].info_rank[i] < lanes_[k].info_rank[j];
              },
              [&](std::size_t l, std::size_t i) { info_.push_back(lanes_[l].info[i]); });
  info_count_ = static_cast<std::int32_t>(info_.size());
}

const ContactInfo* ContactWorld::part_contacts(int part, const std::int32_t*& count) const {
  // The lane's list whenever it holds the last substep's contacts, merged since or not: a
  // stretch run ahead (fence_parts()) starts after a merge and reads the lanes' own lists.
  if (lanes_hold_last_) {
    const Lane& lane = lanes_[static_cast<std::size_t>(part)];
    count = &lane.info_count;
    return lane.info.data();
  }
  count = &info_count_;
  return info_.data();
}

void ContactWorld::place_part(int part, const Pose* poses, const Twist* twists, double step_s) {
  Lane& lane = lanes_[static_cast<std::size_t>(part)];
  if (lane.friction) {  // solved in the part's substep that just ran
    take_friction(*lane.friction, lane.info);
    lane.friction = nullptr;
  }
  place(&lane, poses, twists, step_s);
}

bool ContactWorld::fence_parts() {
  // The last substep part by part: each part's components then read their lane's list at
  // every tick of the stretch, the first included.
  if (lanes_.size() < 2 || !lanes_search_ || !lanes_hold_last_ || !lanes_apart()) return false;
  // Each two lanes stay apart along the axis that parts them best: each may come 45 % of the
  // gap closer to the other there, stopping short of the plane midway between them, so that a
  // tenth of the gap stays between them; sideways, and away from each other, they may go anywhere
  // (robots driving along their rows, the rows apart, never leave their fences).
  for (Lane& lane : lanes_)
    lane.fence = {{-INFINITY, -INFINITY, -INFINITY}, {INFINITY, INFINITY, INFINITY}};
  auto along = [](auto& v, int k) -> decltype(auto) {
    return k == 0 ? (v.x) : k == 1 ? (v.y) : (v.z);
  };
  for (std::size_t l = 0; l < lanes_.size(); ++l)
    for (std::size_t m = l + 1; m < lanes_.size(); ++m) {
      if (lanes_[l].moving.empty() || lanes_[m].moving.empty()) continue;
      const collision::Aabb &a = lanes_[l].bound, &b = lanes_[m].bound;
      int axis = 0;
      double gap = -INFINITY;
      bool l_below = true;  // lane l on the lower side along `axis`
      for (int k = 0; k < 3; ++k) {
        const double above = along(b.min, k) - along(a.max, k);  // l below m
        const double below = along(a.min, k) - along(b.max, k);  // l above m
        if (above > gap) gap = above, axis = k, l_below = true;
        if (below > gap) gap = below, axis = k, l_below = false;
      }
      if (!(gap > 0)) return false;  // lanes_apart() said otherwise: a NaN
      Lane& lower = l_below ? lanes_[l] : lanes_[m];
      Lane& upper = l_below ? lanes_[m] : lanes_[l];
      const double mid = along(lower.bound.max, axis) + 0.5 * gap;
      double& lower_max = along(lower.fence.max, axis);
      double& upper_min = along(upper.fence.min, axis);
      lower_max = std::min(lower_max, mid - 0.05 * gap);
      upper_min = std::max(upper_min, mid + 0.05 * gap);
    }
  found_.clear();
  own_pairs_ = true;
  return true;
}

bool ContactWorld::part_inside_fence(int part) const {
  const Lane& lane = lanes_[static_cast<std::size_t>(part)];
  if (lane.moving.empty()) return true;
  const collision::Aabb &b = lane.bound, &f = lane.fence;
  return f.min.x <= b.min.x && f.min.y <= b.min.y && f.min.z <= b.min.z && b.max.x <= f.max.x &&
         b.max.y <= f.max.y && b.max.z <= f.max.z;
}

void ContactWorld::end_parts_ahead(std::int64_t substeps) {
  own_pairs_substeps_ += substeps;
  end_parts();
}

void ContactWorld::bound_lane(Lane& lane) {
  if (lane.moving.empty()) return;
  const collision::Aabb* boxes = placement_.boxes();
  collision::Aabb bound = boxes[lane.moving.front()];
  for (const std::int32_t s : lane.moving)
    bound = collision::united(bound, boxes[s]);
  lane.bound = bound;
}

bool ContactWorld::lanes_apart() const {
  for (std::size_t l = 0; l < lanes_.size(); ++l)
    for (std::size_t m = l + 1; m < lanes_.size(); ++m)
      if (!lanes_[l].moving.empty() && !lanes_[m].moving.empty() &&
          collision::overlap(lanes_[l].bound, lanes_[m].bound))
        return false;
  return true;
}

}  // namespace s2sim::contact
