// The `pascal_script` controller: a SimTwo project's `control.pas`, compiled with Free Pascal
// (compiler.cpp), loaded (script_library.cpp) and called as SimTwo calls it: references
// zeroed and encoders counted at every script tick, `Initialize` then `Control` at the first,
// `Control` at the later ones, every script period from T − dt (simtwo-script-api.md §1.3).
// The host functions the support unit forwards here are in host_calls.cpp.
#include "script_controller.hpp"

#include "pascal_tokens.hpp"

#include <fstream>
#include <iterator>

namespace s2sim::pascal {

namespace {

/// Whether the script's own file names a UDP routine (outside comments and strings).
bool uses_udp(const std::filesystem::path& script) {
  std::ifstream in(script, std::ios::binary);
  const std::string text((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
  return mentions_any(
      text, {"readudpdata", "writeudpdata", "readudppacket", "getudppacketcount", "udpdataread"});
}

Look read_look(const Params& p, const std::string& k) {
  Look look;
  const char* rgba[] = {"r", "g", "b", "a"};
  for (int c = 0; c < 4; ++c)
    look.rgba_loaded[c] = look.rgba[c] = p.number(k + rgba[c]);
  look.size = {p.number(k + "size_x"), p.number(k + "size_y"), p.number(k + "size_z")};
  look.com = {p.number(k + "com_x"), p.number(k + "com_y"), p.number(k + "com_z")};
  const std::string shape = p.text(k + "shape", "box");
  look.round = shape == "cylinder" ? 1 : shape == "sphere" ? 2 : 0;
  return look;
}
}  // namespace

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
      const BodyHandle body = ctx.body(p.text(sk + "body"));
      robot.solids.push_back({p.text(sk + "id"), body, read_look(p, sk), {}, {}});
      robot.solids.back().belt.index = -1;
      robot.solids.back().canvas = configure_canvas(ctx, p.text(sk + "canvas", ""));
      if (p.boolean(sk + "belt", false)) {
        try {
          robot.solids.back().belt = ctx.input(p.text(sk + "body") + "/belt_speed");
        } catch (const Error&) {
          // a belt without a belt surface has no speed to set: SetBeltSpeed says so
        }
      }
    }
    for (std::int64_t i = 0, n = p.integer(k + "shells"); i < n; ++i) {
      const std::string sk = k + "shell_" + std::to_string(i) + "_";
      RobotRef::Shell shell;
      shell.body = ctx.body(p.text(sk + "body"));
      shell.geom = static_cast<int>(p.integer(sk + "geom"));
      shell.position = {p.number(sk + "x"), p.number(sk + "y"), p.number(sk + "z")};
      const char* rgba[] = {"r", "g", "b", "a"};
      for (int c = 0; c < 4; ++c)
        shell.rgba[c] = p.number(sk + rgba[c]);
      robot.shells.push_back(shell);
    }
    for (std::int64_t i = 0, n = p.integer(k + "axes"); i < n; ++i) {
      AxisRef a;
      a.path = p.text(k + "axis_" + std::to_string(i), "");
      a.joint = p.text(k + "axis_" + std::to_string(i) + "_joint", "");
      if (!a.path.empty()) {
        a.axis = ctx.axis(a.path);
        a.linear = ctx.axis_is_linear(a.axis);
        const char* u = a.linear ? "m" : "rad";
        a.ref_voltage = ctx.declare_input_at(a.path + "/ref_voltage", "V", 0.0);
        a.ref_speed = ctx.declare_input_at(a.path + "/ref_speed", a.linear ? "m/s" : "rad/s", 0.0);
        a.ref_pos = ctx.declare_input_at(a.path + "/ref_pos", u, 0.0);
        a.ref_torque = ctx.declare_input_at(a.path + "/ref_torque", a.linear ? "N" : "N*m", 0.0);
        a.torque = ctx.signal_reader(a.path + "/torque");  // the kernel's, on every axis
        try {
          a.controller_active = ctx.declare_input_at(a.path + "/controller_active", "1", 0.0);
          a.encoder = ctx.published_signal(a.path + "/encoder");
          a.current = ctx.published_signal(a.path + "/current");
          a.voltage = ctx.published_signal(a.path + "/voltage");
          a.power = ctx.published_signal(a.path + "/power");
          const char* motor_inputs[kMotorParCount] = {"motor_ri",     "motor_li",    "motor_ki",
                                                      "motor_vmax",   "motor_imax",  "gear_ratio",
                                                      "motor_simple", "motor_active"};
          // The motor declared them (the drive train is configured before controllers):
          // these join its inputs, and their units must agree.
          const char* motor_units[kMotorParCount] = {
              "ohm", "H", a.linear ? "N/A" : "N*m/A", "V", "A", "1", "1", "1"};
          for (std::size_t m = 0; m < a.motor.size(); ++m)
            a.motor[m] = ctx.declare_input_at(a.path + "/" + motor_inputs[m], motor_units[m], 0.0);
          a.has_motor = true;
          a.spring_k =
              ctx.declare_input_at(a.path + "/spring_k", a.linear ? "N/m" : "N*m/rad", 0.0);
          a.spring_zeropos = ctx.declare_input_at(a.path + "/spring_zeropos", u, 0.0);
          a.friction_bv =
              ctx.declare_input_at(a.path + "/friction_bv", a.linear ? "N*s/m" : "N*m*s/rad", 0.0);
          a.friction_fc =
              ctx.declare_input_at(a.path + "/friction_fc", a.linear ? "N" : "N*m", 0.0);
          const char* gains[] = {"controller_kp", "controller_ki", "controller_kd", "controller_kf",
                                 "controller_mode"};
          for (std::size_t g = 0; g < a.controller.size(); ++g)
            a.controller[g] = ctx.declare_input_at(a.path + "/" + gains[g], "1", 0.0);
          a.energy_drawn = ctx.published_signal(a.path + "/energy_drawn");
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
  configure_paint(ctx);
  configure_camera(ctx);
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
    th.look = read_look(p, tk);
    things_.push_back(th);
  }
  things_loaded_ = things_;
  for (std::int64_t o = 0, n = p.integer("obstacles"); o < n; ++o) {
    const std::string ok = "obstacle_" + std::to_string(o) + "_";
    ObstacleRef ob;
    ob.id = p.text(ok + "id", "");
    ob.position = {p.number(ok + "x"), p.number(ok + "y"), p.number(ok + "z")};
    const char* rgba[] = {"r", "g", "b", "a"};
    for (int c = 0; c < 4; ++c)
      ob.rgba[c] = p.number(ok + rgba[c]);
    for (int r = 0; r < 3; ++r)
      for (int c = 0; c < 3; ++c)
        ob.rotation.m[r][c] = p.number(ok + "rot_" + std::to_string(r) + std::to_string(c));
    ob.scene_index = static_cast<int>(o);
    ob.canvas = configure_canvas(ctx, p.text(ok + "canvas", ""));
    obstacles_.push_back(ob);
  }
  obstacles_loaded_ = obstacles_;
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

  for (auto& r : robots_)
    for (auto& a : r.axes)
      a.index = static_cast<int>(axis_count_++);
  state_ = ctx.declare_state("script", static_cast<int>(3 + 2 * axis_count_), 0.0);
  sig_error_ = ctx.declare_signal("error", "1");
  sig_calls_ = ctx.declare_signal("calls", "1");
  sig_close_ = ctx.declare_signal("close", "1");
  // SimTwo's Stop and Run (the viewer's Script window): 0 stops the calls; a new non-zero
  // value starts the script afresh (fresh globals, Initialize at the next script tick).
  run_input_ = ctx.declare_input("running", "1", 1.0);

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
      break;
  }
  if (period_s_ <= 0) period_s_ = kDefaultControlPeriod_s;
  const double ticks = std::round(period_s_ / ctx.tick_s());
  ctx.set_schedule(Stage::control, ticks * ctx.tick_s(), (ticks - 1) * ctx.tick_s());

  // UDP listens from the start, as SimTwo's, when the script names a UDP routine; otherwise
  // it opens nothing (or at a first call the text did not show: udp()).
  // The scene's `<s2sim><udp>` (loopback and 9808 by default); the environment overrides it.
  udp_address_ = p.text("udp_address", udp_address_);
  udp_port_ = static_cast<int>(p.integer("udp_port", udp_port_));
  if (const char* env = std::getenv("S2SIM_UDP_PORT"); env && *env) udp_port_ = std::atoi(env);
  if (const char* env = std::getenv("S2SIM_UDP_ADDRESS"); env && *env) udp_address_ = env;
  std::string why;
  if (uses_udp(script_) && !udp_.open(udp_address_, udp_port_, why)) ctx.warn(udp_failure(why));
  if (const char* com = std::getenv("S2SIM_COM_PORT"); com && *com) {
    if (!serial_.open(com, why))
      ctx.warn("cannot open the serial port " + std::string(com) + ": " + why);
  }
  if (const char* port = std::getenv("S2SIM_MODBUS_PORT"); port && *port) {
    if (!modbus_.open(std::atoi(port), why))
      ctx.warn("cannot listen on Modbus/TCP port " + std::string(port) + ": " + why +
               "; the Modbus routines work on the script's own tables only");
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
  trails_.assign(kMaxTrails + 1, {});
  // The kernel's reset restores the scene's colours and the script's tags start empty.
  auto restore = [](Look& look) { std::copy(look.rgba_loaded, look.rgba_loaded + 4, look.rgba); };
  for (auto& r : robots_)
    for (auto& sd : r.solids) {
      restore(sd.look);
      sd.tag.clear();
    }
  things_ = things_loaded_;  // the kernel's reset removed the things added and put back the rest
  obstacles_ = obstacles_loaded_;
  fire_ = Fire{};  // the kernel's reset put it out
  for (auto& th : things_)
    restore(th.look);
  chart_series_count_.assign(kMaxCharts, 0);
  clear_canvases(ctx);  // the kernel's reset made their images white
  last_run_value_ = ctx.input(run_input_);
  // Fresh script globals at every reset, as a new compile in SimTwo.
  if (available_) {
    try {
      load_library();
    } catch (const std::exception& e) {
      throw Error(ErrorKind::plugin, std::string("script '") + script_.string() + "': " + e.what());
    }
  }
  ctx.publish(sig_error_, 0);
  ctx.publish(sig_calls_, 0);
  ctx.publish(sig_close_, 0);
}

void ScriptController::update(StepContext& ctx) {
  const Span<double> s = ctx.state(state_);
  if (!available_) return;  // no compiler: the scene runs without its controller
  moves_.clear();
  velocities_.clear();
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
  const double run = ctx.input(run_input_);
  if (run != last_run_value_) {
    last_run_value_ = run;
    if (run != 0) {  // Run: fresh globals, Initialize first, any earlier error forgotten
      load_library();
      s[0] = 0;
      s[1] = 0;
      ctx.publish(sig_error_, 0);
      ctx.log_line("script started");
    } else {
      ctx.log_line("script stopped");
    }
  }
  if (run == 0) return;   // stopped (SimTwo's Stop)
  if (s[1] != 0) return;  // stopped by a run-time error; SimTwo still zeroes the references
  modbus_.serve();        // the clients' requests of the last period, before the script reads
  ctx_ = &ctx;
  using Outcome = ScriptLibrary::Outcome;
  std::string error;
  Outcome outcome = Outcome::returned;
  const char* routine = "Initialize";
  if (s[0] == 0) {
    s[0] = 1;
    outcome = library_.run(0, ctx.time_s(), error);
  }
  if (outcome == Outcome::returned) {
    routine = "Control";
    outcome = library_.run(1, ctx.time_s(), error);
  }
  ctx_ = nullptr;
  flush_canvases(ctx);
  if (outcome == Outcome::raised) report_error(routine, error);
  if (outcome == Outcome::halted) report_halt(ctx, routine, error);
  // Encoder counts of this tick, for the next period's deltas.
  k = 3;
  for (auto& robot : robots_)
    for (auto& a : robot.axes) {
      if (a.encoder.index >= 0) s[k] = ctx.signal(a.encoder);
      ++k;
    }
  s[2] += 1;
  ctx.publish(sig_calls_, s[2]);
  // A raise or a Halt stops the script: SimTwo switches the control block to None.
  if (outcome != Outcome::returned) s[1] = 1;
  if (outcome == Outcome::raised) {
    ctx.publish(sig_error_, 1);
    ctx.log_line(last_error_ + "; the script is stopped");
  }
}

std::string ScriptController::udp_failure(const std::string& why) const {
  return "cannot listen on UDP " + udp_address_ + ":" + std::to_string(udp_port_) + " (" + why +
         "); ReadUDPData returns '' and WriteUDPData sends from another port";
}

UdpPort& ScriptController::udp() {
  std::string why;
  if (!udp_.opened() && !udp_.open(udp_address_, udp_port_, why)) {
    const std::string text = udp_failure(why);
    if (ctx_) ctx_->log_line(text);
    std::fprintf(stderr, "script %s: %s\n", script_.string().c_str(), text.c_str());
  }
  return udp_;
}

namespace {

/// "first | $addr | $addr ...": the text, then the raising address and its callers.
std::vector<std::string> split_frames(const std::string& message) {
  std::vector<std::string> parts;
  for (std::size_t from = 0;;) {
    const auto bar = message.find(" |", from);
    parts.push_back(message.substr(from, bar == std::string::npos ? bar : bar - from));
    if (bar == std::string::npos) break;
    from = bar + 2;
  }
  return parts;
}

}  // namespace

void ScriptController::report_halt(StepContext& ctx, const std::string& routine,
                                   const std::string& message) {
  const std::vector<std::string> parts = split_frames(message);
  const std::string where = where_raised(parts);
  const std::string& halt = parts.front();  // "Halt(code)"
  const long code = std::strtol(halt.c_str() + std::min<std::size_t>(5, halt.size()), nullptr, 10);
  // Halt(0) ends the run as CloseSimTwo does; another code ends it as a failure (exit 5).
  ctx.publish(sig_close_, code == 0 ? 1 : 2);
  const std::string text = "the script called " + halt + " in " + routine +
                           (where.empty() ? std::string() : " (" + where + ")") + ": the run ends";
  ctx.log_line(text);
  std::fprintf(stderr, "script %s: %s\n", script_.string().c_str(), text.c_str());
}

void ScriptController::report_error(const std::string& routine, const std::string& message) {
  // "EClass: text |  $addr |  $addr ...": the raising address, then its callers.
  const std::vector<std::string> parts = split_frames(message);
  const std::string where = where_raised(parts);
  last_error_ = "run-time error in " + routine + ": " + parts.front() +
                (where.empty() ? std::string() : " (" + where + ")");
  std::fprintf(stderr, "script %s: %s; the script is stopped\n", script_.string().c_str(),
               last_error_.c_str());
}

std::string ScriptController::where_raised(const std::vector<std::string>& parts) const {
  // Name the first frame in the user's file (fpc -g DWARF line table, read by addr2line), else
  // the first one known.
  std::string where, any;
  const std::string file = script_.filename().string();
  for (std::size_t i = 1; i < parts.size() && where.empty(); ++i) {
    const auto dollar = parts[i].find('$');
    if (dollar == std::string::npos) continue;
    // parts[1] is where the raise was, the rest are return addresses (ExceptFrames).
    const std::string f = library_.describe(
        static_cast<std::uintptr_t>(std::strtoull(parts[i].c_str() + dollar + 1, nullptr, 16)),
        i > 1);
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
  return where;
}

}  // namespace s2sim::pascal

S2SIM_PLUGIN("pascal_script", S2SIM_KIND("pascal_script", s2sim::Category::controller,
                                         s2sim::pascal::ScriptController));
