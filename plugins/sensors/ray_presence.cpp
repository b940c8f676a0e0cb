/// `capacitive`, `inductive`, `RFID` (simtwo-format.md §4.11): one ray, a yes/no or a code.
#include "kinds.hpp"

#include <cstdlib>
#include <string>

namespace s2sim::sensors {

namespace {
/// The integer value of an ID (Pascal StrToIntDef(ID, 0)): a whole decimal, else 0.
double id_code(const std::string& id) {
  if (id.empty()) return 0;
  char* end = nullptr;
  const long long v = std::strtoll(id.c_str(), &end, 10);
  return (end && *end == '\0') ? static_cast<double>(v) : 0.0;
}
}  // namespace

void RayPresence::configure(ConfigureContext& ctx) {
  s_.read(ctx);
  s_.schedule(ctx);
  value_ = ctx.declare_signal("value", "1");
  if (mode_ == Mode::rfid) {
    rfid_code_.assign(static_cast<std::size_t>(ctx.body_count()), 0.0);
    for (int b = 1; b < ctx.body_count(); ++b)
      rfid_code_[static_cast<std::size_t>(b)] = id_code(ctx.body_id(BodyHandle{b}));
  }
}

void RayPresence::update(StepContext& ctx) {
  const Pose w = s_.world_pose(ctx);
  const RayHit h = ctx.cast_ray(w.position, w.rotation.column(0), s_.spec.beam.length_m, s_.ignore);
  double v = 0;
  if (h.hit) {
    switch (mode_) {
      case Mode::capacitive:
        v = 1;
        break;
      case Mode::inductive:
        v = (h.material & material_metallic) ? 1 : 0;
        break;
      case Mode::rfid:
        v = ((h.material & material_rfid_tag) && h.body.index > 0)
                ? rfid_code_[static_cast<std::size_t>(h.body.index)]
                : 0;
        break;
    }
  }
  RandomStream r = ctx.random();
  ctx.publish(value_, s_.noise.apply(r, v));
}

}  // namespace s2sim::sensors
