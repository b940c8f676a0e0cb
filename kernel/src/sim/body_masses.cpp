// A body's mass properties set while running (SimTwo's SetSolidMass; docs/format.md, "Masses
// set while running"): the multibody model and contact take them at once. A snapshot holds
// them (segment `masses`), a reset restores the scene's.
#include "scene/limits.hpp"
#include "scene/mass.hpp"
#include "sim/names.hpp"
#include "sim/simulation_impl.hpp"

#include <cmath>

namespace s2sim {
namespace {

/// Numbers per body in the `masses` segment: changed, mass, centre of mass (3), the inertia's
/// six distinct entries (xx, yy, zz, xy, xz, yz).
constexpr std::size_t kMassNumbers = 11;
/// The heaviest body a change may ask for, kg.
constexpr double kMaxBodyMass_kg = 1e9;

using sim::short_decimal;

bool same(const Simulation::MassProperties& a, const Simulation::MassProperties& b) {
  if (a.mass_kg != b.mass_kg || a.com_m.x != b.com_m.x || a.com_m.y != b.com_m.y ||
      a.com_m.z != b.com_m.z)
    return false;
  for (int i = 0; i < 3; ++i)
    for (int j = 0; j < 3; ++j)
      if (a.inertia_kg_m2.m[i][j] != b.inertia_kg_m2.m[i][j]) return false;
  return true;
}

}  // namespace

Simulation::MassProperties Simulation::MassProperties::with_mass(double new_mass_kg) const {
  MassProperties out = *this;
  const double ratio = mass_kg > 0 && std::isfinite(new_mass_kg) ? new_mass_kg / mass_kg : 0;
  for (int i = 0; i < 3; ++i)
    for (int j = 0; j < 3; ++j)
      out.inertia_kg_m2.m[i][j] *= ratio;
  out.mass_kg = new_mass_kg;
  return out;
}

Simulation::MassProperties Simulation::Impl::mass_of(int body) const {
  const BodyMass& b = body_masses[static_cast<std::size_t>(body)];
  return b.changed ? b.mass : base_mass(body);
}

void Simulation::Impl::check_mass(int body, const MassProperties* mass, const char* call) const {
  if (body <= 0 || body >= static_cast<int>(poses.size()))
    throw Error(ErrorKind::usage, std::string(call) + ": no body " + std::to_string(body) +
                                      " (bodies are 1 to " + std::to_string(poses.size() - 1) +
                                      ")");
  if (mass == nullptr) return;
  const std::string who = std::string(call) + ": body " + body_label(body) + ": ";
  if (!(mass->mass_kg > 0) || !(mass->mass_kg <= kMaxBodyMass_kg))
    throw Error(ErrorKind::usage, who + "the mass must be positive and at most " +
                                      short_decimal(kMaxBodyMass_kg) + " kg, got " +
                                      short_decimal(mass->mass_kg));
  const Vec3& c = mass->com_m;
  if (!std::isfinite(c.x) || !std::isfinite(c.y) || !std::isfinite(c.z) ||
      std::abs(c.x) > scene::limits::kMaxLength_m || std::abs(c.y) > scene::limits::kMaxLength_m ||
      std::abs(c.z) > scene::limits::kMaxLength_m)
    throw Error(ErrorKind::usage, who + "the centre of mass must be finite and within " +
                                      short_decimal(scene::limits::kMaxLength_m) + " m, got " +
                                      short_decimal(c.x) + ", " + short_decimal(c.y) + ", " +
                                      short_decimal(c.z));
  const std::string why = scene::inertia_problem(mass->mass_kg, mass->inertia_kg_m2);
  if (!why.empty()) throw Error(ErrorKind::usage, who + why);
}

void Simulation::Impl::apply_body_mass(int body) {
  const MassProperties mass = mass_of(body);
  body_mass_kg[static_cast<std::size_t>(body)] = mass.mass_kg;
  if (multibody->is_loose(body)) {
    apply_loose_mass(body, mass);
    return;
  }
  multibody->set_jointed_mass(body, mass.mass_kg, mass.com_m, mass.inertia_kg_m2);
  // What a push meets changes over the whole tree: every jointed body's apparent mass, and
  // the trees' mobilities.
  const std::vector<double> apparent = multibody->apparent_mass_kg();
  for (int b = 1; b < static_cast<int>(apparent.size()); ++b) {
    if (multibody->is_loose(b)) continue;
    const MassProperties own = b == body ? mass : mass_of(b);
    contacts->set_jointed_body(b, apparent[static_cast<std::size_t>(b)], own.com_m,
                               own.inertia_kg_m2);
  }
  contacts->set_mobility(multibody->contact_mobility());
}

void Simulation::Impl::set_body_mass(int body, const MassProperties& mass) {
  check_mass(body, &mass, "set_body_mass");
  BodyMass& b = body_masses[static_cast<std::size_t>(body)];
  b.changed = true;
  b.mass = mass;
  apply_body_mass(body);
}

void Simulation::Impl::init_body_masses() {
  body_masses.assign(poses.size(), BodyMass{});
  body_mass_kg.assign(poses.size(), 0.0);
  for (std::size_t b = 1; b < poses.size(); ++b)
    body_mass_kg[b] = scene.bodies[b - 1].mass_kg;
  world.body_mass_kg = body_mass_kg.data();
  world.request_mass = &Simulation::Impl::request_mass;
}

void Simulation::Impl::reset_body_masses() {
  for (std::size_t b = 1; b < body_masses.size(); ++b) {
    if (!body_masses[b].changed) continue;
    body_masses[b] = BodyMass{};
    apply_body_mass(static_cast<int>(b));
  }
}

void Simulation::Impl::declare_body_masses_state() {
  layout.add(
      "masses", kMassNumbers * (body_masses.size() - 1),
      [this](double* out) {
        for (std::size_t b = 1; b < body_masses.size(); ++b, out += kMassNumbers) {
          const BodyMass& o = body_masses[b];
          const Mat3& I = o.mass.inertia_kg_m2;
          const double numbers[kMassNumbers] = {o.changed ? 1.0 : 0.0,
                                                o.mass.mass_kg,
                                                o.mass.com_m.x,
                                                o.mass.com_m.y,
                                                o.mass.com_m.z,
                                                I.m[0][0],
                                                I.m[1][1],
                                                I.m[2][2],
                                                I.m[0][1],
                                                I.m[0][2],
                                                I.m[1][2]};
          std::copy(numbers, numbers + kMassNumbers, out);
        }
      },
      [this](const double* in, std::size_t) {
        for (std::size_t b = 1; b < body_masses.size(); ++b, in += kMassNumbers) {
          const Mat3 I{{{in[5], in[8], in[9]}, {in[8], in[6], in[10]}, {in[9], in[10], in[7]}}};
          const BodyMass o{in[0] != 0, {in[1], {in[2], in[3], in[4]}, I}};
          BodyMass& now = body_masses[b];
          // A restore changes nothing it need not (run-ahead restores): a jointed body's
          // change rebuilds the multibody model.
          if (o.changed == now.changed && same(o.mass, now.mass)) continue;
          now = o;
          apply_body_mass(static_cast<int>(b));
        }
      });
}

void Simulation::Impl::request_mass(const void* impl, std::int32_t body, double mass_kg,
                                    const Vec3* com_m, const Mat3* inertia_kg_m2) {
  auto& m = *static_cast<Simulation::Impl*>(const_cast<void*>(impl));
  m.check_mass(body, nullptr, "request_mass");
  MassProperties mass = m.mass_of(body).with_mass(mass_kg);
  if (com_m != nullptr) mass.com_m = *com_m;
  if (inertia_kg_m2 != nullptr) mass.inertia_kg_m2 = *inertia_kg_m2;
  m.check_mass(body, &mass, "request_mass");  // refused to the component that asked
  if (m.pending_body_changes.size() < m.pending_body_changes.capacity())
    m.pending_body_changes.push_back(
        {PendingBodyChange::Kind::mass, body, mass.com_m, mass.mass_kg, mass.inertia_kg_m2});
  else
    m.set_body_mass(body, mass);  // more requests than room in one stage: at once
}

void Simulation::set_body_mass(int body, const MassProperties& mass) {
  impl_->set_body_mass(body, mass);
  impl_->changed();
}

void Simulation::set_body_mass(int body, double mass_kg) {
  impl_->check_mass(body, nullptr, "set_body_mass");
  set_body_mass(body, impl_->mass_of(body).with_mass(mass_kg));
}

Simulation::MassProperties Simulation::body_mass(int body) const {
  impl_->check_mass(body, nullptr, "body_mass");
  return impl_->mass_of(body);
}

}  // namespace s2sim
