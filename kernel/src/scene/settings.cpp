/// \file
/// Project settings (simtwo-format.md §10.1): `config_Params.ini` when present, else the
/// `[Config]` section of `SimTwo.ini`, else defaults; then scene.xml's `<s2sim>` overrides.

#include "scene/limits.hpp"
#include "scene/loading.hpp"

#include <arpa/inet.h>

#include <charconv>
#include <fstream>
#include <limits>
#include <map>

namespace s2sim::scene::detail {

std::optional<IniSection> read_ini(const std::filesystem::path& file, const std::string& section) {
  std::ifstream in(file);
  if (!in) return std::nullopt;
  IniSection all, wanted;
  bool has_section = false;
  std::string current, line;
  while (std::getline(in, line)) {
    const std::string t = trim_copy(line);
    if (t.empty() || t[0] == ';' || t[0] == '#') continue;
    if (t.front() == '[' && t.back() == ']') {
      current = t.substr(1, t.size() - 2);
      if (current == section) has_section = true;
      continue;
    }
    const auto eq = t.find('=');
    if (eq == std::string::npos) continue;
    const std::string key = trim_copy(t.substr(0, eq));
    const std::string value = trim_copy(t.substr(eq + 1));
    all[key] = value;
    if (current == section) wanted[key] = value;
  }
  return has_section ? wanted : all;
}

namespace {

/// A Delphi-written float: '.' or (in a Portuguese locale) ',' as decimal separator.
std::optional<double> parse_ini_number(std::string text) {
  for (char& c : text)
    if (c == ',') c = '.';
  double v = 0;
  const auto r = std::from_chars(text.data(), text.data() + text.size(), v);
  if (text.empty() || r.ec != std::errc() || r.ptr != text.data() + text.size())
    return std::nullopt;
  return v;
}

}  // namespace

Settings load_settings(const std::filesystem::path& folder) {
  Settings s;
  std::string source = "defaults";
  std::optional<IniSection> ini;
  if ((ini = read_ini(folder / "config_Params.ini", "Config"))) {
    source = "config_Params.ini";
  } else if ((ini = read_ini(folder / "SimTwo.ini", "Config"))) {
    source = "SimTwo.ini";
  }
  s.source = source;
  if (!ini) return s;

  auto get = [&](const char* key) -> std::optional<std::pair<std::string, double>> {
    auto it = ini->find(key);
    if (it == ini->end()) return std::nullopt;
    auto v = parse_ini_number(it->second);
    return std::pair{it->second, v ? *v : std::numeric_limits<double>::quiet_NaN()};
  };
  auto fail = [&](const char* key, const std::string& msg) {
    throw Error(ErrorKind::scene, Location{source, "[Config]", key}, msg);
  };
  // The step drives everything: a broken one is an error, not a silent default.
  if (auto dt = get("EditOde_dt_Text")) {
    if (!(dt->second > 0))
      fail("EditOde_dt_Text", "physics step must be a number > 0 (ms), got '" + dt->first + "'");
    s.physics_step_s = dt->second / 1000.0;
  }
  if (auto p = get("EditScriptPeriod_Text")) {
    if (!(p->second > 0))
      fail("EditScriptPeriod_Text",
           "script period must be a number > 0 (ms), got '" + p->first + "'");
    s.control_period_s = p->second / 1000.0;
  }
  auto number = [&](const char* key, double& out) {
    if (auto v = get(key)) {
      if (v->second != v->second) fail(key, "not a number: '" + v->first + "'");
      out = v->second;
    }
  };
  number("EditDefaultFriction_Text", s.default_friction);
  number("EditWindSpeedX_Text", s.wind_m_s.x);
  number("EditWindSpeedY_Text", s.wind_m_s.y);
  number("EditWindSpeedZ_Text", s.wind_m_s.z);
  number("EditODE_ERP_Text", s.erp);
  number("EditODE_CFM_Text", s.cfm);
  if (auto it = ini->find("CBIRNoise_Checked"); it != ini->end()) {
    auto b = parse_bool(it->second);
    if (!b) fail("CBIRNoise_Checked", "not a boolean: '" + it->second + "'");
    s.ir_noise = *b;
  }
  return s;
}

void apply_s2sim_settings(const Reader& r, const Element& el, Settings& s) {
  auto positive = [&](const Element& c, const char* attr, double& out, double scale) {
    if (auto v = r.optional_number(c, attr)) {
      if (!(*v > 0)) r.fail(c, attr, "must be > 0, got " + format_number(*v));
      out = *v * scale;
    }
  };
  bool any = false;
  // A scene with an <s2sim> element is written for S2Sim: its gains are tuned for S2Sim's
  // control law unless it says otherwise.
  s.control_semantics = ControlSemantics::s2sim;
  for (const Element& c : el.children) {
    if (c.name == "physics") {
      positive(c, "step_ms", s.physics_step_s, 1e-3);
      if (r.has(c, "step_ms") && (s.physics_step_s < limits::kMinPhysicsStep_s ||
                                  s.physics_step_s > limits::kMaxPhysicsStep_s))
        r.fail(c, "step_ms",
               "must be from " + format_number(limits::kMinPhysicsStep_s * 1e3) + " to " +
                   format_number(limits::kMaxPhysicsStep_s * 1e3) + " ms, got " +
                   format_number(s.physics_step_s * 1e3));
      const auto substeps = r.integer(c, "substeps", s.substeps);
      if (substeps < 1 || substeps > limits::kMaxSubsteps)
        r.fail(c, "substeps",
               "must be an integer from 1 to " + std::to_string(limits::kMaxSubsteps) + ", got " +
                   std::to_string(substeps));
      s.substeps = static_cast<int>(substeps);
      any = true;
    } else if (c.name == "control") {
      positive(c, "period_ms", s.control_period_s, 1e-3);
      if (r.has(c, "semantics")) {
        const std::string semantics = r.text(c, "semantics", "");
        if (semantics == "simtwo") {
          s.control_semantics = ControlSemantics::simtwo;
        } else if (semantics != "s2sim") {
          r.fail(c, "semantics", "must be 'simtwo' or 's2sim', got '" + semantics + "'");
        }
      }
      any = true;
    } else if (c.name == "friction") {
      positive(c, "default", s.default_friction, 1);
      any = true;
    } else if (c.name == "contact") {
      positive(c, "recovery_speed", s.contact_recovery_speed_m_s, 1);
      any = true;
    } else if (c.name == "walls") {
      s.world_walls = r.boolean(c, "active", s.world_walls);
      positive(c, "distance", s.world_wall_distance_m, 1);
      any = true;
    } else if (c.name == "udp") {
      if (r.has(c, "address")) {
        const std::string address = r.text(c, "address", "");
        in_addr parsed{};
        if (::inet_pton(AF_INET, address.c_str(), &parsed) != 1)
          r.fail(c, "address", "must be a numeric IPv4 address, got '" + address + "'");
        s.script_udp_address = address;
      }
      const auto port = r.integer(c, "port", s.script_udp_port);
      if (port < 0 || port > 65535)
        r.fail(c, "port", "must be an integer from 0 to 65535, got " + std::to_string(port));
      s.script_udp_port = static_cast<int>(port);
      any = true;
    } else if (c.name == "runtime_things") {
      const auto count = r.integer(c, "count", 0);
      if (count < 0 || count > limits::kMaxRuntimeThings)
        r.fail(c, "count",
               "must be an integer from 0 to " + std::to_string(limits::kMaxRuntimeThings) +
                   ", got " + std::to_string(count));
      s.runtime_things = static_cast<int>(count);
      any = true;
    }
  }
  if (any) s.source += " + scene.xml <s2sim>";
}

}  // namespace s2sim::scene::detail
