#include "contact/contact_world.hpp"

#include "scene/joint_islands.hpp"

#include <algorithm>
#include <bit>
#include <cmath>

namespace s2sim::contact {
namespace {

constexpr double kMaxApparentMass = 1e12;           // a body that cannot move (welded to the world)
constexpr double kBeltTopCosine = 0.7;              // contacts within 45° of the belt's +Z ride it
constexpr std::size_t kMaxTabulatedMaterials = 64;  // distinct surfaces; beyond, per point
constexpr int kLaneShift = 24;  // a stop's memory reference: lane << 24 | index in the lane

bool same_material(const Surface& a, const Surface& b) {
  return a.has_mu == b.has_mu && a.mu == b.mu && a.mu2 == b.mu2 && a.softness == b.softness &&
         a.restitution == b.restitution &&
         a.restitution_threshold_m_s == b.restitution_threshold_m_s && a.anisotropy == b.anisotropy;
}

/// Insertion sort for a range that is sorted but for a few local swaps; past a budget of moves
/// (a range far from sorted) it hands over to std::sort. Keys are unique, so either way the
/// order is the one std::sort alone would give.
template <class It, class Less>
void sort_nearly_sorted(It first, It last, Less less) {
  if (last - first < 2) return;
  const auto budget = 4 * (last - first) + 64;
  std::ptrdiff_t moves = 0;
  for (It i = first + 1; i != last; ++i) {
    if (!less(*i, *(i - 1))) continue;
    auto value = *i;
    It j = i;
    do {
      *j = *(j - 1);
      --j;
      ++moves;
    } while (j != first && less(value, *(j - 1)));
    *j = value;
    if (moves > budget) {
      std::sort(first, last, less);
      return;
    }
  }
}

bool off_diagonal_zero(const Mat3& m) {
  return m.m[0][1] == 0 && m.m[0][2] == 0 && m.m[1][0] == 0 && m.m[1][2] == 0 && m.m[2][0] == 0 &&
         m.m[2][1] == 0;
}

std::uint64_t pair_key(std::int32_t shape_a, std::uint64_t other_id, std::int32_t feature) {
  return (static_cast<std::uint64_t>(shape_a) << 40) | (other_id << 16) |
         static_cast<std::uint16_t>(feature);
}

std::uint64_t body_pair(std::int32_t a, std::int32_t b) {
  if (a > b) std::swap(a, b);
  return (static_cast<std::uint64_t>(a) << 32) | static_cast<std::uint32_t>(b);
}

/// A body's apparent mass as contact takes it: welded to the world (infinite), unknown or
/// beyond the bound, the bound.
double bounded_apparent_mass(double m) {
  return m > 0 && std::isfinite(m) && m <= kMaxApparentMass ? m : kMaxApparentMass;
}

}  // namespace

ContactWorld::ContactWorld(const collision::ShapeTable& shapes, const scene::Scene& scene,
                           const std::vector<double>& apparent_mass_kg, const ForceLawSettings& law)
    : table_(shapes),
      apparent_mass_kg_(apparent_mass_kg),
      default_mu_(scene.settings.default_friction),
      law_(law),
      placement_(shapes),
      query_(shapes) {
  law_.erp = scene.settings.erp;
  law_.max_recovery_speed_m_s = scene.settings.contact_recovery_speed_m_s;
  for (const auto& surface : table_.surfaces())
    restitution_beta_.push_back(surface.restitution > 0 ? restitution_beta(surface.restitution)
                                                        : 0.0);
  belt_speed_input_.assign(restitution_beta_.size(), -1);

  com_m_.assign(scene.bodies.size() + 1, Vec3{});
  inverse_inertia_.assign(scene.bodies.size() + 1, Mat3{});
  for (std::size_t i = 0; i < scene.bodies.size(); ++i) {
    com_m_[i + 1] = scene.bodies[i].com_m;
    inverse_inertia_[i + 1] = inverse(scene.bodies[i].inertia_kg_m2);
  }
  diagonal_inertia_.resize(inverse_inertia_.size());
  for (std::size_t i = 0; i < inverse_inertia_.size(); ++i)
    diagonal_inertia_[i] = off_diagonal_zero(inverse_inertia_[i]) ? 1 : 0;
  to_body_.assign(apparent_mass_kg_.size(), Mat3{});
  fixed_to_world_.assign(scene.bodies.size() + 1, 0);
  for (const auto& j : scene.joints) {
    if (j.body1 < 0 || j.body2 < 0) {
      fixed_to_world_[(j.body1 < 0 ? j.body2 : j.body1) + 1] = 1;
    } else {
      joined_pairs_.push_back(body_pair(j.body1 + 1, j.body2 + 1));
    }
  }
  std::sort(joined_pairs_.begin(), joined_pairs_.end());
  parked_.assign(fixed_to_world_.size(), 0);
  planes_skipped_ = fixed_to_world_;
  held_.assign(fixed_to_world_.size(), 0);
  parked_shape_.assign(static_cast<std::size_t>(table_.size()), 0);
  jointless_.assign(scene.bodies.size() + 1, 1);
  jointless_[0] = 0;
  for (const auto& j : scene.joints)
    for (const int body : {j.body1, j.body2})
      if (body >= 0) jointless_[static_cast<std::size_t>(body) + 1] = 0;
  falls_m_s2_.assign(jointless_.size(), 0.0);
  for (std::size_t i = 0; i < scene.bodies.size(); ++i)
    if (jointless_[i + 1] && scene.bodies[i].gravity) falls_m_s2_[i + 1] = kGravity_m_s2;
  for (double& m : apparent_mass_kg_)
    m = bounded_apparent_mass(m);
  for (const double m : apparent_mass_kg_)
    inverse_apparent_mass_.push_back(1 / m);
  tabulate_materials();
  group_islands(scene);

  reserve_ = 64 + 16 * static_cast<std::size_t>(table_.size());
  info_.reserve(reserve_);
  found_.reserve(reserve_);
  touching_points_.assign(apparent_mass_kg_.size(), 0);
  stops_.reserve(apparent_mass_kg_.size(), reserve_);
  // One lane, every body: the serial run (split() deals them to the parts).
  lanes_.resize(1);
  for (std::size_t b = 1; b < apparent_mass_kg_.size(); ++b)
    lanes_[0].bodies.push_back(static_cast<std::int32_t>(b));
  lanes_[0].moving = table_.moving();
  reserve(lanes_[0]);
  merge_at_.assign(1, 0);
  lane_of_shape_.assign(static_cast<std::size_t>(table_.size()), 0);
  plane_rank_.assign(static_cast<std::size_t>(table_.size()), 0);
  for (std::size_t k = 0; k < table_.moving().size(); ++k)
    plane_rank_[static_cast<std::size_t>(table_.moving()[k])] = k;
}

void ContactWorld::group_islands(const scene::Scene& scene) {
  const std::vector<int> island_root = scene::joint_island_roots(scene);
  const auto& body = table_.bodies();
  std::vector<std::int32_t>& island_of_shape = island_of_shape_;
  island_of_shape.assign(body.size(), -1);
  for (std::size_t s = 0; s < body.size(); ++s)
    island_of_shape[s] = body[s] == 0 ? -1 : island_root[static_cast<std::size_t>(body[s] - 1)];
  query_.group_by_islands(island_of_shape, [&](std::int32_t i, std::int32_t j) {
    return !excluded(body[static_cast<std::size_t>(i)], body[static_cast<std::size_t>(j)]);
  });
}

void ContactWorld::surface_changed(std::int32_t shape) {
  const Surface& surface = table_.surfaces().at(static_cast<std::size_t>(shape));
  restitution_beta_[static_cast<std::size_t>(shape)] =
      surface.restitution > 0 ? restitution_beta(surface.restitution) : 0.0;
  tabulate_materials();
}

void ContactWorld::tabulate_materials() {
  material_of_.clear();
  pair_materials_.clear();
  material_count_ = 0;
  const auto& surfaces = table_.surfaces();
  std::vector<std::size_t> first_shape;  // per material, the first shape that has it
  for (std::size_t s = 0; s < surfaces.size(); ++s) {
    std::size_t m = 0;
    while (m < first_shape.size() && !same_material(surfaces[first_shape[m]], surfaces[s]))
      ++m;
    if (m == first_shape.size()) {
      if (first_shape.size() == kMaxTabulatedMaterials) return;  // combined per point instead
      first_shape.push_back(s);
    }
    material_of_.push_back(static_cast<std::int32_t>(m));
  }
  material_count_ = first_shape.size();
  const std::size_t columns = material_count_ + 1;
  pair_materials_.resize(material_count_ * columns);
  for (std::size_t a = 0; a < material_count_; ++a) {
    const std::size_t sa = first_shape[a];
    for (std::size_t b = 0; b < material_count_; ++b) {
      const std::size_t sb = first_shape[b];
      pair_materials_[a * columns + b] = combine_surfaces(
          surfaces[sa], restitution_beta_[sa], &surfaces[sb], restitution_beta_[sb], default_mu_);
    }
    pair_materials_[a * columns + material_count_] =
        combine_surfaces(surfaces[sa], restitution_beta_[sa], nullptr, 0.0, default_mu_);
  }
}

const PairMaterial& ContactWorld::pair_material(std::size_t shape_a, std::size_t other,
                                                bool other_is_plane, PairMaterial& scratch) const {
  if (!pair_materials_.empty()) {
    const auto a = static_cast<std::size_t>(material_of_[shape_a]);
    const std::size_t b =
        other_is_plane ? material_count_ : static_cast<std::size_t>(material_of_[other]);
    return pair_materials_[a * (material_count_ + 1) + b];
  }
  const auto& surfaces = table_.surfaces();
  scratch = other_is_plane
                ? combine_surfaces(surfaces[shape_a], restitution_beta_[shape_a], nullptr, 0.0,
                                   default_mu_)
                : combine_surfaces(surfaces[shape_a], restitution_beta_[shape_a], &surfaces[other],
                                   restitution_beta_[other], default_mu_);
  return scratch;
}

void ContactWorld::set_belt_speed_input(std::int32_t body, std::int32_t input) {
  for (std::int32_t s = 0; s < table_.size(); ++s) {
    const auto i = static_cast<std::size_t>(s);
    if (table_.surfaces()[i].belt && table_.bodies()[i] == body) belt_speed_input_[i] = input;
  }
}

void ContactWorld::set_mobility(const std::vector<model::Multibody::Mobility>& mobility) {
  mobility_.assign(apparent_mass_kg_.size(), model::Multibody::Mobility{});
  for (std::size_t b = 1; b < mobility.size() && b < mobility_.size(); ++b)
    mobility_[b] = mobility[b];
}

void ContactWorld::inverse_masses(std::int32_t body, const Vec3& point, const Pose* poses,
                                  const Vec3* directions, double* inverse_mass) const {
  if (body == 0) return;
  const auto b = static_cast<std::size_t>(body);
  if (!mobility_.empty() && mobility_[b].root > 0) {
    // Along each direction d: Fᵀ Φ F, F = (r × d; d) the unit push at the point as a wrench at
    // the COM, in the axes of the tree's base, in which Φ was taken.
    const model::Multibody::Mobility& m = mobility_[b];
    const Mat3& to_root = to_body_[static_cast<std::size_t>(m.root)];
    const Vec3 r = point - (poses[body].position + poses[body].rotation * com_m_[b]);
    for (int k = 0; k < 3; ++k) {
      const Vec3 torque = to_root * cross(r, directions[k]), force = to_root * directions[k];
      const double f[6] = {torque.x, torque.y, torque.z, force.x, force.y, force.z};
      double sum = 0;
      for (int i = 0; i < 6; ++i) {
        double row = 0;
        for (int j = 0; j < 6; ++j)
          row += m.phi[i][j] * f[j];
        sum += f[i] * row;
      }
      inverse_mass[k] += std::max(sum, 1 / kMaxApparentMass);
    }
    return;
  }
  // Along each direction d: 1/m + wᵀ I⁻¹ w with w = r × d in body axes. The body's own inertia
  // stands for its rotation, its apparent mass for its translation.
  const Mat3& rt = to_body_[b];
  const Vec3 r = rt * (point - poses[body].position) - com_m_[b];  // from the COM, body axes
  const double translation = inverse_apparent_mass_[b];
  const Mat3& inertia = inverse_inertia_[b];
  if (diagonal_inertia_[b]) {
    // The products with the zero entries add nothing (translation > 0 absorbs a signed
    // zero): the same numbers as the full product, a third of the work.
    const Vec3 diagonal{inertia.m[0][0], inertia.m[1][1], inertia.m[2][2]};
    for (int k = 0; k < 3; ++k) {
      const Vec3 w = cross(r, rt * directions[k]);
      inverse_mass[k] +=
          translation + dot(w, Vec3{diagonal.x * w.x, diagonal.y * w.y, diagonal.z * w.z});
    }
    return;
  }
  for (int k = 0; k < 3; ++k) {
    const Vec3 w = cross(r, rt * directions[k]);
    inverse_mass[k] += translation + dot(w, inertia * w);
  }
}

void ContactWorld::set_parked(std::int32_t body, bool parked) {
  const auto b = static_cast<std::size_t>(body);
  parked_.at(b) = parked ? 1 : 0;
  planes_skipped_[b] = (fixed_to_world_[b] || parked) ? 1 : 0;
}

void ContactWorld::set_free_body(std::int32_t body, double mass_kg, const Vec3& com_m,
                                 const Mat3& inertia, bool gravity, bool fixed) {
  const auto b = static_cast<std::size_t>(body);
  const double m = bounded_apparent_mass(fixed ? kMaxApparentMass : mass_kg);
  apparent_mass_kg_.at(b) = m;
  inverse_apparent_mass_[b] = 1 / m;
  com_m_[b] = com_m;
  inverse_inertia_[b] = fixed ? Mat3{} : inverse(inertia);
  diagonal_inertia_[b] = off_diagonal_zero(inverse_inertia_[b]) ? 1 : 0;
  falls_m_s2_[b] = jointless_[b] && gravity && !fixed ? kGravity_m_s2 : 0.0;
  // Held in place, it meets the world's shapes as a body jointed to the world does: never.
  held_[b] = fixed ? 1 : 0;
  fixed_to_world_[b] = fixed ? 1 : 0;
  planes_skipped_[b] = (fixed || parked_[b]) ? 1 : 0;
}

void ContactWorld::set_jointed_body(std::int32_t body, double apparent_mass_kg, const Vec3& com_m,
                                    const Mat3& inertia) {
  const auto b = static_cast<std::size_t>(body);
  const double m = bounded_apparent_mass(apparent_mass_kg);
  apparent_mass_kg_.at(b) = m;
  inverse_apparent_mass_[b] = 1 / m;
  com_m_[b] = com_m;
  inverse_inertia_[b] = inverse(inertia);
  diagonal_inertia_[b] = off_diagonal_zero(inverse_inertia_[b]) ? 1 : 0;
}

bool ContactWorld::excluded(std::int32_t body_a, std::int32_t body_b) const {
  if (body_a == body_b) return true;
  if (parked_[body_a] || parked_[body_b] || (held_[body_a] && held_[body_b])) return true;
  if (body_a == 0) return fixed_to_world_[body_b] != 0;
  if (body_b == 0) return fixed_to_world_[body_a] != 0;
  return std::binary_search(joined_pairs_.begin(), joined_pairs_.end(), body_pair(body_a, body_b));
}

void ContactWorld::reset() {
  for (Lane& lane : lanes_) {
    lane.memory.clear();
    lane.next_memory.clear();
    lane.info.clear();
    lane.info_rank.clear();
    lane.info_count = 0;
    if (lane.query) lane.query->reset();
  }
  info_.clear();
  info_count_ = 0;
  in_lanes_ = lanes_hold_last_ = false;
  query_.reset();
}

void ContactWorld::plane_points(std::int32_t s, std::vector<Found>& out) {
  collision::ContactPoint points[collision::kMaxPointsPerPair];
  const std::uint64_t rank = plane_rank_[static_cast<std::size_t>(s)];
  collision::ContactQuery::plane_points(table_, placement_, s, points,
                                        [&](std::int32_t p, const ContactPoint* found, int n) {
                                          for (int k = 0; k < n; ++k)
                                            out.push_back({s, p, true, found[k], rank});
                                        });
}

bool ContactWorld::pair_points_into_found(bool within_lanes) {
  return pair_points_into(query_, query_.overlapping_pairs(placement_), found_, within_lanes);
}

bool ContactWorld::pair_points_into(collision::ContactQuery& query,
                                    const std::vector<std::pair<std::int32_t, std::int32_t>>& pairs,
                                    std::vector<Found>& out, bool within_lanes) {
  const std::int32_t* body = table_.bodies().data();
  collision::ContactPoint points[collision::kMaxPointsPerPair];
  const char* parked_shape = parked_shape_.data();
  for (const auto& [i, j] : pairs) {
    if (excluded(body[i], body[j]) || parked_shape[i] || parked_shape[j]) continue;
    // Shape a must move: a static shape is always b.
    const bool swap = body[i] == 0;
    const std::int32_t ia = swap ? j : i, ib = swap ? i : j;
    const int n = pair_points(query, ia, ib, points);
    if (n == 0) continue;
    if (within_lanes && body[ib] != 0 &&
        lane_of_shape_[static_cast<std::size_t>(ib)] !=
            lane_of_shape_[static_cast<std::size_t>(ia)])
      return false;
    for (int k = 0; k < n; ++k)
      out.push_back({ia, ib, false, points[k], pair_rank(i, j, k)});
  }
  return true;
}

int ContactWorld::pair_points(collision::ContactQuery& query, std::int32_t ia, std::int32_t ib,
                              collision::ContactPoint* points) {
  bool renumbered = false;
  const int n = query.pair_points(table_, placement_, ia, ib, points, renumbered);
  if (renumbered && n > 0) match_features(ia, ib, points, n);
  return n;
}

void ContactWorld::reserve(Lane& lane) const {
  lane.memory.reserve(reserve_);
  lane.next_memory.reserve(reserve_);
  lane.found.reserve(reserve_);
  lane.info.reserve(reserve_);
  lane.info_rank.reserve(reserve_);
  lane.stops.reserve(apparent_mass_kg_.size(), reserve_);
}

void ContactWorld::place(Lane* lane, const Pose* poses, const Twist* twists, double step_s) {
  const double min_margin_m = law_.min_speculative_speed_m_s * step_s;
  if (!lane) {
    for (std::size_t b = 1; b < to_body_.size(); ++b)
      to_body_[b] = poses[b].rotation.transposed();
    placement_.update(table_, poses, twists, step_s, min_margin_m, law_.max_speculative_margin_m);
    if (lanes_search_)
      for (Lane& each : lanes_)
        bound_lane(each);
    return;
  }
  for (const std::int32_t b : lane->bodies)
    to_body_[static_cast<std::size_t>(b)] = poses[b].rotation.transposed();
  placement_.update(table_, poses, twists, step_s, min_margin_m, law_.max_speculative_margin_m,
                    lane->moving.data(), lane->moving.size());
  if (lanes_search_) bound_lane(*lane);
}

void ContactWorld::set_solved_friction(const std::vector<char>& solved_per_body) {
  solved_friction_.assign(apparent_mass_kg_.size(), 0);
  for (std::size_t b = 1; b < solved_per_body.size() && b < solved_friction_.size(); ++b)
    solved_friction_[b] = solved_per_body[b];
}

void ContactWorld::take_friction(const model::FrictionPoints& friction,
                                 std::vector<ContactInfo>& infos) {
  for (std::int32_t i = 0; i < friction.count; ++i) {
    const model::FrictionPoint& p = friction.points[i];
    infos[static_cast<std::size_t>(p.report)].force_N += p.force_N;
  }
}

void ContactWorld::end_substep() {
  if (!friction_) return;
  take_friction(*friction_, info_);
  friction_ = nullptr;
}

void ContactWorld::compute(const Pose* poses, const Twist* twists, double step_s, Wrench* wrenches,
                           model::FrictionPoints* friction) {
  std::fill(wrenches, wrenches + apparent_mass_kg_.size(), Wrench{});
  friction_ = friction;
  if (friction) friction->count = 0;
  for (Lane& lane : lanes_)
    lane.friction = nullptr;
  place(nullptr, poses, twists, step_s);
  in_lanes_ = lanes_hold_last_ = false;  // this substep's list is the whole one, below
  info_.clear();
  stops_.clear();
  for (Lane& lane : lanes_) {
    lane.next_memory.clear();
    lane.cursor = 0;
  }

  // First every point, then the forces: a point's damping is shared with the other points on
  // its bodies (docs/models/contact.md, "Stiff terms at any step"), so each body's count of
  // touching points must be known before any force.
  const std::int32_t* body = table_.bodies().data();
  found_.clear();
  // Moving shapes against the ground and the walls.
  for (const std::int32_t s : table_.moving())
    if (!planes_skipped_[body[s]]) plane_points(s, found_);
  const std::size_t plane_count = found_.size();
  pair_points_into_found(false);
  for (Lane& lane : lanes_)
    lane.cursor = 0;
  forces(nullptr, found_, plane_count, poses, twists, step_s, wrenches);
  info_count_ = static_cast<std::int32_t>(info_.size());
}

void ContactWorld::forces(Lane* lane, const std::vector<Found>& found, std::size_t plane_count,
                          const Pose* poses, const Twist* twists, double step_s, Wrench* wrenches) {
  const std::int32_t* body = table_.bodies().data();
  auto body_b = [&](const Found& f) { return f.plane ? 0 : body[f.other]; };
  // The world's count would gather every point on the ground: only moving bodies share.
  for (const Found& f : found)
    if (f.point.depth_m > 0) {
      ++touching_points_[static_cast<std::size_t>(body[f.shape_a])];
      if (const std::int32_t b = body_b(f); b != 0) ++touching_points_[static_cast<std::size_t>(b)];
    }
  auto mark_pair_run = [&] {
    if (lane) {
      lane->pair_run_begin = lane->next_memory.size();
    } else {
      for (Lane& each : lanes_)
        each.pair_run_begin = each.next_memory.size();
    }
  };
  for (std::size_t k = 0; k < found.size(); ++k) {
    if (k == plane_count) mark_pair_run();
    add_point(lane, found[k], poses, twists, step_s, wrenches);
  }
  if (plane_count == found.size()) mark_pair_run();
  for (const Found& f : found) {  // the world's entry is never counted (parts run at once)
    touching_points_[static_cast<std::size_t>(body[f.shape_a])] = 0;
    if (const std::int32_t b = body_b(f); b != 0) touching_points_[static_cast<std::size_t>(b)] = 0;
  }
  StopGraph& stops = lane ? lane->stops : stops_;
  if (!stops.empty()) {
    const BodyInertiaView view{inverse_apparent_mass_.data(),
                               inverse_inertia_.data(),
                               to_body_.data(),
                               com_m_.data(),
                               poses,
                               falls_m_s2_.data()};
    stops.solve(view, step_s, wrenches, (lane ? lane->info : info_).data());
    stops.resting_forces(step_s, [&](std::int32_t memory, double force_N) {
      Lane& owner = lanes_[static_cast<std::size_t>(memory >> kLaneShift)];
      owner.next_memory[static_cast<std::size_t>(memory & ((1 << kLaneShift) - 1))]
          .state.held_force_N = force_N;
    });
  }
  if (lane) {
    keep_sorted_memory(*lane);
  } else {
    for (Lane& each : lanes_)
      keep_sorted_memory(each);
  }
}

void ContactWorld::keep_sorted_memory(Lane& lane) {
  // The plane run comes shape by shape, corner by corner: sorted. The pair run follows the
  // sorted pair list but for pairs with a static first shape and FCL's renumbered points.
  auto less = [](const Memory& x, const Memory& y) { return x.key < y.key; };
  auto& next = lane.next_memory;
  const auto middle = next.begin() + static_cast<std::ptrdiff_t>(lane.pair_run_begin);
  sort_nearly_sorted(next.begin(), middle, less);
  sort_nearly_sorted(middle, next.end(), less);
  lane.memory.resize(next.size());
  std::merge(next.begin(), middle, middle, next.end(), lane.memory.begin(), less);
}

std::vector<ContactWorld::Memory>::const_iterator ContactWorld::remembered(Lane& lane,
                                                                           std::uint64_t key) {
  // Everything before `lo` is below key; gallop forward, then search the last stride.
  const std::vector<Memory>& memory = lane.memory;
  std::size_t lo = lane.cursor;
  if (lo > memory.size() || (lo > 0 && memory[lo - 1].key >= key)) lo = 0;
  std::size_t hi = lo, stride = 1;
  while (hi < memory.size() && memory[hi].key < key) {
    lo = hi + 1;
    hi += stride;
    stride *= 2;
  }
  hi = std::min(hi, memory.size());
  const auto found = std::lower_bound(memory.cbegin() + static_cast<std::ptrdiff_t>(lo),
                                      memory.cbegin() + static_cast<std::ptrdiff_t>(hi), key,
                                      [](const Memory& m, std::uint64_t k) { return m.key < k; });
  lane.cursor = static_cast<std::size_t>(found - memory.cbegin());
  return found;
}

void ContactWorld::match_features(std::int32_t shape_a, std::int32_t shape_b, ContactPoint* points,
                                  int count) {
  // FCL numbers its points by its own clipping order, which changes as the overlap changes:
  // give each point the id of the remembered point of this pair nearest to it (in a's frame),
  // so that friction memory follows the material point.
  const std::uint64_t prefix = pair_key(shape_a, static_cast<std::uint64_t>(shape_b), 0);
  Lane& lane = lane_of(shape_a);
  const auto first = remembered(lane, prefix);
  auto last = first;
  while (last != lane.memory.cend() && (last->key >> 16) == (prefix >> 16))
    ++last;
  const Pose inverse = placement_.world()[shape_a].inverse();
  const double tolerance =
      0.25 * table_.shapes()[static_cast<std::size_t>(shape_a)].bounding_radius_m;
  std::uint32_t taken = 0;  // bit per remembered point (at most 16 per pair)
  int next_free = 0;
  for (auto it = first; it != last; ++it)
    next_free = std::max(next_free, static_cast<int>(it->key & 0xffff) + 1);
  for (int i = 0; i < count; ++i) {
    const Vec3 local = inverse * points[i].point_m;
    int best = -1;
    double best_distance = tolerance;
    for (auto it = first; it != last && it - first < 32; ++it) {
      const int k = static_cast<int>(it - first);
      if (taken & (1u << k)) continue;
      const double d = norm(it->state.local_point_m - local);
      if (d < best_distance) best_distance = d, best = k;
    }
    if (best >= 0) {
      taken |= 1u << best;
      points[i].feature = static_cast<std::int32_t>((first + best)->key & 0xffff);
    } else {
      points[i].feature = next_free++;
    }
  }
}

void ContactWorld::add_point(Lane* part_lane, const Found& f, const Pose* poses,
                             const Twist* twists, double step_s, Wrench* wrenches) {
  const std::int32_t shape_a = f.shape_a, other = f.other;
  const bool other_is_plane = f.plane;
  const ContactPoint& p = f.point;
  const auto& surfaces = table_.surfaces();
  const auto& bodies = table_.bodies();
  const Pose* world = placement_.world();
  const auto ia = static_cast<std::size_t>(shape_a), ib = static_cast<std::size_t>(other);
  const Surface& a = surfaces[ia];
  const Surface* b = other_is_plane ? nullptr : &surfaces[ib];
  const std::int32_t body_a = bodies[ia], body_b = b ? bodies[ib] : 0;

  auto point_velocity = [&](std::int32_t body) {
    if (body == 0) return Vec3{};
    const Twist& t = twists[body];
    return t.linear_m_s + cross(t.angular_rad_s, p.point_m - poses[body].position);
  };
  // A conveyor's surface moves on its top face only (+Z of the belt); its sides and its
  // underside are the frame. `toward_other` is the normal pointing from the belt to the other.
  auto belt_velocity = [&](const Surface& s, std::size_t index, const Vec3& toward_other) {
    const std::int32_t input = belt_speed_input_[index];
    if (!s.belt || input < 0 || !inputs_) return Vec3{};
    const Mat3& r = world[index].rotation;
    if (dot(toward_other, r.column(2)) < kBeltTopCosine) return Vec3{};
    return r.column(0) * inputs_[input];
  };
  PointKinematics kin;
  kin.relative_velocity_m_s = point_velocity(body_a) + belt_velocity(a, ia, -p.normal) -
                              point_velocity(body_b) -
                              (b ? belt_velocity(*b, ib, p.normal) : Vec3{});
  PairMaterial scratch;
  const PairMaterial& material = pair_material(ia, ib, other_is_plane, scratch);
  if (material.anisotropic)
    kin.friction_axis = (material.anisotropy_on_a ? world[ia] : world[ib]).rotation.column(2);
  const Vec3 helper = std::abs(p.normal.x) < 0.9 ? Vec3{1, 0, 0} : Vec3{0, 1, 0};
  const Vec3 t1 = cross(p.normal, helper) / norm(cross(p.normal, helper));
  const Vec3 directions[3] = {p.normal, t1, cross(p.normal, t1)};
  double inverse_mass[3] = {0, 0, 0};
  inverse_masses(body_a, p.point_m, poses, directions, inverse_mass);
  inverse_masses(body_b, p.point_m, poses, directions, inverse_mass);
  kin.mass_kg = 1 / inverse_mass[0];
  kin.tangent_mass_kg = 1 / std::max(inverse_mass[1], inverse_mass[2]);
  kin.step_s = step_s;
  // The world's count gathers every point on the ground: only moving bodies share.
  kin.points_sharing =
      std::max({1, touching_points_[static_cast<std::size_t>(body_a)],
                body_b > 0 ? touching_points_[static_cast<std::size_t>(body_b)] : 0});

  kin.bounded_recovery = jointless_[body_a] && (body_b == 0 || jointless_[body_b]);

  const std::uint64_t other_id =
      other_is_plane ? static_cast<std::uint64_t>(table_.size()) + static_cast<std::uint64_t>(other)
                     : static_cast<std::uint64_t>(other);
  const std::uint64_t key = pair_key(shape_a, other_id, p.feature);
  Lane& lane = part_lane ? *part_lane : lane_of(shape_a);
  std::vector<ContactInfo>& infos = part_lane ? part_lane->info : info_;
  StopGraph& stops = part_lane ? part_lane->stops : stops_;
  const auto found = remembered(lane, key);
  const bool known = found != lane.memory.cend() && found->key == key;
  PointState state = known ? found->state : PointState{};
  // Speculative contact: a point not touching that cannot cross the gap within the step
  // leaves no trace; one that would is stopped at the surface but is not a contact (not in
  // info_). Its memory carries its approach speed to the impact's second half.
  PointRole role = PointRole::contact;
  const double last_hold_N = state.held_force_N;
  // A jointed body on a static surface, light across the normal: its friction is solved with
  // the axes (when there is room in the substep's list), else the force law's.
  model::FrictionPoints* friction = part_lane ? part_lane->friction : friction_;
  const bool solve_friction = friction && body_b == 0 && friction->count < friction->capacity &&
                              (material.mu1 > 0 || material.mu2 > 0) &&
                              kin.tangent_mass_kg < law_.solved_friction_mass_ratio * kin.mass_kg &&
                              !solved_friction_.empty() &&
                              solved_friction_[static_cast<std::size_t>(body_a)];
  double friction_load_N = -1;
  const Vec3 force = contact_force(p, material, kin, law_, !known, state, role,
                                   solve_friction ? &friction_load_N : nullptr);
  if (role == PointRole::apart) return;
  state.local_point_m = world[ia].inverse() * p.point_m;
  lane.next_memory.push_back({key, state});
  const auto memory_ref =
      static_cast<std::int32_t>((static_cast<std::size_t>(&lane - lanes_.data()) << kLaneShift) |
                                (lane.next_memory.size() - 1));
  Vec3 applied = force;
  if (role == PointRole::speculative || role == PointRole::impact) {
    // The normal part is a change of the point's closing speed, solved with the substep's
    // other stops and the resting points they reach (stop_graph.hpp); an impact's friction is
    // applied now.
    const double normal = dot(force, p.normal);
    stops.add_stop(body_a, body_b, p.point_m, p.normal, normal * step_s / kin.mass_kg);
    if (role == PointRole::speculative) return;
    applied = force - p.normal * normal;
  }

  Wrench& wa = wrenches[body_a];
  wa.force_N += applied;
  wa.torque_Nm += cross(p.point_m - poses[body_a].position, applied);
  if (body_b > 0) {
    Wrench& wb = wrenches[body_b];
    wb.force_N -= applied;
    wb.torque_Nm -= cross(p.point_m - poses[body_b].position, applied);
  }
  ContactInfo info;
  info.body_a = BodyHandle{body_a};
  info.body_b = BodyHandle{body_b};
  info.point_m = p.point_m;
  info.normal = p.normal;
  info.force_N = force;
  info.depth_m = std::max(p.depth_m, 0.0);  // an impact completed just short of the surface
  infos.push_back(info);
  if (part_lane) part_lane->info_rank.push_back(f.rank);
  if (friction_load_N >= 0) {
    model::FrictionPoint& fp = friction->points[friction->count++];
    fp.body = body_a;
    fp.point_m = p.point_m;
    fp.isotropic = !pyramid_directions(material, p.normal, kin.friction_axis, fp.direction[0],
                                       fp.direction[1]);
    if (fp.isotropic) {
      fp.direction[0] = directions[1];
      fp.direction[1] = directions[2];
    }
    fp.limit_N[0] = material.mu1 * friction_load_N;
    fp.limit_N[1] = (fp.isotropic ? material.mu1 : material.mu2) * friction_load_N;
    // The slip is a's point's velocity less the static side's material's (belts).
    fp.surface_velocity_m_s =
        (b ? belt_velocity(*b, ib, p.normal) : Vec3{}) - belt_velocity(a, ia, -p.normal);
    fp.report = static_cast<std::int32_t>(infos.size() - 1);
    fp.scene_index = -1;
    fp.force_N = Vec3{};
  }
  if (role == PointRole::contact && jointless_[body_a] && (body_b == 0 || jointless_[body_b]))
    stops.add_resting(body_a, body_b, -dot(kin.relative_velocity_m_s, p.normal),
                      p.depth_m > law_.hold_depth_m, static_cast<std::int32_t>(infos.size() - 1),
                      memory_ref, last_hold_N * step_s, held_recovery_speed(law_, p.depth_m));
}

}  // namespace s2sim::contact
