/// `spraygun` (simtwo-format.md §4.11; docs/models/sensors.md, "Spray painting"): while its
/// input `on` is 1, paints every painting target of the scene (ConfigureContext::
/// painting_targets) by the model of spray_model.hpp, each triangle's thickness in the
/// target's body frame, so that the paint moves with the body. Every triangle's thickness of
/// this gun's paint is its state (a reset and a snapshot are exact) and its signal
/// `paint/<k>/<t>` (metres, target k, triangle t): a target's paint is the sum over the guns.
/// `paint_targets/<k>/resets`, an input every gun joins, clears target k when it changes
/// (SimTwo's ResetPaintTargetPaint); `paint/<k>/resets` says which request a gun carried out.
#include "kinds.hpp"
#include "spray_model.hpp"

#include <limits>
#include <string>

namespace s2sim::sensors {

namespace {

/// Below this solid angle a triangle takes no paint (a degenerate or edge-on one).
constexpr double kTinySolidAngle_sr = 1e-15;
/// A ray that stops this short of the triangle's centre (relative to the distance, plus an
/// absolute part) met something in front of it.
constexpr double kOcclusionSlack = 1e-6;
constexpr double kOcclusionSlack_m = 1e-6;

}  // namespace

void SprayGun::read_paint(ConfigureContext& ctx) {
  const Params& p = ctx.params();
  // SimTwo's defaults (simtwo-format.md §4.11); the getters locate a bad value.
  rate_m3_s_ = p.number("paint_rate.value", 0.01, Range::non_negative());
  max_angle_rad_ = p.number("paint_max_angle.value", 0.2, Range{0, kPi / 2, true, false});
  sigma_rad_ = max_angle_rad_ / 2;
  cos_max_ = std::cos(max_angle_rad_);
  per_sr_ = 1 / spray::cone_weight(max_angle_rad_, sigma_rad_);
  occlusion_ = p.boolean("paint_occlusion.value", false);
  const bool on = p.boolean("paint_default_on.value", false);
  on_ = ctx.declare_input("on", "1", on ? 1.0 : 0.0, Range::unit_interval());
  // Red without the element; with it, a channel it does not give is SimTwo's 0, 0, 255.
  const bool has_color = p.has_element("paint_color_rgb");
  const char* channel[3] = {"paint_color_rgb.r", "paint_color_rgb.g", "paint_color_rgb.b"};
  const double fallback[3] = {has_color ? 0.0 : 255.0, 0, has_color ? 255.0 : 0.0};
  const char* name[3] = {"paint_color/r", "paint_color/g", "paint_color/b"};
  for (int i = 0; i < 3; ++i) {
    color_[i] = p.number(channel[i], fallback[i], Range{0, 255}) / 255;
    color_sig_[i] = ctx.declare_signal(name[i], "1");
  }
}

void SprayGun::configure(ConfigureContext& ctx) {
  s_.read(ctx);
  s_.schedule(ctx);
  read_paint(ctx);
  volume_ = ctx.declare_signal("volume", "m^3");
  min_dist_ = ctx.declare_signal("min_dist", "m");
  const std::vector<PaintingTarget> targets = ctx.painting_targets();
  for (std::size_t k = 0; k < targets.size(); ++k) {
    const PaintingTarget& pt = targets[k];
    const std::string key = std::to_string(k);
    Target t;
    t.body = pt.body;
    t.first = static_cast<int>(triangles_.size());
    t.count = static_cast<int>(pt.vertices_m.size() / 3);
    t.resets =
        ctx.declare_input_at("paint_targets/" + key + "/resets", "1", 0, Range::non_negative());
    t.resets_seen = ctx.declare_signal("paint/" + key + "/resets", "1");
    for (int i = 0; i < t.count; ++i) {
      Triangle tri;
      tri.a = pt.vertices_m[static_cast<std::size_t>(3 * i)];
      tri.b = pt.vertices_m[static_cast<std::size_t>(3 * i + 1)];
      tri.c = pt.vertices_m[static_cast<std::size_t>(3 * i + 2)];
      tri.centre = (tri.a + tri.b + tri.c) * (1.0 / 3);
      const Vec3 n = cross(tri.b - tri.a, tri.c - tri.a);
      const double twice_area = norm(n);
      tri.area_m2 = twice_area / 2;
      tri.normal = twice_area > 0 ? n * (1 / twice_area) : Vec3{};
      triangles_.push_back(tri);
      thickness_sig_.push_back(ctx.declare_signal("paint/" + key + "/" + std::to_string(i), "m"));
    }
    targets_.push_back(t);
  }
  if (targets_.empty()) {
    ctx.warn(
        "the scene has no painting target (<painting_target/> on a solid with a <mesh>): "
        "the gun paints nothing");
    return;
  }
  thickness_ = ctx.declare_state("thickness", static_cast<int>(triangles_.size()), 0.0);
  resets_done_ = ctx.declare_state("resets_done", static_cast<int>(targets_.size()), 0.0);
}

void SprayGun::initialize(StepContext& ctx) {
  for (int i = 0; i < 3; ++i)
    ctx.publish(color_sig_[i], color_[i]);
  publish_all(ctx);
}

bool SprayGun::occluded(StepContext& ctx, const Vec3& nozzle, const Vec3& to, double distance,
                        BodyHandle target) const {
  const RayHit h = ctx.cast_ray(nozzle, to * (1 / distance), distance, s_.ignore);
  if (!h.hit) return false;
  // The target's own collision shape stands for its mesh (which rays do not see); on an
  // obstacle (the world) only what stops short of the triangle is in front of it.
  if (target.index > 0 && h.body.index == target.index) return false;
  return h.distance_m < distance * (1 - kOcclusionSlack) - kOcclusionSlack_m;
}

void SprayGun::publish_all(StepContext& ctx) {
  double nearest = std::numeric_limits<double>::infinity();
  double volume = 0;
  const Vec3 nozzle = s_.world_pose(ctx).position;
  if (!targets_.empty()) {
    const Span<double> thickness = ctx.state(thickness_);
    const Span<double> done = ctx.state(resets_done_);
    for (std::size_t k = 0; k < targets_.size(); ++k) {
      const Target& t = targets_[k];
      const Pose& body = ctx.body_pose(t.body);
      ctx.publish(t.resets_seen, done[k]);
      for (int i = t.first; i < t.first + t.count; ++i) {
        const Triangle& tri = triangles_[static_cast<std::size_t>(i)];
        nearest = std::min(nearest, norm(body * tri.centre - nozzle));
        volume += thickness[static_cast<std::size_t>(i)] * tri.area_m2;
        ctx.publish(thickness_sig_[static_cast<std::size_t>(i)],
                    thickness[static_cast<std::size_t>(i)]);
      }
    }
  }
  ctx.publish(volume_, volume);
  ctx.publish(min_dist_, targets_.empty() ? -1.0 : nearest);
}

void SprayGun::update(StepContext& ctx) {
  if (targets_.empty()) {
    publish_all(ctx);
    return;
  }
  const Span<double> thickness = ctx.state(thickness_);
  const Span<double> done = ctx.state(resets_done_);
  // Resets first: a request made before this tick clears the paint before the gun sprays.
  for (std::size_t k = 0; k < targets_.size(); ++k) {
    const Target& t = targets_[k];
    const double asked = ctx.input(t.resets);
    if (asked == done[k]) continue;
    for (int i = t.first; i < t.first + t.count; ++i)
      thickness[static_cast<std::size_t>(i)] = 0;
    done[k] = asked;
  }
  if (ctx.input(on_) > 0.5 && rate_m3_s_ > 0) {
    const Pose gun = s_.world_pose(ctx);
    const Vec3 nozzle = gun.position;
    const Vec3 axis = gun.rotation.column(0);                   // the beam, the sensor frame's +X
    const double dose = rate_m3_s_ * per_sr_ * ctx.period_s();  // m³ per sr at the beam
    for (const Target& t : targets_) {
      const Pose& body = ctx.body_pose(t.body);
      for (int i = t.first; i < t.first + t.count; ++i) {
        const Triangle& tri = triangles_[static_cast<std::size_t>(i)];
        if (!(tri.area_m2 > 0)) continue;
        const Vec3 to = body * tri.centre - nozzle;
        const double r = norm(to);
        if (!(r > 0) || dot(axis, to) < cos_max_ * r) continue;  // outside the cone
        if (dot(body.rotation * tri.normal, to) >= 0) continue;  // its back to the nozzle
        const double omega =
            spray::solid_angle(body * tri.a - nozzle, body * tri.b - nozzle, body * tri.c - nozzle);
        if (!(omega > kTinySolidAngle_sr)) continue;
        if (occlusion_ && occluded(ctx, nozzle, to, r, t.body)) continue;
        const double theta = spray::angle_off(axis, to, r);
        thickness[static_cast<std::size_t>(i)] +=
            dose * spray::profile(theta, sigma_rad_) * omega / tri.area_m2;
      }
    }
  }
  publish_all(ctx);
}

}  // namespace s2sim::sensors
