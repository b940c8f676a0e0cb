// The `pascal_script` controller: a SimTwo project's `control.pas`, compiled with Free Pascal
// (compiler.cpp), loaded (script_library.cpp) and called as SimTwo calls it: references
// zeroed and encoders counted at every script tick, `Initialize` then `Control` at the first,
// `Control` at the later ones, every script period from T − dt (simtwo-script-api.md §1.3).
// The host functions the support unit forwards here are dispatched in `call()`.
#include "compiler.hpp"
#include "host_ids.hpp"
#include "io_ports.hpp"
#include "script_library.hpp"
#include "sheet.hpp"

#include <s2sim/sdk.hpp>

#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <deque>
#include <memory>
#include <string>
#include <vector>

namespace s2sim::pascal {
namespace {

constexpr int kMaxNumbers = 4096;  // a host function's numeric result (ranger rays...)

/// Virtual-key codes the viewer can press: the input `keyboard/<code>` is 1 while held.
constexpr int kKeyCodes[] = {9, 13, 27, 32, 33, 34, 37, 38, 39, 40};

struct AxisRef {
  std::string path;  // empty for a Fixed or Ball joint (SimTwo gives it an index too)
  AxisHandle axis;
  bool linear = false;
  InputHandle ref_voltage, ref_speed, ref_pos, ref_torque, controller_active;
  SignalHandle encoder{-1}, current{-1}, voltage{-1};
};

struct SensorRef {
  std::string id, kind, prefix;
  SignalHandle value{-1};
  std::vector<SignalHandle> rays;  // a ranger's rays; empty otherwise
  InputHandle vin{-1};
};

struct SolidRef {
  std::string id;
  BodyHandle body;
};

struct RobotRef {
  std::string id;
  BodyHandle main;
  Vec3 origin, offset;
  double yaw = 0;
  Pose main_load_pose;  // read at the first initialize()
  std::vector<SolidRef> solids;
  std::vector<AxisRef> axes;
  std::vector<int> sensors;  // indices into global sensors
  std::vector<std::string> shell_tags;
};

struct ThingRef {
  std::string id;
  BodyHandle body;
  double rgba[4] = {0, 0, 0, 0};
};

/// Rotation about world Z.
Mat3 rot_z(double a) {
  const double c = std::cos(a), s = std::sin(a);
  return Mat3{{{c, -s, 0}, {s, c, 0}, {0, 0, 1}}};
}

class ScriptController final : public Component {
 public:
  void configure(ConfigureContext& ctx) override;
  void initialize(StepContext& ctx) override;
  void update(StepContext& ctx) override;

  // The host table's entries (static trampolines to the object).
  static double host_call(void* host, std::int32_t fn, const double* args, std::int32_t nargs,
                          const char* text, std::int32_t text_len, const char* text2,
                          std::int32_t text2_len);
  static std::int32_t host_result(void* host, std::int32_t kind, const void** data);

 private:
  double call(HostFn fn, const double* a, int n, const std::string& s, const std::string& s2);
  [[noreturn]] void fail(const std::string& message);
  [[noreturn]] void not_provided(HostFn fn, const char* why);
  RobotRef& robot(double r);
  AxisRef& axis(double r, double i);
  SensorRef& robot_sensor(double r, double i);
  SensorRef& global_sensor(double i);
  SolidRef& solid(double r, double i);
  ThingRef& thing(double t);
  double sensor_value(const SensorRef& s, bool substitute);
  void sensor_values(const SensorRef& s);
  void load_library();
  void report_error(const std::string& routine, const std::string& message);

  // The model, from configure().
  std::filesystem::path script_;
  std::filesystem::path library_path_;
  bool available_ = false;  // compiled and loadable
  double period_s_ = 0.04;
  std::uint64_t seed_ = 1;
  std::vector<RobotRef> robots_;
  std::vector<SensorRef> sensors_;  // SimTwo's global list
  std::vector<ThingRef> things_;
  std::vector<Vec3> obstacles_;
  std::vector<std::string> obstacle_ids_;
  std::vector<std::pair<std::string, double>> constants_;
  std::vector<InputHandle> sheet_inputs_;
  std::vector<double> sheet_initial_values_;  // the inputs' values at reset
  std::vector<std::pair<int, std::string>> key_inputs_;
  std::vector<InputHandle> keys_;
  Sheet sheet_;
  Sheet sheet_initial_;
  std::vector<std::pair<std::string, InputHandle>> sheet_input_names_;
  StateHandle state_;  // [0] started, [1] stopped, [2] calls, then per axis the last encoder count
  SignalHandle sig_compiled_, sig_error_, sig_calls_;
  double compiled_ = 0;
  bool loaded_poses_ = false;

  // Run-time state outside the kernel (docs/scripting.md, "State"): the script's own globals,
  // the texts it wrote, its ports.
  ScriptLibrary library_;
  StepContext* ctx_ = nullptr;  // during a call
  std::string pending_error_;
  std::string last_error_;  // the run-time error that stopped the script
  std::string text_result_;
  std::vector<double> numbers_;
  std::deque<std::string> output_;  // WriteLn, the last 100 lines
  std::string hud_;
  UdpPort udp_;
  SerialPort serial_;
  bool warned_unavailable_ = false;
};

void ScriptController::configure(ConfigureContext& ctx) {
  const Params& p = ctx.params();
  script_ = p.text("file");
  seed_ = ctx.seed();
  period_s_ = 0;
  const double dt = ctx.tick_s();
  // The controller period the kernel gave every controller: the scene's script period.
  // SimTwo's first call comes at T - dt, then every T (§1.3).
  period_s_ = p.number("period_s", 0.0);
  (void)dt;

  const auto robot_count = p.integer("robots");
  for (std::int64_t r = 0; r < robot_count; ++r) {
    const std::string k = "robot_" + std::to_string(r) + "_";
    RobotRef robot;
    robot.id = p.text(k + "id");
    const std::string main = p.text(k + "main", "");
    if (!main.empty()) robot.main = ctx.body(main);
    robot.origin = {p.number(k + "origin_x"), p.number(k + "origin_y"), p.number(k + "origin_z")};
    robot.offset = {p.number(k + "offset_x"), p.number(k + "offset_y"), p.number(k + "offset_z")};
    robot.yaw = p.number(k + "yaw");
    for (std::int64_t i = 0, n = p.integer(k + "solids"); i < n; ++i) {
      const std::string sk = k + "solid_" + std::to_string(i) + "_";
      robot.solids.push_back({p.text(sk + "id"), ctx.body(p.text(sk + "body"))});
    }
    for (std::int64_t i = 0, n = p.integer(k + "axes"); i < n; ++i) {
      AxisRef a;
      a.path = p.text(k + "axis_" + std::to_string(i), "");
      if (!a.path.empty()) {
        a.axis = ctx.axis(a.path);
        a.linear = ctx.axis_is_linear(a.axis);
        const char* u = a.linear ? "m" : "rad";
        a.ref_voltage = ctx.declare_input_at(a.path + "/ref_voltage", "V", 0.0);
        a.ref_speed = ctx.declare_input_at(a.path + "/ref_speed", a.linear ? "m/s" : "rad/s", 0.0);
        a.ref_pos = ctx.declare_input_at(a.path + "/ref_pos", u, 0.0);
        a.ref_torque = ctx.declare_input_at(a.path + "/ref_torque", a.linear ? "N" : "N*m", 0.0);
        try {
          a.controller_active = ctx.declare_input_at(a.path + "/controller_active", "1", 0.0);
          a.encoder = ctx.published_signal(a.path + "/encoder");
          a.current = ctx.published_signal(a.path + "/current");
          a.voltage = ctx.published_signal(a.path + "/voltage");
        } catch (const Error&) {
          // an axis without a drive train (loop-closing): GetAxisOdo/I/U raise if asked
        }
      }
      robot.axes.push_back(a);
    }
    const auto sensor_count = p.integer(k + "sensors");
    for (std::int64_t i = 0; i < sensor_count; ++i)
      robot.sensors.push_back(-1);  // filled below from the global list
    robots_.push_back(std::move(robot));
  }
  for (std::int64_t g = 0, n = p.integer("global_sensors"); g < n; ++g) {
    const std::string sk = "global_sensor_" + std::to_string(g) + "_";
    SensorRef s;
    s.id = p.text(sk + "id");
    s.kind = p.text(sk + "kind");
    s.prefix = p.text(sk + "prefix");
    try {
      s.value = ctx.published_signal(s.prefix + "/value");
    } catch (const Error&) {
    }
    if (s.kind == "ranger2d") {
      for (int k = 0;; ++k) {
        try {
          s.rays.push_back(ctx.published_signal(s.prefix + "/ray/" + std::to_string(k)));
        } catch (const Error&) {
          break;
        }
      }
    }
    if (s.kind == "solenoid") s.vin = ctx.declare_input_at(s.prefix + "/vin", "1", 0.0);
    sensors_.push_back(std::move(s));
  }
  // A robot's sensor i is the global sensor with its prefix (the robot's come in its order).
  for (auto& robot : robots_) {
    int next = 0;
    const std::string prefix = "robots/" + robot.id + "/sensors/";
    for (std::size_t g = 0; g < sensors_.size() && next < static_cast<int>(robot.sensors.size());
         ++g)
      if (sensors_[g].prefix.rfind(prefix, 0) == 0)
        robot.sensors[static_cast<std::size_t>(next++)] = static_cast<int>(g);
  }
  for (std::int64_t t = 0, n = p.integer("things"); t < n; ++t) {
    const std::string tk = "thing_" + std::to_string(t) + "_";
    ThingRef th;
    th.id = p.text(tk + "id");
    th.body = ctx.body(p.text(tk + "body"));
    th.rgba[0] = p.number(tk + "r");
    th.rgba[1] = p.number(tk + "g");
    th.rgba[2] = p.number(tk + "b");
    th.rgba[3] = p.number(tk + "a");
    things_.push_back(th);
  }
  for (std::int64_t o = 0, n = p.integer("obstacles"); o < n; ++o) {
    const std::string ok = "obstacle_" + std::to_string(o) + "_";
    obstacle_ids_.push_back(p.text(ok + "id", ""));
    obstacles_.push_back({p.number(ok + "x"), p.number(ok + "y"), p.number(ok + "z")});
  }
  for (std::int64_t i = 0, n = p.integer("constants"); i < n; ++i)
    constants_.emplace_back(p.text("constant_" + std::to_string(i) + "_name"),
                            p.number("constant_" + std::to_string(i) + "_value"));
  // The sheet: every cell of Global.S2Sheet is an input sheet/<cell> holding its number (a
  // button: its click count).
  for (std::int64_t i = 0, n = p.integer("cells"); i < n; ++i) {
    const std::string ck = "cell_" + std::to_string(i) + "_";
    const int row = static_cast<int>(p.integer(ck + "r"));
    const int col = static_cast<int>(p.integer(ck + "c"));
    Sheet::Cell& cell = sheet_initial_.set(row, col, p.text(ck + "text", ""));
    if (cell.input < 0) {
      cell.input = static_cast<int>(sheet_inputs_.size());
      sheet_inputs_.push_back(ctx.declare_input_at(
          "sheet/" + cell_name(row, col), cell.kind == Sheet::Kind::button ? "button" : "1", 0.0));
    }
    sheet_initial_values_.resize(sheet_inputs_.size());
    sheet_initial_values_[static_cast<std::size_t>(cell.input)] = cell.value;
  }
  for (int code : kKeyCodes)
    keys_.push_back(ctx.declare_input_at("keyboard/" + std::to_string(code), "1", 0.0));

  std::size_t axis_count = 0;
  for (const auto& r : robots_)
    axis_count += r.axes.size();
  state_ = ctx.declare_state("script", static_cast<int>(3 + axis_count), 0.0);
  sig_compiled_ = ctx.declare_signal("compiled", "1");
  sig_error_ = ctx.declare_signal("error", "1");
  sig_calls_ = ctx.declare_signal("calls", "1");

  // Compile (or find in the cache). A compile error refuses the scene, located.
  const CompileResult compiled = compile_script(script_, CompilerSettings::from_environment());
  switch (compiled.status) {
    case CompileResult::Status::compiler_missing:
      ctx.warn(compiled.output + " (install fpc: scripts/install-deps.sh); the script '" +
               script_.string() + "' does not run");
      available_ = false;
      break;
    case CompileResult::Status::failed: {
      if (compiled.errors.empty())
        throw Error(ErrorKind::scene, Location{script_.string(), "", ""},
                    "the script does not compile:\n" + compiled.output);
      const CompileMessage& first = compiled.errors.front();
      std::string message = first.file + ":" + std::to_string(first.line) + ":" +
                            std::to_string(first.column) + ": " + first.text;
      for (std::size_t i = 1; i < compiled.errors.size(); ++i)
        message += "\n" + compiled.errors[i].file + ":" + std::to_string(compiled.errors[i].line) +
                   ":" + std::to_string(compiled.errors[i].column) + ": " + compiled.errors[i].text;
      throw Error(ErrorKind::scene, message);
    }
    case CompileResult::Status::ok:
      available_ = true;
      library_path_ = compiled.library;
      compiled_ = compiled.compiled ? 1 : 0;
      break;
  }
  if (period_s_ <= 0) period_s_ = 0.04;
  const double ticks = std::round(period_s_ / ctx.tick_s());
  ctx.set_schedule(Stage::control, ticks * ctx.tick_s(), (ticks - 1) * ctx.tick_s());

  int udp_port = 9808;
  if (const char* env = std::getenv("S2SIM_UDP_PORT"); env && *env) udp_port = std::atoi(env);
  if (!udp_.open(udp_port))
    ctx.warn("cannot listen on UDP port " + std::to_string(udp_port) +
             " (in use?); ReadUDPData returns '' and WriteUDPData sends from another port");
  if (const char* com = std::getenv("S2SIM_COM_PORT"); com && *com) {
    std::string why;
    if (!serial_.open(com, why))
      ctx.warn("cannot open the serial port " + std::string(com) + ": " + why);
  }
  numbers_.reserve(kMaxNumbers);
}

void ScriptController::load_library() {
  HostTable table;
  table.host = this;
  table.call = &ScriptController::host_call;
  table.result = &ScriptController::host_result;
  library_.load(library_path_, table, static_cast<std::int32_t>(seed_ & 0x7fffffff));
}

void ScriptController::initialize(StepContext& ctx) {
  if (!loaded_poses_) {
    for (auto& r : robots_)
      if (r.main.valid()) r.main_load_pose = ctx.body_pose(r.main);
    loaded_poses_ = true;
  }
  sheet_ = sheet_initial_;  // texts as loaded; the numbers are the inputs sheet/<cell>
  for (std::size_t i = 0; i < sheet_inputs_.size(); ++i)
    ctx.set_input(sheet_inputs_[i], sheet_initial_values_[i]);
  output_.clear();
  hud_.clear();
  // Fresh script globals at every reset, as a new compile in SimTwo.
  if (available_) {
    try {
      load_library();
    } catch (const std::exception& e) {
      throw Error(ErrorKind::plugin, std::string("script '") + script_.string() + "': " + e.what());
    }
  }
  ctx.publish(sig_compiled_, compiled_);
  ctx.publish(sig_error_, 0);
  ctx.publish(sig_calls_, 0);
}

void ScriptController::update(StepContext& ctx) {
  double* s = ctx.state(state_);
  if (!available_) return;  // no compiler: the scene runs without its controller
  // The script tick, before the script: encoders counted over the period, references zeroed
  // (§1.3 steps 1-2; the position reference is kept).
  std::size_t k = 3;
  for (auto& robot : robots_)
    for (auto& a : robot.axes) {
      if (!a.path.empty()) {
        ctx.set_input(a.ref_voltage, 0);
        ctx.set_input(a.ref_speed, 0);
        ctx.set_input(a.ref_torque, 0);
      }
      ++k;
    }
  if (s[1] != 0) return;  // stopped by a run-time error; SimTwo still zeroes the references
  ctx_ = &ctx;
  std::string error;
  bool ok = true;
  const bool first = s[0] == 0;
  if (first) {
    s[0] = 1;
    ok = library_.run(0, ctx.time_s(), error);
    if (!ok) report_error("Initialize", error);
  }
  if (ok) {
    ok = library_.run(1, ctx.time_s(), error);
    if (!ok) report_error("Control", error);
  }
  ctx_ = nullptr;
  // Encoder counts of this tick, for the next period's deltas.
  k = 3;
  for (auto& robot : robots_)
    for (auto& a : robot.axes) {
      if (a.encoder.index >= 0) s[k] = ctx.signal(a.encoder);
      ++k;
    }
  s[2] += 1;
  ctx.publish(sig_calls_, s[2]);
  if (!ok) {
    s[1] = 1;  // SimTwo switches the control block to None: no further calls
    ctx.publish(sig_error_, 1);
  }
}

void ScriptController::report_error(const std::string& routine, const std::string& message) {
  // "EClass: text |  $addr |  $addr ...": the raising address, then its callers. Name the first
  // frame in the user's file (fpc -gl line table), else the first one known.
  std::vector<std::string> parts;
  for (std::size_t from = 0;;) {
    const auto bar = message.find(" |", from);
    parts.push_back(message.substr(from, bar == std::string::npos ? bar : bar - from));
    if (bar == std::string::npos) break;
    from = bar + 2;
  }
  std::string where, any;
  const std::string file = script_.filename().string();
  for (std::size_t i = 1; i < parts.size() && where.empty(); ++i) {
    const auto dollar = parts[i].find('$');
    if (dollar == std::string::npos) continue;
    const std::string f = library_.describe(
        static_cast<std::uintptr_t>(std::strtoull(parts[i].c_str() + dollar + 1, nullptr, 16)));
    if (f.empty()) continue;
    if (any.empty()) any = f;
    if (f.find("/" + file + ":") != std::string::npos ||
        f.find(" " + file + ":") != std::string::npos)
      where = f;
  }
  if (where.empty()) where = any;
  // The line table names the compiled copy: show the user's file, same line.
  if (const auto at = where.find("/" + file + ":"); at != std::string::npos) {
    const auto space = where.rfind(' ', at);
    where = where.substr(0, space + 1) + script_.string() + where.substr(at + 1 + file.size());
  }
  last_error_ = "run-time error in " + routine + ": " + parts.front() +
                (where.empty() ? std::string() : " (" + where + ")");
  std::fprintf(stderr, "script %s: %s; the script is stopped\n", script_.string().c_str(),
               last_error_.c_str());
}

// --- the host functions ---------------------------------------------------------------------

void ScriptController::fail(const std::string& message) {
  throw Error(ErrorKind::runtime, message);
}

void ScriptController::not_provided(HostFn fn, const char* why) {
  fail(std::string(kHostFnNames[static_cast<int>(fn)]) + " is not provided by S2Sim" +
       (why && *why ? std::string(": ") + why : std::string()));
}

static std::string index_error(double n) {
  char buf[64];
  std::snprintf(buf, sizeof buf, "List index (%.0f) out of bounds", n);
  return buf;
}

RobotRef& ScriptController::robot(double r) {
  if (r < 0 || r >= static_cast<double>(robots_.size())) fail(index_error(r));
  return robots_[static_cast<std::size_t>(r)];
}
AxisRef& ScriptController::axis(double r, double i) {
  RobotRef& rb = robot(r);
  if (i < 0 || i >= static_cast<double>(rb.axes.size())) fail(index_error(i));
  return rb.axes[static_cast<std::size_t>(i)];
}
SolidRef& ScriptController::solid(double r, double i) {
  RobotRef& rb = robot(r);
  if (i < 0 || i >= static_cast<double>(rb.solids.size())) fail(index_error(i));
  return rb.solids[static_cast<std::size_t>(i)];
}
SensorRef& ScriptController::global_sensor(double i) {
  if (i < 0 || i >= static_cast<double>(sensors_.size())) fail(index_error(i));
  return sensors_[static_cast<std::size_t>(i)];
}
SensorRef& ScriptController::robot_sensor(double r, double i) {
  RobotRef& rb = robot(r);
  if (i < 0 || i >= static_cast<double>(rb.sensors.size()) ||
      rb.sensors[static_cast<std::size_t>(i)] < 0)
    fail(index_error(i));
  return sensors_[static_cast<std::size_t>(rb.sensors[static_cast<std::size_t>(i)])];
}
ThingRef& ScriptController::thing(double t) {
  if (t < 0 || t >= static_cast<double>(things_.size())) fail(index_error(t));
  return things_[static_cast<std::size_t>(t)];
}

double ScriptController::sensor_value(const SensorRef& s, bool substitute) {
  // SimTwo's GetSensorVal is -1 for the kinds that never flag "has a measure" (§3.2, Q7).
  if (substitute && (s.kind == "ranger2d" || s.kind == "beacon" || s.kind == "imu" ||
                     s.kind == "IR" || s.kind == "spraygun"))
    return -1;
  if (s.value.index < 0) return substitute ? -1 : 0;
  return ctx_->signal(s.value);
}

void ScriptController::sensor_values(const SensorRef& s) {
  numbers_.clear();
  if (!s.rays.empty()) {
    for (const auto& ray : s.rays)
      numbers_.push_back(ctx_->signal(ray));
  } else {
    numbers_.push_back(sensor_value(s, false));
  }
}

double ScriptController::host_call(void* host, std::int32_t fn, const double* args,
                                   std::int32_t nargs, const char* text, std::int32_t text_len,
                                   const char* text2, std::int32_t text2_len) {
  auto* self = static_cast<ScriptController*>(host);
  self->pending_error_.clear();
  try {
    if (fn < 0 || fn >= static_cast<int>(HostFn::count) || !self->ctx_)
      throw Error(ErrorKind::runtime, "invalid host call");
    return self->call(
        static_cast<HostFn>(fn), args, nargs,
        text ? std::string(text, static_cast<std::size_t>(text_len)) : std::string(),
        text2 ? std::string(text2, static_cast<std::size_t>(text2_len)) : std::string());
  } catch (const Error& e) {
    self->pending_error_ = e.message();
  } catch (const std::exception& e) {
    self->pending_error_ = e.what();
  }
  return 0;
}

std::int32_t ScriptController::host_result(void* host, std::int32_t kind, const void** data) {
  auto* self = static_cast<ScriptController*>(host);
  switch (kind) {
    case 0:
      *data = self->text_result_.data();
      return static_cast<std::int32_t>(self->text_result_.size());
    case 1:
      *data = self->numbers_.data();
      return static_cast<std::int32_t>(self->numbers_.size());
    default:
      *data = self->pending_error_.data();
      return static_cast<std::int32_t>(self->pending_error_.size());
  }
}

double ScriptController::call(HostFn fn, const double* a, int n, const std::string& s,
                              const std::string& s2) {
  StepContext& ctx = *ctx_;
  auto need = [&](int count) {
    if (n < count) fail(std::string(kHostFnNames[static_cast<int>(fn)]) + ": missing arguments");
  };
  auto drive = [&](double r, double i) -> AxisRef& {
    AxisRef& ax = axis(r, i);
    if (ax.path.empty())
      fail("axis " + std::to_string(static_cast<int>(i)) + " of robot " +
           std::to_string(static_cast<int>(r)) + " is a Fixed or Ball joint");
    return ax;
  };
  auto pose_of = [&](BodyHandle b) -> const Pose& { return ctx.body_pose(b); };
  auto point = [&](const Vec3& v) {
    numbers_.assign({v.x, v.y, v.z});
    return 0.0;
  };
  switch (fn) {
    case HostFn::WriteLn:
      std::fprintf(stderr, "script: %s\n", s.c_str());
      output_.push_back(s);
      if (output_.size() > 100) output_.pop_front();
      return 0;
    case HostFn::KeyPressed: {
      need(1);
      for (std::size_t k = 0; k < std::size(kKeyCodes); ++k)
        if (kKeyCodes[k] == static_cast<int>(a[0])) return ctx.input(keys_[k]) != 0 ? 1 : 0;
      return 0;  // a key the viewer cannot press is never held
    }
    case HostFn::ScriptPeriod:
      return period_s_;
    case HostFn::GetSceneConstant: {
      need(1);
      for (const auto& [name, value] : constants_) {
        if (name.size() != s.size()) continue;
        bool same = true;
        for (std::size_t i = 0; i < s.size() && same; ++i)
          same = std::toupper(static_cast<unsigned char>(name[i])) ==
                 std::toupper(static_cast<unsigned char>(s[i]));
        if (same) return value;
      }
      return a[0];
    }
    case HostFn::SetRCValue: {
      need(2);
      const int r = static_cast<int>(a[0]), c = static_cast<int>(a[1]);
      if (r <= 0 || c <= 0) return 0;
      Sheet::Cell& cell = sheet_.set(r, c, s);
      if (cell.input >= 0 && cell.kind != Sheet::Kind::button)
        ctx.set_input(sheet_inputs_[static_cast<std::size_t>(cell.input)], cell.value);
      else if (cell.input >= 0 && cell.kind == Sheet::Kind::button && cell.text != s)
        ctx.set_input(sheet_inputs_[static_cast<std::size_t>(cell.input)], 0);
      return 0;
    }
    case HostFn::GetRCValue: {
      need(2);
      Sheet::Cell* cell = sheet_.find(static_cast<int>(a[0]), static_cast<int>(a[1]));
      if (!cell) return 0;
      if (cell->input >= 0) return ctx.input(sheet_inputs_[static_cast<std::size_t>(cell->input)]);
      return cell->value;
    }
    case HostFn::GetRCText: {
      need(2);
      const int r = static_cast<int>(a[0]), c = static_cast<int>(a[1]);
      text_result_.clear();
      if (r == 0 || c == 0) {  // the fixed headers show their numbers (Q8)
        text_result_ = std::to_string(r == 0 ? c : r);
        return 0;
      }
      Sheet::Cell* cell = sheet_.find(r, c);
      if (!cell) return 0;
      text_result_ = cell->kind == Sheet::Kind::button
                         ? cell->text.substr(cell->text.find('[') + 1,
                                             cell->text.rfind(']') - cell->text.find('[') - 1)
                         : cell->text;
      if (cell->input >= 0 && cell->kind == Sheet::Kind::text) {
        // Set from outside (--sheet, --set, the viewer): the number is the truth.
        const double v = ctx.input(sheet_inputs_[static_cast<std::size_t>(cell->input)]);
        if (v != cell->value) {
          char buf[40];
          std::snprintf(buf, sizeof buf, "%.15g", v);
          text_result_ = buf;
        }
      }
      return 0;
    }
    case HostFn::RCButtonPressed: {
      need(2);
      Sheet::Cell* cell = sheet_.find(static_cast<int>(a[0]), static_cast<int>(a[1]));
      if (!cell || cell->kind != Sheet::Kind::button || cell->input < 0) return 0;
      const InputHandle h = sheet_inputs_[static_cast<std::size_t>(cell->input)];
      if (ctx.input(h) <= 0) return 0;
      ctx.set_input(h, 0);  // the latch: clicked at least once since the last query
      return 1;
    }
    case HostFn::ClearButtons:
      for (const auto& [rc, cell] : sheet_.cells())
        if (cell.kind == Sheet::Kind::button && cell.input >= 0)
          ctx.set_input(sheet_inputs_[static_cast<std::size_t>(cell.input)], 0);
      return 0;
    case HostFn::RefreshSheets:
      return 0;  // formulas are not evaluated (docs/scripting.md): nothing to recalculate
    case HostFn::GetRobotIndex:
      for (std::size_t r = 0; r < robots_.size(); ++r)
        if (robots_[r].id == s) return static_cast<double>(r);
      return -1;
    case HostFn::GetSolidIndex: {
      need(1);
      const RobotRef& rb = robot(a[0]);
      for (std::size_t i = 0; i < rb.solids.size(); ++i)
        if (rb.solids[i].id == s) return static_cast<double>(i);
      return -1;
    }
    case HostFn::GetSensorIndex: {
      need(1);
      const RobotRef& rb = robot(a[0]);
      for (std::size_t i = 0; i < rb.sensors.size(); ++i)
        if (rb.sensors[i] >= 0 && sensors_[static_cast<std::size_t>(rb.sensors[i])].id == s)
          return static_cast<double>(i);
      return -1;
    }
    case HostFn::GetAxisIndex: {
      need(2);
      const RobotRef& rb = robot(a[0]);
      (void)rb;
      not_provided(fn, "look axes up by their index in joint order");
    }
    case HostFn::GetGlobalSensorIndex:
      for (std::size_t i = 0; i < sensors_.size(); ++i)
        if (sensors_[i].id == s) return static_cast<double>(i);
      return -1;
    case HostFn::GetThingIndex:
      for (std::size_t i = 0; i < things_.size(); ++i)
        if (things_[i].id == s) return static_cast<double>(i);
      return -1;
    case HostFn::GetThingsCount:
      return static_cast<double>(things_.size());
    case HostFn::SetAxisVoltageRef:
      need(3);
      ctx.set_input(drive(a[0], a[1]).ref_voltage, a[2]);
      return 0;
    case HostFn::SetAxisSpeedRef:
      need(3);
      ctx.set_input(drive(a[0], a[1]).ref_speed, a[2]);
      return 0;
    case HostFn::SetAxisPosRef:
      need(3);
      ctx.set_input(drive(a[0], a[1]).ref_pos, a[2]);
      return 0;
    case HostFn::SetAxisTorqueRef:
      need(3);
      ctx.set_input(drive(a[0], a[1]).ref_torque, a[2]);
      return 0;
    case HostFn::GetAxisPosRef:
      need(2);
      return ctx.input(drive(a[0], a[1]).ref_pos);
    case HostFn::GetAxisSpeedRef:
      need(2);
      return ctx.input(drive(a[0], a[1]).ref_speed);
    case HostFn::GetAxisOdo: {
      need(2);
      AxisRef& ax = drive(a[0], a[1]);
      if (ax.encoder.index < 0) fail("axis " + ax.path + " has no encoder");
      // The ticks counted during the last script period (state: the count at the last tick).
      std::size_t k = 3;
      for (const auto& rb : robots_)
        for (const auto& other : rb.axes) {
          if (&other == &ax) return ctx.signal(ax.encoder) - ctx.state(state_)[k];
          ++k;
        }
      return 0;
    }
    case HostFn::GetAxisPos: {
      need(2);
      const AxisRef& ax = axis(a[0], a[1]);
      if (ax.path.empty()) return 0;
      const double q = ctx.axis_position(ax.axis);
      if (ax.linear) return q;
      // SimTwo's (ODE's) hinge angle lies in (-pi, pi] (Q2).
      double w = std::remainder(q, 2 * kPi);
      if (w <= -kPi) w += 2 * kPi;
      return w;
    }
    case HostFn::GetAxisSpeed: {
      need(2);
      const AxisRef& ax = axis(a[0], a[1]);
      return ax.path.empty() ? 0 : ctx.axis_velocity(ax.axis);
    }
    case HostFn::GetAxisI: {
      need(2);
      const AxisRef& ax = drive(a[0], a[1]);
      if (ax.current.index < 0) fail("axis " + ax.path + " has no motor");
      return ctx.signal(ax.current);
    }
    case HostFn::GetAxisU: {
      need(2);
      const AxisRef& ax = drive(a[0], a[1]);
      if (ax.voltage.index < 0) fail("axis " + ax.path + " has no motor");
      return ctx.signal(ax.voltage);
    }
    case HostFn::GetAxisTorque:
      not_provided(fn, "read the axis torque signal from a log instead");
    case HostFn::SetMotorActive:
      need(3);
      (void)drive(a[0], a[1]);
      if (a[2] == 0) not_provided(fn, "a motor cannot be switched off at run time yet");
      return 0;  // motors are active as the scene declares them
    case HostFn::IsMotorActive:
      need(2);
      (void)drive(a[0], a[1]);
      return 1;
    case HostFn::SetMotorControllerState:
      need(3);
      ctx.set_input(drive(a[0], a[1]).controller_active, a[2] != 0 ? 1 : 0);
      return 0;
    case HostFn::GetMotorControllerState:
      need(2);
      return ctx.input(drive(a[0], a[1]).controller_active);
    case HostFn::GetMotorPars:
    case HostFn::SetMotorPars:
      not_provided(fn, "motor parameters are fixed at load");
    case HostFn::GetSensorVal:
      need(2);
      return sensor_value(robot_sensor(a[0], a[1]), true);
    case HostFn::GetSensorValues:
      need(2);
      sensor_values(robot_sensor(a[0], a[1]));
      return static_cast<double>(numbers_.size()) * 65536 + 1;
    case HostFn::SetSensorVin: {
      need(3);
      SensorRef& sn = robot_sensor(a[0], a[1]);
      if (sn.vin.index >= 0) ctx.set_input(sn.vin, a[2]);
      return 0;
    }
    case HostFn::GetGlobalSensorVal:
      need(1);
      return sensor_value(global_sensor(a[0]), false);
    case HostFn::GetGlobalSensorValues:
      need(1);
      sensor_values(global_sensor(a[0]));
      return static_cast<double>(numbers_.size()) * 65536 + 1;
    case HostFn::SetRobotPos: {
      need(5);
      RobotRef& rb = robot(a[0]);
      if (!rb.main.valid()) fail("robot '" + rb.id + "' has no main body");
      // SimTwo's re-placement (§3.3, Q4): offsets to the file coordinates, yaw about the main
      // body's file position; the file rotation is the load rotation without the scene's yaw.
      Pose pose;
      pose.position = rb.origin + Vec3{a[1], a[2], a[3]};
      pose.rotation = rot_z(a[4]) * (rot_z(-rb.yaw) * rb.main_load_pose.rotation);
      ctx.request_place(rb.main, pose);
      return 0;
    }
    case HostFn::GetRobotX:
      need(1);
      return pose_of(robot(a[0]).main).position.x;
    case HostFn::GetRobotY:
      need(1);
      return pose_of(robot(a[0]).main).position.y;
    case HostFn::GetRobotTheta: {
      need(1);
      const Mat3& R = pose_of(robot(a[0]).main).rotation;
      return std::atan2(R.m[1][0], R.m[0][0]);
    }
    case HostFn::GetRobotVx:
      need(1);
      return ctx.body_twist(robot(a[0]).main).linear_m_s.x;
    case HostFn::GetRobotVy:
      need(1);
      return ctx.body_twist(robot(a[0]).main).linear_m_s.y;
    case HostFn::GetRobotW:
      need(1);
      return ctx.body_twist(robot(a[0]).main).angular_rad_s.z;
    case HostFn::GetSolidPos:
      need(2);
      return point(pose_of(solid(a[0], a[1]).body).position);
    case HostFn::GetSolidTheta: {
      need(2);
      const Mat3& R = pose_of(solid(a[0], a[1]).body).rotation;
      return std::atan2(R.m[1][0], R.m[0][0]);
    }
    case HostFn::GetSolidRotMat: {
      need(2);
      const Mat3& R = pose_of(solid(a[0], a[1]).body).rotation;
      numbers_.clear();
      for (int r = 0; r < 3; ++r)
        for (int c = 0; c < 3; ++c)
          numbers_.push_back(R.m[r][c]);
      return 3 * 65536 + 3;
    }
    case HostFn::GetSolidLinearVel:
      need(2);
      return point(ctx.body_twist(solid(a[0], a[1]).body).linear_m_s);
    case HostFn::SetSolidPos:
    case HostFn::SetSolidRotationMat:
    case HostFn::SetSolidLinearVel:
    case HostFn::SetSolidAngularVel:
      not_provided(fn,
                   "one body of a jointed robot cannot be teleported; SetRobotPos moves a robot");
    case HostFn::SetSolidColor:
      need(5);
      (void)solid(a[0], a[1]);
      not_provided(fn, "colours are fixed at load");
    case HostFn::SetShellTag: {
      need(2);
      RobotRef& rb = robot(a[0]);
      if (a[1] < 0) fail(index_error(a[1]));
      const auto i = static_cast<std::size_t>(a[1]);
      if (rb.shell_tags.size() <= i) rb.shell_tags.resize(i + 1);
      rb.shell_tags[i] = s;
      return 0;
    }
    case HostFn::GetShellTag: {
      need(2);
      RobotRef& rb = robot(a[0]);
      const auto i = static_cast<std::size_t>(a[1] < 0 ? 0 : a[1]);
      text_result_ = i < rb.shell_tags.size() ? rb.shell_tags[i] : std::string();
      return 0;
    }
    case HostFn::SetThingPos: {
      need(4);
      ThingRef& th = thing(a[0]);
      Pose pose = pose_of(th.body);
      pose.position = {a[1], a[2], a[3]};
      ctx.request_place(th.body, pose);
      return 0;
    }
    case HostFn::GetThingPos:
      need(1);
      return point(pose_of(thing(a[0]).body).position);
    case HostFn::GetThingColor: {
      need(1);
      const ThingRef& th = thing(a[0]);
      numbers_.clear();
      for (double v : th.rgba)
        numbers_.push_back(std::round(v * 255));
      return 0;
    }
    case HostFn::GetObstaclePos:
      need(1);
      if (a[0] < 0 || a[0] >= static_cast<double>(obstacles_.size())) fail(index_error(a[0]));
      return point(obstacles_[static_cast<std::size_t>(a[0])]);
    case HostFn::AddOBstacleBox:
    case HostFn::ClearObstacles:
      not_provided(fn, "obstacles are fixed at load");
    case HostFn::ChartSeriesSetCount:
    case HostFn::ChartSeriesSetColor:
    case HostFn::ChartSeriesClear:
    case HostFn::ChartSeriesAddXY:
      not_provided(fn, "the viewer's chart plots signals; log them with --log");
    case HostFn::AddTrailNode:
    case HostFn::ClearTrail:
      not_provided(fn, "the viewer draws no trails yet");
    case HostFn::WriteUDPData:
      need(1);
      udp_.send(s, static_cast<int>(a[0]), s2);
      return 0;
    case HostFn::ReadUDPData:
      text_result_ = udp_.receive();
      return 0;
    case HostFn::WriteComPort:
      serial_.write(s);
      return 0;
    case HostFn::ReadComPort:
      text_result_ = serial_.read();
      return 0;
    case HostFn::HUDText:
      hud_ = s;
      return 0;
    case HostFn::count:
      break;
  }
  fail("invalid host call");
}

}  // namespace
}  // namespace s2sim::pascal

S2SIM_PLUGIN("pascal_script", S2SIM_KIND("pascal_script", s2sim::Category::controller,
                                         s2sim::pascal::ScriptController));
