/// \file
/// Drive-train children shared by `<articulations>` and `<wheels>` (simtwo-format.md §4.10).

#include "scene/loading.hpp"

#include <cmath>

namespace s2sim::scene::detail {
namespace {

bool named(const Element& child, std::string_view base, std::string_view suffix) {
  return child.name.size() == base.size() + suffix.size() &&
         child.name.compare(0, base.size(), base) == 0 &&
         child.name.compare(base.size(), std::string::npos, suffix) == 0;
}

std::string lower(std::string s) {
  for (char& c : s)
    c = static_cast<char>(std::tolower(static_cast<unsigned char>(c)));
  return s;
}

}  // namespace

bool read_drive_child(LoadContext& ctx, const Reader& r, const Element& c, std::string_view suffix,
                      DriveTrain& d) {
  if (named(c, "motor", suffix)) {
    Motor& m = d.motor;
    m.resistance_ohm = r.number(c, "ri", m.resistance_ohm);
    m.inductance_H = r.number(c, "li", m.inductance_H);
    m.torque_constant_Nm_A = r.number(c, "ki", m.torque_constant_Nm_A);
    m.voltage_max_V = r.number(c, "vmax", m.voltage_max_V);
    m.current_max_A = r.number(c, "imax", m.current_max_A);
    m.active = r.boolean(c, "active", m.active);
    m.simple = r.boolean(c, "simple", m.simple);
    if (const std::string* b = c.attribute("backemf")) {  // S2Sim extension
      const std::string v = lower(*b);
      if (v == "physical")
        m.back_emf_simtwo = false;
      else if (v == "simtwo")
        m.back_emf_simtwo = true;
      else
        r.fail(c, "backemf", "must be 'physical' or 'simtwo', got '" + *b + "'");
    }
    return true;
  }
  if (named(c, "gear", suffix)) {
    Gear& g = d.gear;
    g.ratio = r.number(c, "ratio", g.ratio);
    g.ke = r.number(c, "ke", g.ke);
    g.be = r.number(c, "be", g.be);
    g.ke2 = r.number(c, "ke2", g.ke2);
    g.kv2 = r.number(c, "kv2", g.kv2);
    return true;
  }
  if (named(c, "rotor", suffix)) {
    Rotor& ro = d.rotor;
    ro.inertia_kg_m2 = r.number(c, "J", r.number(c, "j", ro.inertia_kg_m2));
    ro.viscous_Nms_rad = r.number(c, "bv", ro.viscous_Nms_rad);
    ro.coulomb_Nm = r.number(c, "fc", ro.coulomb_Nm);
    return true;
  }
  if (named(c, "encoder", suffix)) {
    Encoder& e = d.encoder;
    // SimTwo rounds the tick count (RobotTh_wo_comm writes ppr='700.8').
    if (auto ppr = r.optional_number(c, "ppr")) e.ppr = std::llround(*ppr);
    e.mean = r.number(c, "mean", e.mean);
    e.stdev = r.number(c, "stdev", e.stdev);
    if (auto period_ms = r.optional_number(c, "period")) {  // S2Sim extension
      if (!(*period_ms > 0)) r.fail(c, "period", "must be > 0, got " + format_number(*period_ms));
      e.period_s = *period_ms / 1000.0;
    }
    return true;
  }
  if (named(c, "controller", suffix)) {
    MotorController& k = d.controller;
    if (const std::string* mode = c.attribute("mode")) {
      const std::string m = lower(*mode);
      if (m == "pidspeed") {
        k.mode = ControllerMode::pid_speed;
      } else if (m == "pidposition") {
        k.mode = ControllerMode::pid_position;
      } else if (m == "state" || m == "statefeedback") {
        k.mode = ControllerMode::state;
      } else {
        // SimTwo silently keeps the previous mode for an unknown string; a typo would leave
        // the axis under another law, so S2Sim refuses it.
        r.fail(c, "mode",
               "unknown controller mode '" + *mode + "' (expected pidspeed, pidposition or state)");
      }
    } else {
      k.mode = ControllerMode::pid_speed;  // quirk 7b: an absent mode resets to pidspeed
    }
    k.kp = r.number(c, "kp", k.kp);
    k.ki = r.number(c, "ki", k.ki);
    k.kd = r.number(c, "kd", k.kd);
    k.kf = r.number(c, "kf", k.kf);
    if (auto period_ms = r.optional_number(c, "period")) {
      if (!(*period_ms > 0)) r.fail(c, "period", "must be > 0, got " + format_number(*period_ms));
      k.period_s = *period_ms / 1000.0;
    }
    k.active = r.boolean(c, "active", k.active);
    if (const std::string* law = c.attribute("law")) {  // S2Sim extension
      const std::string v = lower(*law);
      if (v == "textbook")
        k.simtwo_law = false;
      else if (v == "simtwo")
        k.simtwo_law = true;
      else
        r.fail(c, "law", "must be 'textbook' or 'simtwo', got '" + *law + "'");
    }
    return true;
  }
  if (named(c, "friction", suffix)) {
    d.friction.viscous = r.number(c, "bv", d.friction.viscous);
    d.friction.coulomb = r.number(c, "fc", d.friction.coulomb);
    return true;  // `coulomblimit` is obsolete
  }
  if (named(c, "spring", suffix)) {
    d.spring.stiffness = r.number(c, "k", d.spring.stiffness);
    d.spring.zero_position = r.number(c, "zeropos", d.spring.zero_position);
    return true;
  }
  return false;
}

}  // namespace s2sim::scene::detail
