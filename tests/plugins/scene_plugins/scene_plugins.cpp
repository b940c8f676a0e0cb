// Components used by the simulation tests, built exactly like a third-party plugin: against
// the SDK headers alone, loaded from a scene by kind name.
#include <s2sim/sdk.hpp>

#include <algorithm>
#include <string>
#include <vector>

namespace {

using namespace s2sim;

// A torsion spring on an axis: torque = -k (q - zero). Reads typed, ranged parameters.
class AxisSpring : public Component {
 public:
  void configure(ConfigureContext& ctx) override {
    const Params& p = ctx.params();
    axis_ = ctx.axis(p.text("axis"));
    stiffness_ = p.number("stiffness", Range::positive());
    zero_rad_ = p.number("zero_deg", 0.0) * kPi / 180.0;
    torque_ = ctx.declare_signal("torque", ctx.axis_is_linear(axis_) ? "N" : "N*m");
  }
  void update(StepContext& ctx) override {
    const double t = -stiffness_ * (ctx.axis_position(axis_) - zero_rad_);
    ctx.apply_axis_force(axis_, t);
    ctx.publish(torque_, t);
  }

 private:
  AxisHandle axis_;
  double stiffness_ = 0, zero_rad_ = 0;
  SignalHandle torque_;
};

// Sets an input to `value` times its update count, on its own period and phase.
class ReferenceController : public Component {
 public:
  void configure(ConfigureContext& ctx) override {
    const Params& p = ctx.params();
    input_ = ctx.declare_input_at(p.text("input"), p.text("unit", "1"), 0.0);
    value_ = p.number("value", 1.0);
    ctx.set_schedule(Stage::control, p.number("period_ms", 40.0) / 1000.0,
                     p.number("phase_ms", 0.0) / 1000.0);
    updates_state_ = ctx.declare_state("updates", 1, 0.0);
    updates_ = ctx.declare_signal("updates", "1");
  }
  void update(StepContext& ctx) override {
    double& n = ctx.state(updates_state_)[0];
    n += 1;
    ctx.set_input(input_, value_ * n);
    ctx.publish(updates_, n);
  }

 private:
  InputHandle input_;
  double value_ = 1;
  StateHandle updates_state_;
  SignalHandle updates_;
};

// Publishes the value of an input as it sees it in its stage (actuator or sensor kind).
class Echo : public Component {
 public:
  void configure(ConfigureContext& ctx) override {
    input_ = ctx.declare_input_at(ctx.params().text("input"), ctx.params().text("unit", "1"), 0.0);
    seen_ = ctx.declare_signal("seen", "1");
  }
  void update(StepContext& ctx) override { ctx.publish(seen_, ctx.input(input_)); }

 private:
  InputHandle input_;
  SignalHandle seen_;
};

// Gaussian noise from the component's own random stream.
class Noise : public Component {
 public:
  void configure(ConfigureContext& ctx) override {
    value_ = ctx.declare_signal("value", "1");
    stdev_ = ctx.params().number("stdev", 1.0, Range::non_negative());
  }
  void update(StepContext& ctx) override { ctx.publish(value_, ctx.random().normal(0, stdev_)); }

 private:
  SignalHandle value_;
  double stdev_ = 1;
};

// Pushes a body with a constant world force at a point given in the body frame.
class BodyPush : public Component {
 public:
  void configure(ConfigureContext& ctx) override {
    const Params& p = ctx.params();
    body_ = ctx.body(p.text("solid"));
    force_ = p.vec3("force");
    point_ = p.vec3("point");
  }
  void update(StepContext& ctx) override {
    ctx.apply_force(body_, force_, ctx.body_pose(body_) * point_);
  }

 private:
  BodyHandle body_;
  Vec3 force_, point_;
};

// SDK 0.10: at its first update at or after `at_s`, moves `solid` to `position` (its rotation
// kept) with StepContext::request_move, then sets its velocity with request_velocity.
class BodyMover : public Component {
 public:
  void configure(ConfigureContext& ctx) override {
    const Params& p = ctx.params();
    body_ = ctx.body(p.text("solid"));
    at_s_ = p.number("at_s");
    position_ = p.vec3("position");
    twist_ = {p.vec3("angular"), p.vec3("linear")};
    done_ = ctx.declare_state("done", 1, 0.0);
  }
  void update(StepContext& ctx) override {
    double& done = ctx.state(done_)[0];
    if (done != 0 || ctx.time_s() < at_s_ - 1e-12) return;
    done = 1;
    Pose pose = ctx.body_pose(body_);
    pose.position = position_;
    ctx.request_move(body_, pose);
    ctx.request_velocity(body_, twist_);
  }

 private:
  BodyHandle body_;
  double at_s_ = 0;
  Vec3 position_;
  Twist twist_;
  StateHandle done_;
};

// SDK 0.7: finds signals and inputs by name. Publishes how many signals match `signals`, the
// values of `time` and of `read` as it reads them, and sets the existing input `input` to
// `value` (never declaring it).
class NameReader : public Component {
 public:
  void configure(ConfigureContext& ctx) override {
    const Params& p = ctx.params();
    matched_count_ = static_cast<double>(ctx.signal_names(p.text("signals")).size());
    inputs_matched_ = static_cast<double>(ctx.input_names(p.text("signals")).size());
    time_ = ctx.signal_reader("time");
    read_ = ctx.signal_reader(p.text("read"));
    input_ = ctx.input(p.text("input"));
    value_ = p.number("value");
    matched_ = ctx.declare_signal("matched", "1");
    matched_inputs_ = ctx.declare_signal("matched_inputs", "1");
    time_read_ = ctx.declare_signal("time_read", "s");
    value_read_ = ctx.declare_signal("value_read", "1");
  }
  void initialize(StepContext& ctx) override {
    ctx.publish(matched_, matched_count_);
    ctx.publish(matched_inputs_, inputs_matched_);
  }
  void update(StepContext& ctx) override {
    ctx.publish(time_read_, ctx.signal(time_));
    ctx.publish(value_read_, ctx.signal(read_));
    ctx.set_input(input_, value_);
  }

 private:
  double matched_count_ = 0, inputs_matched_ = 0, value_ = 0;
  SignalReader time_, read_;
  InputHandle input_;
  SignalHandle matched_, matched_inputs_, time_read_, value_read_;
};

// SDK 0.9: publishes for the people watching, on every update: a log line "update N", its HUD
// text "updates N", a trail point (t, 0, 0) on trail 0 and an XY point (t, 2t) on series 1;
// every `clear_every`-th update clears the trail.
class Annotator : public Component {
 public:
  void configure(ConfigureContext& ctx) override {
    clear_every_ = static_cast<int>(ctx.params().number("clear_every", 0.0));
    padding_ = static_cast<std::size_t>(ctx.params().number("line_bytes", 0.0));
    ctx.set_schedule(Stage::control, ctx.params().number("period_ms", 10.0) / 1000.0, 0.0);
  }
  void initialize(StepContext&) override { updates_ = 0; }
  void update(StepContext& ctx) override {
    ++updates_;
    ctx.log_line("update " + std::to_string(updates_) + std::string(padding_, 'x'));
    ctx.set_hud_text("updates " + std::to_string(updates_) + std::string(padding_, 'x'));
    if (clear_every_ > 0 && updates_ % clear_every_ == 0) ctx.clear_trail(0);
    ctx.add_trail_point(0, Vec3{ctx.time_s(), 0, 0});
    ctx.add_xy_point(1, ctx.time_s(), 2 * ctx.time_s());
  }

 private:
  int clear_every_ = 0;
  int updates_ = 0;
  std::size_t padding_ = 0;  // bytes added to each line and HUD text (line_bytes)
};

// SDK 0.11: a local component (ConfigureContext::declare_local). A speed controller on the
// axes `axes` (space-separated names) that reads the published signal `reads` (e.g. its
// encoder's count) and sets each axis's `ref_voltage` input to gain * (ref - speed), or, with
// `act`, does what a local component may not: `ray` casts a ray, `log` logs a line, `move`
// asks to move the axis's body... `stray_drive` applies a drive to axis index `stray_axis`,
// which it did not look up. `local='0'` leaves the declaration out; `reader` names any signal it
// reads through a SignalReader (published as `seen` too). With `body`, it publishes
// `touch`, the vertical contact force on that body summed over the last step's contacts.
class LocalController : public Component {
 public:
  void configure(ConfigureContext& ctx) override {
    const Params& p = ctx.params();
    if (p.number("local", 1.0) != 0.0) ctx.declare_local();
    std::string names = p.text("axes");
    for (std::size_t at = 0; at < names.size();) {
      const std::size_t end = std::min(names.find(' ', at), names.size());
      if (end > at) {
        const AxisHandle axis = ctx.axis(names.substr(at, end - at));
        axes_.push_back(axis);
        refs_.push_back(ctx.input(ctx.axis_prefix(axis) + "/ref_voltage"));
      }
      at = end + 1;
    }
    if (p.has("reads")) reads_ = ctx.published_signal(p.text("reads"));
    if (p.has("reader")) reader_ = ctx.signal_reader(p.text("reader"));
    if (p.has("body")) body_ = ctx.body(p.text("body"));
    gain_ = p.number("gain", 1.0);
    ref_ = p.number("ref", 5.0);
    act_ = p.text("act", "none");
    stray_axis_ = static_cast<std::int32_t>(p.number("stray_axis", 0.0));
    seen_ = ctx.declare_signal("seen", "1");
    touch_ = ctx.declare_signal("touch", "N");
    ctx.set_schedule(Stage::control, p.number("period_ms", 10.0) / 1000.0);
  }
  void update(StepContext& ctx) override {
    for (std::size_t k = 0; k < axes_.size(); ++k)
      ctx.set_input(refs_[k], gain_ * (ref_ - ctx.axis_velocity(axes_[k])));
    if (reads_.index >= 0) ctx.publish(seen_, ctx.signal(reads_));
    if (reader_.read) ctx.publish(seen_, ctx.signal(reader_));
    if (body_.index > 0) {  // the contact force on its body, from the last step's contacts
      Vec3 sum;
      for (int i = 0; i < ctx.contact_count(); ++i) {
        const ContactInfo& c = ctx.contact(i);
        if (c.body_a.index == body_.index) sum += c.force_N;
        if (c.body_b.index == body_.index) sum -= c.force_N;
      }
      ctx.publish(touch_, sum.z);
    }
    if (ctx.time_s() < 0.05) return;
    if (act_ == "ray") ctx.cast_ray(Vec3{0, 0, 1}, Vec3{0, 0, -1}, 2.0);
    if (act_ == "log") ctx.log_line("hello");
    if (act_ == "move") ctx.request_move(body_, ctx.body_pose(body_));
    if (act_ == "stray_drive") ctx.apply_axis_drive(AxisHandle{stray_axis_}, 0.0, 0.0);
  }

 private:
  std::vector<AxisHandle> axes_;
  std::vector<InputHandle> refs_;
  SignalHandle reads_;
  SignalReader reader_;
  BodyHandle body_;
  double gain_ = 1, ref_ = 5;
  std::string act_;
  std::int32_t stray_axis_ = 0;
  SignalHandle seen_, touch_;
};

}  // namespace

S2SIM_PLUGIN("s2sim_test_scene_plugins",
             S2SIM_KIND("test_axis_spring", Category::actuator, AxisSpring),
             S2SIM_KIND("test_reference_controller", Category::controller, ReferenceController),
             S2SIM_KIND("test_echo_actuator", Category::actuator, Echo),
             S2SIM_KIND("test_echo_sensor", Category::sensor, Echo),
             S2SIM_KIND("test_noise", Category::sensor, Noise),
             S2SIM_KIND("test_body_push", Category::body, BodyPush),
             S2SIM_KIND("test_body_mover", Category::actuator, BodyMover),
             S2SIM_KIND("test_name_reader", Category::controller, NameReader),
             S2SIM_KIND("test_annotator", Category::controller, Annotator),
             S2SIM_KIND("test_local_controller", Category::controller, LocalController))
