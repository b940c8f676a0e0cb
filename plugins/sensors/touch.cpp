/// `touch` (a bumper): 1 when the contacts of the last physics step on the sensor's body,
/// optionally only those inside `<region x y z>` (a box of that size centred on the sensor
/// frame), push with more than `<threshold value>` newtons in total; `force` is that total.
#include "kinds.hpp"

namespace s2sim::sensors {

void Touch::configure(ConfigureContext& ctx) {
  ctx.declare_local();  // its own body (and joint): stepped in that body's part
  s_.read(ctx);
  s_.schedule(ctx);
  const Params& p = ctx.params();
  if (s_.body.index <= 0) fail(p, "solid", "id", "a touch sensor must be attached to a body");
  region_ = p.has_element("region");
  if (region_) {
    const Vec3 size = p.vec3("region", {0, 0, 0});
    if (!(size.x > 0 && size.y > 0 && size.z > 0))
      fail(p, "region", "x", "the region's x, y, z must be > 0 m");
    half_ = size * 0.5;
  }
  threshold_N_ = p.number("threshold.value", 0.0, Range::non_negative());
  value_ = ctx.declare_signal("value", "1");
  force_ = ctx.declare_signal("force", "N");
}

void Touch::update(StepContext& ctx) {
  const Pose w = s_.world_pose(ctx);
  const Pose inv = w.inverse();
  double total = 0;
  const int n = ctx.contact_count();
  for (int i = 0; i < n; ++i) {
    const ContactInfo& c = ctx.contact(i);
    if (c.body_a.index != s_.body.index && c.body_b.index != s_.body.index) continue;
    if (region_) {
      const Vec3 q = inv * c.point_m;
      if (std::abs(q.x) > half_.x || std::abs(q.y) > half_.y || std::abs(q.z) > half_.z) continue;
    }
    total += norm(c.force_N);
  }
  RandomStream r = ctx.random();
  ctx.publish(force_, total);
  ctx.publish(value_, s_.noise.apply(r, total > threshold_N_ ? 1.0 : 0.0));
}

}  // namespace s2sim::sensors
