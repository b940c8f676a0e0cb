// The host functions a compiled SimTwo script calls (simtwo-script-api.md §3): dispatched by
// number from the support unit's table; each either returns its value (numbers, a text or a
// vector of numbers kept for the script to copy) or leaves an error the script raises.
#include "script_controller.hpp"

#include <algorithm>

namespace s2sim::pascal {

// --- the host functions ---------------------------------------------------------------------

void ScriptController::fail(const std::string& message) {
  throw Error(ErrorKind::runtime, message);
}

void ScriptController::not_provided(HostFn fn, const char* why) {
  fail(std::string(kHostFnNames[static_cast<int>(fn)]) + " is not yet available in S2Sim" +
       (why && *why ? std::string(": ") + why : std::string()));
}

std::string number_text(double v) {
  if (std::isnan(v)) return "NaN";
  if (std::isinf(v)) return v > 0 ? "+Inf" : "-Inf";
  char buf[32];
  std::snprintf(buf, sizeof buf, "%.15g", v);
  return buf;
}
std::string index_error(double n) {
  char buf[64];
  std::snprintf(buf, sizeof buf, "List index (%.0f) out of bounds", n);
  return buf;
}

void ScriptController::require_arguments(HostFn fn, int have, int want) {
  if (have < want) fail(std::string(kHostFnNames[static_cast<int>(fn)]) + ": missing arguments");
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
const AxisRef& ScriptController::motor(const AxisRef& ax) {
  if (!ax.has_motor) fail("axis " + ax.path + " has no motor");
  return ax;
}
int ScriptController::chart_series(double chart, double series) {
  if (chart < 0 || chart >= kMaxCharts) fail(index_error(chart));
  if (series < 0 || series >= kMaxChartSeries) fail(index_error(series));
  return static_cast<int>(chart) * kMaxChartSeries + static_cast<int>(series);
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
ObstacleRef& ScriptController::obstacle(double t) {
  if (t < 0 || t >= static_cast<double>(obstacles_.size())) fail(index_error(t));
  return obstacles_[static_cast<std::size_t>(t)];
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
    // Errors the host raises name the routine; one from the kernel (an input out of its range)
    // gets it put in front.
    const std::string routine =
        fn >= 0 && fn < static_cast<int>(HostFn::count) ? kHostFnNames[fn] : std::string();
    self->pending_error_ = routine.empty() || e.message().rfind(routine, 0) == 0
                               ? e.message()
                               : routine + ": " + e.message();
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
  // A NaN or infinite number (a 0/0 in the script) would reach the simulation, or an index
  // cast; it stops the script instead. SetMotorPars names its fields itself, and a rotation
  // matrix may carry unused cells: past their indices they check their own.
  const int checked = fn == HostFn::SetMotorPars          ? std::min(n, 2)
                      : fn == HostFn::SetSolidRotationMat ? std::min(n, 4)
                      : fn == HostFn::SetThingRotationMat ? std::min(n, 3)
                                                          : n;
  for (int k = 0; k < checked; ++k)
    if (!std::isfinite(a[k]))
      fail(std::string(kHostFnNames[static_cast<int>(fn)]) + ": argument " + std::to_string(k + 1) +
           " is " + number_text(a[k]));
  auto need = [&](int count) { require_arguments(fn, n, count); };
  auto drive = [&](double r, double i) -> AxisRef& {
    AxisRef& ax = axis(r, i);
    if (ax.path.empty())
      fail("axis " + std::to_string(static_cast<int>(i)) + " of robot " +
           std::to_string(static_cast<int>(r)) + " is a Fixed or Ball joint");
    return ax;
  };
  switch (fn) {
    case HostFn::WriteLn:
      std::fprintf(stderr, "script: %s\n", s.c_str());
      ctx.log_line(s);  // the viewer's Log window (SDK 0.9)
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
    case HostFn::AxisCount:  // for the support units (joint waypoints)
      need(1);
      return static_cast<double>(robot(a[0]).axes.size());
    case HostFn::AxisJoint: {
      need(2);
      const AxisRef& ax = axis(a[0], a[1]);
      text_result_ = ax.joint;
      return ax.path.size() > 2 && ax.path.compare(ax.path.size() - 2, 2, ":2") == 0 ? 1 : 0;
    }
    case HostFn::ScriptFolder:
      text_result_ = std::filesystem::absolute(script_).parent_path().string();
      return 0;
    case HostFn::getModbusCoil:
      need(1);
      return modbus_.coil(static_cast<int>(a[0])) ? 1 : 0;
    case HostFn::getModbusInput:
      need(1);
      return modbus_.input(static_cast<int>(a[0])) ? 1 : 0;
    case HostFn::setModbusCoil:
      need(2);
      modbus_.set_coil(static_cast<int>(a[0]), a[1] != 0);
      return 0;
    case HostFn::setModbusInput:
      need(2);
      modbus_.set_input(static_cast<int>(a[0]), a[1] != 0);
      return 0;
    case HostFn::CloseSimTwo:  // SimTwo closes once the call returns; the runner stops there
      ctx.publish(sig_close_, 1);
      ctx.log_line("CloseSimTwo: the script ends the run");
      return 0;
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
      // Joint ID's axis k (0 first, 1 a Universal joint's second, listed before its first).
      const RobotRef& rb = robot(a[0]);
      const bool second = a[1] == 1;
      for (std::size_t i = 0; i < rb.axes.size(); ++i) {
        const AxisRef& ax = rb.axes[i];
        const bool is_second =
            ax.path.size() > 2 && ax.path.compare(ax.path.size() - 2, 2, ":2") == 0;
        if (ax.joint == s && is_second == second) return static_cast<double>(i);
      }
      return -1;
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
    case HostFn::GetAxisTorque: {
      need(2);
      const AxisRef& ax = axis(a[0], a[1]);
      return ax.path.empty() ? 0 : ctx.signal(ax.torque);  // Fixed and Ball: 0
    }
    case HostFn::SetMotorActive:
      need(3);
      ctx.set_input(motor(drive(a[0], a[1])).motor[kMotorActive], a[2] != 0 ? 1 : 0);
      return 0;
    case HostFn::IsMotorActive:
      need(2);
      return ctx.input(motor(drive(a[0], a[1])).motor[kMotorActive]) != 0 ? 1 : 0;
    case HostFn::SetMotorControllerState:
      need(3);
      ctx.set_input(drive(a[0], a[1]).controller_active, a[2] != 0 ? 1 : 0);
      return 0;
    case HostFn::GetMotorControllerState:
      need(2);
      return ctx.input(drive(a[0], a[1]).controller_active);
    case HostFn::GetMotorPars: {
      need(2);
      const AxisRef& ax = motor(drive(a[0], a[1]));
      numbers_.clear();
      for (const InputHandle h : ax.motor)
        numbers_.push_back(ctx.input(h));
      return 0;
    }
    case HostFn::SetMotorPars: {
      need(2 + kMotorParCount);
      const AxisRef& ax = motor(drive(a[0], a[1]));
      // Checked here, so that a bad record stops the script, not the simulation (the motor
      // refuses the same values set from outside). As SimTwo, the controller's anti-windup
      // keeps the scene's Vmax.
      for (int k = 0; k < kMotorParCount; ++k) {
        const double v = a[2 + k];
        const bool positive = k == kMotorGearRatio || (k == kMotorRi && a[2 + kMotorSimple] != 0 &&
                                                       a[2 + kMotorActive] != 0);
        if (!std::isfinite(v) || v < 0 || (positive && v == 0))
          fail(std::string("SetMotorPars: ") + kMotorParNames[k] + " = " + number_text(v) +
               (positive ? " must be positive" : " must be >= 0"));
      }
      for (int k = 0; k < kMotorParCount; ++k)
        ctx.set_input(ax.motor[static_cast<std::size_t>(k)],
                      k >= kMotorSimple ? (a[2 + k] != 0 ? 1.0 : 0.0) : a[2 + k]);
      return 0;
    }
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
    case HostFn::SetGlobalSensorVin: {
      need(2);
      SensorRef& sn = global_sensor(a[0]);
      if (sn.vin.index >= 0) ctx.set_input(sn.vin, a[1]);
      return 0;
    }
    case HostFn::GetAxisUIPower: {
      need(2);
      const AxisRef& ax = motor(drive(a[0], a[1]));
      return ctx.signal(ax.power);
    }
    case HostFn::SetRobotPos:
    case HostFn::GetRobotX:
    case HostFn::GetRobotY:
    case HostFn::GetRobotTheta:
    case HostFn::GetRobotVx:
    case HostFn::GetRobotVy:
    case HostFn::GetRobotW:
    case HostFn::GetSolidPos:
    case HostFn::GetSolidTheta:
    case HostFn::GetSolidRotMat:
    case HostFn::GetSolidLinearVel:
    case HostFn::SetSolidPos:
    case HostFn::SetSolidLinearVel:
    case HostFn::SetSolidAngularVel:
    case HostFn::SetSolidRotationMat:
    case HostFn::SetSolidColor:
    case HostFn::SetShellTag:
    case HostFn::GetShellTag:
    case HostFn::SetThingPos:
    case HostFn::GetThingPos:
    case HostFn::GetThingColor:
    case HostFn::GetObstaclePos:
    case HostFn::GetSolidAngularVel:
    case HostFn::GetSolidMass:
    case HostFn::SetSolidForce:
    case HostFn::SetThingColor:
    case HostFn::GetThingRotMat:
    case HostFn::SetThingRotationMat:
    case HostFn::GetThingAngularVel:
    case HostFn::GetThingSpeed:
    case HostFn::SetThingSpeed:
    case HostFn::SetThingLinearVel:
    case HostFn::SetThingAngularVel:
    case HostFn::SetThingForce:
    case HostFn::SetThingForceAtRelPos:
    case HostFn::SetThingRelForce:
    case HostFn::SetThingRelForceAtRelPos:
    case HostFn::GetObstacleIndex:
    case HostFn::GetSolidColor:
    case HostFn::GetSolidSize:
    case HostFn::GetThingSize:
    case HostFn::GetSolidCenterOfMass:
    case HostFn::GetRobotCenterOfMass:
    case HostFn::GetSolidTag:
    case HostFn::SetSolidTag:
    case HostFn::GetObstacleColor:
    case HostFn::GetObstacleRotMat:
    case HostFn::SetBeltSpeed:
    case HostFn::GetBeltSpeed:
    case HostFn::GetShellPos:
    case HostFn::GetShellColor:
    case HostFn::SetShellColor:
    case HostFn::SetObstacleColor:
    case HostFn::SetSensorColor:
      return call_bodies(fn, a, n, s);
    case HostFn::Fire:
    case HostFn::SetSolidMass:
    case HostFn::SetSolidSize:
    case HostFn::SetThingSize:
    case HostFn::SetSolidSurfaceFriction:
    case HostFn::SetThingSurfaceMu:
    case HostFn::AddOBstacleBox:
    case HostFn::ClearObstacles:
    case HostFn::DeleteObstacle:
    case HostFn::SetObstaclePos:
    case HostFn::SetObstacleRotationMat:
    case HostFn::AddThingBox:
    case HostFn::AddThingSphere:
    case HostFn::AddThingCylinder:
    case HostFn::DeleteThing:
    case HostFn::ClearThings:
      return call_things(fn, a, n, s);
    case HostFn::MeshThing:
      return mesh_thing(a, n, s, s2);
    case HostFn::ChartSeriesSetCount:
    case HostFn::ChartSeriesSetColor:
    case HostFn::ChartSeriesClear:
    case HostFn::ChartSeriesAddXY:
    case HostFn::ChartSetAxisMinMax:
    case HostFn::ChartSeriesGetCount:
    case HostFn::ChartSeriesCreate:
    case HostFn::ChartSeriesDeleteAll:
    case HostFn::AddTrailNode:
    case HostFn::ClearTrail:
    case HostFn::DelTrailNode:
    case HostFn::SetTrailColor:
    case HostFn::SetRCBackColor:
    case HostFn::ReadUDPPacket:
    case HostFn::GetUDPPacketCount:
      return call_annotations(fn, a, n);
    case HostFn::SetAxisSpring:
    case HostFn::SetFrictionDef:
    case HostFn::GetFrictionDef:
    case HostFn::SetMotorControllerPars:
    case HostFn::GetMotorControllerPars:
    case HostFn::SetMotorControllerMode:
    case HostFn::GetMotorControllerMode:
    case HostFn::GetAxisEnergy:
    case HostFn::ResetAxisEnergy:
      return call_axes(fn, a, n, s);
    case HostFn::SetSprayGunOn:
    case HostFn::SetSprayGunOff:
    case HostFn::GetPaintGunMinDist:
    case HostFn::GetPaintTargetExtents:
    case HostFn::ResetPaintTargetPaint:
    case HostFn::SetPaintTargetPaintMode:
    case HostFn::GetPaintTargetTriangles:
    case HostFn::SetResultTrianglesColor:
    case HostFn::CalculateSprayThicknessHistogram:
    case HostFn::CalculateAvgSprayThickness:
    case HostFn::CalculateSDSprayThickness:
    case HostFn::CalculatePosAvgSprayThickness:
    case HostFn::CalculatePosSDSprayThickness:
    case HostFn::CalculatePosMinSprayThickness:
    case HostFn::CalculateMinSprayThickness:
    case HostFn::CalculateMaxSprayThickness:
    case HostFn::CalculateSprayCoverage:
      return call_paint(fn, a, n);
    case HostFn::GetCameraPixel:
      return call_camera(fn, a, n);
    case HostFn::CanvasOf:
    case HostFn::CanvasOp:
      return call_canvas(fn, a, n, s, s2);
    case HostFn::WriteUDPData:
      need(1);
      udp().send(s, static_cast<int>(a[0]), s2);
      return 0;
    case HostFn::UDPDataArrived:  // before each run of the script and in ReadUDPData
      text_result_ = udp_.opened() ? udp_.receive() : std::string();
      return 0;
    case HostFn::WriteComPort:
      serial_.write(s);
      return 0;
    case HostFn::ReadComPort:
      text_result_ = serial_.read();
      return 0;
    case HostFn::HUDText:
      hud_ = s;
      {  // TStringList.Text: CR LF after every line; the viewer wants '\n' between lines
        std::string lines;
        for (char c : s)
          if (c != '\r') lines += c;
        while (!lines.empty() && lines.back() == '\n')
          lines.pop_back();
        ctx.set_hud_text(lines);  // drawn over the viewer's 3-D view (SDK 0.9)
      }
      return 0;
    case HostFn::count:
      break;
  }
  fail("invalid host call");
}

}  // namespace s2sim::pascal
