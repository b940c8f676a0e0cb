// The host functions on an axis's drive train beyond its references (simtwo-script-api.md §4):
// its spring and friction, its motor controller's gains and mode (inputs of the drive_train
// plugin, read every tick) and SimTwo's energy meter (the motor's energy_drawn, from a zero
// the script state keeps).
#include "script_controller.hpp"

namespace s2sim::pascal {
namespace {
constexpr const char* kModeNames[] = {"pidspeed", "pidposition", "state"};
}

double ScriptController::call_axes(HostFn fn, const double* a, int n, const std::string& s) {
  StepContext& ctx = *ctx_;
  auto need = [&](int count) { require_arguments(fn, n, count); };
  auto driven = [&]() -> AxisRef& {
    need(2);
    AxisRef& ax = axis(a[0], a[1]);
    if (ax.path.empty())
      fail("axis " + std::to_string(static_cast<int>(a[1])) + " of robot " +
           std::to_string(static_cast<int>(a[0])) + " is a Fixed or Ball joint");
    if (!ax.has_motor) fail("axis " + ax.path + " has no drive train");
    return ax;
  };
  switch (fn) {
    case HostFn::SetAxisSpring: {
      need(4);
      AxisRef& ax = driven();
      ctx.set_input(ax.spring_k, a[2]);
      ctx.set_input(ax.spring_zeropos, a[3]);
      return 0;
    }
    case HostFn::SetFrictionDef: {
      need(5);
      AxisRef& ax = driven();
      if (a[2] < 0 || a[3] < 0)
        fail("SetFrictionDef: " +
             std::string(a[2] < 0 ? "Bv = " + number_text(a[2]) : "Fc = " + number_text(a[3])) +
             " must be >= 0");
      ctx.set_input(ax.friction_bv, a[2]);
      ctx.set_input(ax.friction_fc, a[3]);
      return 0;  // the Coulomb limit is ignored, as by SimTwo
    }
    case HostFn::GetFrictionDef: {
      AxisRef& ax = driven();
      numbers_.assign({ctx.input(ax.friction_bv), ctx.input(ax.friction_fc), 0.0});  // as SimTwo
      return 0;
    }
    case HostFn::SetMotorControllerPars: {  // nKi, nKd, nKp, nKf: SimTwo's order
      need(6);
      AxisRef& ax = driven();
      ctx.set_input(ax.controller[0], a[4]);
      ctx.set_input(ax.controller[1], a[2]);
      ctx.set_input(ax.controller[2], a[3]);
      ctx.set_input(ax.controller[3], a[5]);
      return 0;
    }
    case HostFn::GetMotorControllerPars: {  // TMotorControllerPars: Ki, Kd, Kp, Kf
      AxisRef& ax = driven();
      numbers_.assign({ctx.input(ax.controller[1]), ctx.input(ax.controller[2]),
                       ctx.input(ax.controller[0]), ctx.input(ax.controller[3])});
      return 0;
    }
    case HostFn::SetMotorControllerMode: {
      AxisRef& ax = driven();
      std::string mode;
      for (char c : s)
        mode += static_cast<char>(std::tolower(static_cast<unsigned char>(c)));
      if (mode == "statefeedback") mode = "state";
      for (int m = 0; m < 3; ++m)
        if (mode == kModeNames[m]) {
          ctx.set_input(ax.controller[4], m);
          return 0;
        }
      fail("Invalid SetMotorControllerMode parameter: " + s);
    }
    case HostFn::GetMotorControllerMode: {
      AxisRef& ax = driven();
      const int m = static_cast<int>(ctx.input(ax.controller[4]));
      text_result_ = m >= 0 && m < 3 ? kModeNames[m] : "";
      return 0;
    }
    case HostFn::GetAxisEnergy: {
      AxisRef& ax = driven();
      return ctx.signal(ax.energy_drawn) -
             ctx.state(state_)[3 + axis_count_ + static_cast<std::size_t>(ax.index)];
    }
    case HostFn::ResetAxisEnergy: {
      AxisRef& ax = driven();
      ctx.state(state_)[3 + axis_count_ + static_cast<std::size_t>(ax.index)] =
          ctx.signal(ax.energy_drawn);
      return 0;
    }
    default:
      fail("invalid host call");
  }
}

}  // namespace s2sim::pascal
