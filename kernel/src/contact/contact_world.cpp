#include "contact/contact_world.hpp"

#include "contact/primitives.hpp"

#include <algorithm>
#include <cmath>

namespace s2sim::contact {
namespace {

constexpr double kMaxApparentMass = 1e12;  // a body that cannot move (welded to the world)
constexpr double kBeltTopCosine = 0.7;     // contacts within 45° of the belt's +Z ride it

Shape make_shape(const scene::Geom& g, std::int32_t body) {
  Shape s;
  s.body = body;
  s.local = g.pose;
  switch (g.shape.type) {
    case scene::ShapeType::box:
      s.kind = ShapeKind::box;
      s.half_extents_m = g.shape.size_m * 0.5;
      s.bounding_radius_m = norm(s.half_extents_m);
      break;
    case scene::ShapeType::cylinder:
      s.kind = ShapeKind::cylinder;
      s.radius_m = g.shape.radius_m;
      s.half_length_m = 0.5 * g.shape.length_m;
      s.bounding_radius_m = std::hypot(s.radius_m, s.half_length_m);
      break;
    case scene::ShapeType::sphere:
      s.kind = ShapeKind::sphere;
      s.radius_m = g.shape.radius_m;
      s.bounding_radius_m = s.radius_m;
      break;
  }
  s.surface.has_mu = g.surface.explicit_surface && g.surface.mu >= 0;
  s.surface.mu = g.surface.mu;
  s.surface.mu2 = g.surface.mu2;
  s.surface.softness = g.surface.softness;
  s.surface.restitution = g.surface.bounce;
  s.surface.restitution_threshold_m_s = g.surface.bounce_threshold_m_s;
  if (s.surface.restitution > 0)
    s.surface.restitution_beta = restitution_beta(s.surface.restitution);
  switch (g.friction) {
    case scene::FrictionKind::isotropic:
      s.anisotropy = Anisotropy::none;
      break;
    case scene::FrictionKind::omni:
      s.anisotropy = Anisotropy::omni;
      break;
    case scene::FrictionKind::mecanum_left:
      s.anisotropy = Anisotropy::mecanum_left;
      break;
    case scene::FrictionKind::mecanum_right:
      s.anisotropy = Anisotropy::mecanum_right;
      break;
  }
  return s;
}

Aabb bounds(const Shape& s, const Pose& pose) {
  Vec3 e;
  const Mat3& r = pose.rotation;
  switch (s.kind) {
    case ShapeKind::box:
      e = {std::abs(r.m[0][0]) * s.half_extents_m.x + std::abs(r.m[0][1]) * s.half_extents_m.y +
               std::abs(r.m[0][2]) * s.half_extents_m.z,
           std::abs(r.m[1][0]) * s.half_extents_m.x + std::abs(r.m[1][1]) * s.half_extents_m.y +
               std::abs(r.m[1][2]) * s.half_extents_m.z,
           std::abs(r.m[2][0]) * s.half_extents_m.x + std::abs(r.m[2][1]) * s.half_extents_m.y +
               std::abs(r.m[2][2]) * s.half_extents_m.z};
      break;
    case ShapeKind::cylinder: {
      const Vec3 a = r.column(2);
      auto extent = [&](double ai) {
        return std::abs(ai) * s.half_length_m + s.radius_m * std::sqrt(std::max(0.0, 1 - ai * ai));
      };
      e = {extent(a.x), extent(a.y), extent(a.z)};
      break;
    }
    case ShapeKind::sphere:
      e = {s.radius_m, s.radius_m, s.radius_m};
      break;
  }
  return {pose.position - e, pose.position + e};
}

std::uint64_t pair_key(std::int32_t shape_a, std::uint64_t other_id, std::int32_t feature) {
  return (static_cast<std::uint64_t>(shape_a) << 40) | (other_id << 16) |
         static_cast<std::uint16_t>(feature);
}

std::uint64_t body_pair(std::int32_t a, std::int32_t b) {
  if (a > b) std::swap(a, b);
  return (static_cast<std::uint64_t>(a) << 32) | static_cast<std::uint32_t>(b);
}

}  // namespace

ContactWorld::ContactWorld(const scene::Scene& scene, const std::vector<double>& apparent_mass_kg,
                           const ForceLawSettings& law)
    : apparent_mass_kg_(apparent_mass_kg), default_mu_(scene.settings.default_friction), law_(law) {
  law_.erp = scene.settings.erp;
  for (std::size_t i = 0; i < scene.bodies.size(); ++i) {
    const auto& body = scene.bodies[i];
    for (std::size_t g = 0; g < body.geoms.size(); ++g) {
      Shape s = make_shape(body.geoms[g], static_cast<std::int32_t>(i + 1));
      s.belt = body.kind == scene::SolidKind::belt && g == 0;
      shapes_.push_back(s);
    }
  }
  for (const auto& obstacle : scene.obstacles)
    shapes_.push_back(make_shape(obstacle, 0));

  planes_.push_back({{0, 0, 1}, 0});  // the ground
  if (scene.settings.world_walls) {
    const double d = scene.settings.world_wall_distance_m;
    planes_.push_back({{1, 0, 0}, -d});
    planes_.push_back({{-1, 0, 0}, -d});
    planes_.push_back({{0, 1, 0}, -d});
    planes_.push_back({{0, -1, 0}, -d});
  }

  com_m_.assign(scene.bodies.size() + 1, Vec3{});
  inverse_inertia_.assign(scene.bodies.size() + 1, Mat3{});
  for (std::size_t i = 0; i < scene.bodies.size(); ++i) {
    com_m_[i + 1] = scene.bodies[i].com_m;
    inverse_inertia_[i + 1] = inverse(scene.bodies[i].inertia_kg_m2);
  }
  fixed_to_world_.assign(scene.bodies.size() + 1, 0);
  for (const auto& j : scene.joints) {
    if (j.body1 < 0 || j.body2 < 0) {
      fixed_to_world_[(j.body1 < 0 ? j.body2 : j.body1) + 1] = 1;
    } else {
      joined_pairs_.push_back(body_pair(j.body1 + 1, j.body2 + 1));
    }
  }
  std::sort(joined_pairs_.begin(), joined_pairs_.end());
  for (double& m : apparent_mass_kg_)
    if (!(m > 0) || !std::isfinite(m) || m > kMaxApparentMass) m = kMaxApparentMass;

  world_pose_.resize(shapes_.size());
  boxes_.resize(shapes_.size());
  for (std::size_t s = 0; s < shapes_.size(); ++s)
    if (shapes_[s].body == 0) {
      world_pose_[s] = shapes_[s].local;
      boxes_[s] = bounds(shapes_[s], world_pose_[s]);
    }
  broad_phase_.resize(static_cast<int>(shapes_.size()));
  const std::size_t reserve = 64 + 16 * shapes_.size();
  pairs_.reserve(reserve);
  memory_.reserve(reserve);
  next_memory_.reserve(reserve);
  info_.reserve(reserve);
}

std::vector<std::int32_t> ContactWorld::belt_bodies() const {
  std::vector<std::int32_t> out;
  for (const auto& s : shapes_)
    if (s.belt) out.push_back(s.body);
  return out;
}

void ContactWorld::set_belt_speed_input(std::int32_t body, std::int32_t input) {
  for (auto& s : shapes_)
    if (s.belt && s.body == body) s.belt_speed_input = input;
}

void ContactWorld::inverse_masses(std::int32_t body, const Vec3& point, const Pose* poses,
                                  const Vec3* directions, double* inverse_mass) const {
  // Along each direction d: 1/m + wᵀ I⁻¹ w with w = r × d in body axes. The body's own inertia
  // stands for its rotation, its apparent mass for its translation.
  if (body == 0) return;
  const Pose& pose = poses[body];
  const Mat3 rt = pose.rotation.transposed();
  const Vec3 r = rt * (point - pose.position) - com_m_[body];  // from the COM, body axes
  const double translation = 1 / apparent_mass_kg_[body];
  for (int k = 0; k < 3; ++k) {
    const Vec3 w = cross(r, rt * directions[k]);
    inverse_mass[k] += translation + dot(w, inverse_inertia_[body] * w);
  }
}

bool ContactWorld::excluded(std::int32_t body_a, std::int32_t body_b) const {
  if (body_a == body_b) return true;
  if (body_a == 0) return fixed_to_world_[body_b] != 0;
  if (body_b == 0) return fixed_to_world_[body_a] != 0;
  return std::binary_search(joined_pairs_.begin(), joined_pairs_.end(), body_pair(body_a, body_b));
}

void ContactWorld::reset() {
  memory_.clear();
  next_memory_.clear();
  info_.clear();
  info_count_ = 0;
  broad_phase_.resize(static_cast<int>(shapes_.size()));
}

void ContactWorld::compute(const Pose* poses, const Twist* twists, double step_s,
                           Wrench* wrenches) {
  const std::size_t body_count = apparent_mass_kg_.size();
  std::fill(wrenches, wrenches + body_count, Wrench{});
  for (std::size_t s = 0; s < shapes_.size(); ++s) {
    const Shape& shape = shapes_[s];
    if (shape.body == 0) continue;
    world_pose_[s] = poses[shape.body] * shape.local;
    boxes_[s] = bounds(shape, world_pose_[s]);
  }
  next_memory_.clear();
  info_.clear();

  ContactPoint points[kMaxPointsPerPair];
  // Moving shapes against the ground and the walls.
  for (std::size_t s = 0; s < shapes_.size(); ++s) {
    const Shape& shape = shapes_[s];
    if (shape.body == 0 || fixed_to_world_[shape.body]) continue;
    const Aabb& box = boxes_[s];
    const Vec3 center = (box.min + box.max) * 0.5, half = (box.max - box.min) * 0.5;
    for (std::size_t p = 0; p < planes_.size(); ++p) {
      const Plane& plane = planes_[p];
      const double reach = std::abs(plane.normal.x) * half.x + std::abs(plane.normal.y) * half.y +
                           std::abs(plane.normal.z) * half.z;
      if (dot(plane.normal, center) - reach >= plane.offset_m) continue;
      const int n = plane_contacts(shape, world_pose_[s], plane, points);
      for (int k = 0; k < n; ++k)
        add_point(static_cast<std::int32_t>(s), static_cast<std::int32_t>(p), true, points[k],
                  poses, twists, step_s, wrenches);
    }
  }
  // Shape pairs.
  broad_phase_.find_pairs(boxes_.data(), pairs_);
  for (const auto& [i, j] : pairs_) {
    const Shape& a = shapes_[i];
    const Shape& b = shapes_[j];
    if (excluded(a.body, b.body)) continue;
    // Shape a must move: a static shape is always b.
    const bool swap = a.body == 0;
    const std::int32_t ia = swap ? j : i, ib = swap ? i : j;
    const Shape& sa = shapes_[ia];
    const Shape& sb = shapes_[ib];
    const Pose& pa = world_pose_[ia];
    const Pose& pb = world_pose_[ib];
    int n = 0;
    if (sa.kind == ShapeKind::sphere && sb.kind == ShapeKind::sphere) {
      n = sphere_sphere(sa.radius_m, pa.position, sb.radius_m, pb.position, points);
    } else if (sa.kind == ShapeKind::sphere && sb.kind == ShapeKind::box) {
      n = sphere_box(sa.radius_m, pa.position, sb.half_extents_m, pb, points);
    } else if (sa.kind == ShapeKind::box && sb.kind == ShapeKind::sphere) {
      n = sphere_box(sb.radius_m, pb.position, sa.half_extents_m, pa, points);
      swap_roles(points, n);
    } else {
      n = fcl_.collide(sa, pa, sb, pb, points);
      match_features(ia, ib, points, n);
    }
    for (int k = 0; k < n; ++k)
      add_point(ia, ib, false, points[k], poses, twists, step_s, wrenches);
  }
  std::sort(next_memory_.begin(), next_memory_.end(),
            [](const Memory& x, const Memory& y) { return x.key < y.key; });
  memory_.swap(next_memory_);
  info_count_ = static_cast<std::int32_t>(info_.size());
}

void ContactWorld::match_features(std::int32_t shape_a, std::int32_t shape_b, ContactPoint* points,
                                  int count) const {
  // FCL numbers its points by its own clipping order, which changes as the overlap changes:
  // give each point the id of the remembered point of this pair nearest to it (in a's frame),
  // so that friction memory follows the material point.
  const std::uint64_t prefix = pair_key(shape_a, static_cast<std::uint64_t>(shape_b), 0);
  auto first = std::lower_bound(memory_.begin(), memory_.end(), prefix,
                                [](const Memory& m, std::uint64_t k) { return m.key < k; });
  auto last = first;
  while (last != memory_.end() && (last->key >> 16) == (prefix >> 16))
    ++last;
  const Pose inverse = world_pose_[shape_a].inverse();
  const double tolerance = 0.25 * shapes_[shape_a].bounding_radius_m;
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

void ContactWorld::add_point(std::int32_t shape_a, std::int32_t other, bool other_is_plane,
                             const ContactPoint& p, const Pose* poses, const Twist* twists,
                             double step_s, Wrench* wrenches) {
  const Shape& a = shapes_[shape_a];
  const Shape* b = other_is_plane ? nullptr : &shapes_[other];
  const std::int32_t body_a = a.body, body_b = b ? b->body : 0;

  auto point_velocity = [&](std::int32_t body) {
    if (body == 0) return Vec3{};
    const Twist& t = twists[body];
    return t.linear_m_s + cross(t.angular_rad_s, p.point_m - poses[body].position);
  };
  // A conveyor's surface moves on its top face only (+Z of the belt); its sides and its
  // underside are the frame. `toward_other` is the normal pointing from the belt to the other.
  auto belt_velocity = [&](const Shape& s, std::int32_t index, const Vec3& toward_other) {
    if (!s.belt || s.belt_speed_input < 0 || !inputs_) return Vec3{};
    const Mat3& r = world_pose_[index].rotation;
    if (dot(toward_other, r.column(2)) < kBeltTopCosine) return Vec3{};
    return r.column(0) * inputs_[s.belt_speed_input];
  };
  PointKinematics kin;
  kin.relative_velocity_m_s = point_velocity(body_a) + belt_velocity(a, shape_a, -p.normal) -
                              point_velocity(body_b) -
                              (b ? belt_velocity(*b, other, p.normal) : Vec3{});
  const PairMaterial material = combine_surfaces(a, b, default_mu_);
  if (material.anisotropic)
    kin.friction_axis =
        (material.anisotropy_on_a ? world_pose_[shape_a] : world_pose_[other]).rotation.column(2);
  const Vec3 helper = std::abs(p.normal.x) < 0.9 ? Vec3{1, 0, 0} : Vec3{0, 1, 0};
  const Vec3 t1 = cross(p.normal, helper) / norm(cross(p.normal, helper));
  const Vec3 directions[3] = {p.normal, t1, cross(p.normal, t1)};
  double inverse_mass[3] = {0, 0, 0};
  inverse_masses(body_a, p.point_m, poses, directions, inverse_mass);
  inverse_masses(body_b, p.point_m, poses, directions, inverse_mass);
  kin.mass_kg = 1 / inverse_mass[0];
  kin.tangent_mass_kg = 1 / std::max(inverse_mass[1], inverse_mass[2]);
  kin.step_s = step_s;

  const std::uint64_t other_id = other_is_plane ? shapes_.size() + static_cast<std::uint64_t>(other)
                                                : static_cast<std::uint64_t>(other);
  const std::uint64_t key = pair_key(shape_a, other_id, p.feature);
  auto found = std::lower_bound(memory_.begin(), memory_.end(), key,
                                [](const Memory& m, std::uint64_t k) { return m.key < k; });
  const bool known = found != memory_.end() && found->key == key;
  PointState state = known ? found->state : PointState{};
  const Vec3 force = contact_force(p, material, kin, law_, !known, state);
  state.local_point_m = world_pose_[shape_a].inverse() * p.point_m;
  next_memory_.push_back({key, state});

  Wrench& wa = wrenches[body_a];
  wa.force_N += force;
  wa.torque_Nm += cross(p.point_m - poses[body_a].position, force);
  if (body_b > 0) {
    Wrench& wb = wrenches[body_b];
    wb.force_N -= force;
    wb.torque_Nm -= cross(p.point_m - poses[body_b].position, force);
  }
  ContactInfo info;
  info.body_a = BodyHandle{body_a};
  info.body_b = BodyHandle{body_b};
  info.point_m = p.point_m;
  info.normal = p.normal;
  info.force_N = force;
  info.depth_m = p.depth_m;
  info_.push_back(info);
}

void ContactWorld::save(std::vector<double>& out) const {
  out.push_back(static_cast<double>(memory_.size()));
  for (const auto& m : memory_) {
    out.push_back(static_cast<double>(m.key >> 32));
    out.push_back(static_cast<double>(m.key & 0xffffffffu));
    out.push_back(m.state.bristle_m.x);
    out.push_back(m.state.bristle_m.y);
    out.push_back(m.state.bristle_m.z);
    out.push_back(m.state.approach_speed_m_s);
    out.push_back(m.state.local_point_m.x);
    out.push_back(m.state.local_point_m.y);
    out.push_back(m.state.local_point_m.z);
  }
}

std::size_t ContactWorld::restore(const std::vector<double>& in, std::size_t offset) {
  const auto count = static_cast<std::size_t>(in.at(offset++));
  memory_.clear();
  for (std::size_t i = 0; i < count; ++i) {
    Memory m;
    m.key = (static_cast<std::uint64_t>(in.at(offset)) << 32) |
            static_cast<std::uint64_t>(in.at(offset + 1));
    m.state.bristle_m = {in.at(offset + 2), in.at(offset + 3), in.at(offset + 4)};
    m.state.approach_speed_m_s = in.at(offset + 5);
    m.state.local_point_m = {in.at(offset + 6), in.at(offset + 7), in.at(offset + 8)};
    offset += 9;
    memory_.push_back(m);
  }
  info_.clear();
  info_count_ = 0;
  return offset;
}

}  // namespace s2sim::contact
