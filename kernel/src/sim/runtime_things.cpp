// Things added and deleted while running (docs/format.md, "Things added while running"): a
// thing added takes one of the spare bodies reserved at load (scene::reserve_runtime_things),
// given its primitive, mass and pose; a deleted thing is parked, touching nothing, until a
// reset. Everything a spare body is lies in the state layout, so snapshots hold it.
#include "scene/limits.hpp"
#include "scene/mass.hpp"
#include "sim/names.hpp"
#include "sim/simulation_impl.hpp"

#include <cmath>

namespace s2sim {
namespace {

/// Numbers per thing in the `things` segment: present, shape, size x, y, z, mass, r, g, b,
/// fixed.
constexpr std::size_t kThingNumbers = 10;

scene::Geom geom_of(const ThingSpec& spec, const std::string& id) {
  scene::Geom g;
  g.id = id;
  switch (spec.shape) {
    case ThingShape::box:
      g.shape.type = scene::ShapeType::box;
      g.shape.size_m = spec.size_m;
      break;
    case ThingShape::sphere:
      g.shape.type = scene::ShapeType::sphere;
      g.shape.radius_m = spec.size_m.x;
      break;
    case ThingShape::cylinder:
      g.shape.type = scene::ShapeType::cylinder;
      g.shape.radius_m = spec.size_m.x;
      g.shape.length_m = spec.size_m.z;
      break;
  }
  g.visual.color = {spec.rgb[0], spec.rgb[1], spec.rgb[2], 1};
  return g;
}

using sim::short_decimal;

/// Throws (usage) naming the thing and the value for a spec that is not a body.
void check_spec(const ThingSpec& spec, std::string_view id) {
  const std::string who = "add_thing '" + std::string(id) + "': ";
  auto size_ok = [](double v) { return v > 0 && v <= scene::limits::kMaxLength_m; };
  const char* shape = spec.shape == ThingShape::box      ? "box"
                      : spec.shape == ThingShape::sphere ? "sphere"
                                                         : "cylinder";
  if (spec.shape != ThingShape::box && spec.shape != ThingShape::sphere &&
      spec.shape != ThingShape::cylinder)
    throw Error(ErrorKind::usage,
                who + "unknown shape " + std::to_string(static_cast<int>(spec.shape)));
  const bool sizes_ok =
      spec.shape == ThingShape::box
          ? size_ok(spec.size_m.x) && size_ok(spec.size_m.y) && size_ok(spec.size_m.z)
      : spec.shape == ThingShape::sphere ? size_ok(spec.size_m.x)
                                         : size_ok(spec.size_m.x) && size_ok(spec.size_m.z);
  if (!sizes_ok)
    throw Error(ErrorKind::usage, who + "a " + shape + "'s size must be positive and at most " +
                                      short_decimal(scene::limits::kMaxLength_m) + " m, got " +
                                      short_decimal(spec.size_m.x) + ", " +
                                      short_decimal(spec.size_m.y) + ", " +
                                      short_decimal(spec.size_m.z));
  if (!(spec.mass_kg > 0) || !std::isfinite(spec.mass_kg))
    throw Error(ErrorKind::usage,
                who + "mass must be positive, got " + short_decimal(spec.mass_kg));
  const Pose& p = spec.pose;
  double sum = p.position.x + p.position.y + p.position.z;
  double worst = 0;  // |R·Rᵀ − I|
  for (int i = 0; i < 3; ++i)
    for (int j = 0; j < 3; ++j) {
      sum += p.rotation.m[i][j];
      double dot = 0;
      for (int k = 0; k < 3; ++k)
        dot += p.rotation.m[i][k] * p.rotation.m[j][k];
      worst = std::max(worst, std::abs(dot - (i == j ? 1.0 : 0.0)));
    }
  if (!std::isfinite(sum)) throw Error(ErrorKind::usage, who + "the pose is not finite");
  if (worst > 1e-6) throw Error(ErrorKind::usage, who + "the rotation is not orthonormal");
  for (double c : spec.rgb)
    if (!(c >= 0 && c <= 1))
      throw Error(ErrorKind::usage,
                  who + "colour components must be from 0 to 1, got " + short_decimal(c));
}

}  // namespace

void Simulation::Impl::init_things() {
  thing_views.clear();
  for (int b : scene.things)
    thing_views.push_back({b + 1, false, true, scene.bodies[static_cast<std::size_t>(b)].id, {}});
  for (int b : scene.runtime_things)
    thing_views.push_back({b + 1, true, false, std::string(), {}});
  thing_of_body.assign(poses.size(), -1);
  for (std::size_t t = 0; t < thing_views.size(); ++t)
    thing_of_body[static_cast<std::size_t>(thing_views[t].body)] = static_cast<std::int32_t>(t);
  // Room for every request of a stage: one add or delete per thing, twice.
  pending_things.reserve(2 * thing_views.size());
  for (std::size_t t = 0; t < thing_views.size(); ++t)
    if (thing_views[t].added) apply_thing(t, false);
  world.request_add_thing = &Simulation::Impl::request_add_thing;
  world.request_delete_thing = &Simulation::Impl::request_delete_thing;
  obstacle_present.assign(scene.obstacles.size(), 1);
  pending_obstacles.reserve(2 * obstacle_present.size());
  world.request_delete_obstacle = &Simulation::Impl::request_delete_obstacle;
}

void Simulation::Impl::reset_things() {
  pending_things.clear();
  pending_obstacles.clear();
  for (std::size_t o = 0; o < obstacle_present.size(); ++o)
    if (!obstacle_present[o]) {
      obstacle_present[o] = 1;
      apply_obstacle(o);
    }
  for (std::size_t t = 0; t < thing_views.size(); ++t) {
    ThingView& v = thing_views[t];
    const bool changed = v.present != !v.added || (v.added && !v.id.empty());
    v.present = !v.added;
    if (v.added) {
      v.id.clear();
      v.spec = ThingSpec{};
    }
    if (changed) apply_thing(t, false);  // the multibody's reset put it back at its load pose
  }
}

void Simulation::Impl::apply_thing(std::size_t t, bool place) {
  const ThingView& v = thing_views[t];
  const int body = v.body;
  const scene::Body& loaded = scene.bodies[static_cast<std::size_t>(body - 1)];
  // The spare bodies are counted after the scene's things in the park order.
  const int park_slot = static_cast<int>(t < scene.things.size() ? scene.runtime_things.size() + t
                                                                 : t - scene.things.size());
  if (v.added) {
    const std::int32_t shape = shapes->first_shape_of(body);
    const scene::Geom g = v.present ? geom_of(v.spec, v.id) : loaded.geoms[0];
    shapes->reshape(shape, g);
    contacts->reshaped(shape);
    ray_caster->reshaped(shape);
  }
  apply_body_mass(body);
  contacts->set_parked(body, !v.present);
  if (place)
    multibody->place_free_body(body,
                               v.present ? v.spec.pose : scene::runtime_thing_park_pose(park_slot));
}

Simulation::MassProperties Simulation::Impl::base_mass(int body) const {
  const scene::Body& loaded = scene.bodies[static_cast<std::size_t>(body - 1)];
  const std::int32_t t = thing_of_body[static_cast<std::size_t>(body)];
  if (t < 0 || !thing_views[static_cast<std::size_t>(t)].added)
    return {loaded.mass_kg, loaded.com_m, loaded.inertia_kg_m2};
  // An added thing: a uniform solid of its spec, its centre at its origin; a spare at rest
  // weighs what it was loaded with.
  const ThingView& v = thing_views[static_cast<std::size_t>(t)];
  if (!v.present) return {loaded.mass_kg, {}, loaded.inertia_kg_m2};
  return {v.spec.mass_kg, {}, scene::uniform_inertia(geom_of(v.spec, v.id).shape, v.spec.mass_kg)};
}

void Simulation::Impl::apply_loose_mass(int body, const MassProperties& mass) {
  const scene::Body& loaded = scene.bodies[static_cast<std::size_t>(body - 1)];
  const std::int32_t t = thing_of_body[static_cast<std::size_t>(body)];
  bool gravity = loaded.gravity, fixed = false;
  if (t >= 0) {
    const ThingView& v = thing_views[static_cast<std::size_t>(t)];
    // An added thing falls unless held; a scene thing is weightless while deleted, so that it
    // stays put.
    fixed = v.added && v.present && v.spec.fixed;
    gravity = v.present && !fixed && (v.added || loaded.gravity);
  }
  multibody->set_loose_mass(body, mass.mass_kg, mass.com_m, mass.inertia_kg_m2, gravity, fixed);
  contacts->set_free_body(body, mass.mass_kg, mass.com_m, mass.inertia_kg_m2, gravity, fixed);
}

int Simulation::Impl::take_spare_thing(const ThingSpec& spec, std::string_view id) {
  check_spec(spec, id);
  for (std::size_t t = scene.things.size(); t < thing_views.size(); ++t) {
    ThingView& v = thing_views[t];
    if (v.present) continue;
    v.present = true;
    v.id = std::string(id);
    v.spec = spec;
    body_masses[static_cast<std::size_t>(v.body)] = BodyMass{};  // nor a mass it was given
    annotations.forget_body(v.body);                             // nor its colours and mesh
    // A surface a former holder was given is not the new thing's.
    if (body_shapes[static_cast<std::size_t>(v.body)].surfaced) {
      body_shapes[static_cast<std::size_t>(v.body)] = BodyShape{};
      apply_body_shape(v.body);
    }
    pending_things.push_back(static_cast<std::int32_t>(t));
    return v.body;
  }
  throw Error(ErrorKind::usage,
              "add_thing '" + std::string(id) + "': all " +
                  std::to_string(scene.runtime_things.size()) +
                  " spare bodies hold things; raise <s2sim><runtime_things count> in the scene "
                  "(docs/format.md, \"Things added while running\")");
}

void Simulation::Impl::mark_thing_deleted(int body) {
  const std::int32_t t = body > 0 && body < static_cast<int>(thing_of_body.size())
                             ? thing_of_body[static_cast<std::size_t>(body)]
                             : -1;
  if (t < 0)
    throw Error(ErrorKind::usage,
                "delete_thing: body " + body_label(body) + " is not a thing of the scene");
  ThingView& v = thing_views[static_cast<std::size_t>(t)];
  if (!v.added && !multibody->is_loose(body))
    throw Error(ErrorKind::usage, "delete_thing: thing " + body_label(body) +
                                      " is jointed to something and cannot be deleted");
  if (!v.present) return;
  v.present = false;
  pending_things.push_back(t);
}

void Simulation::Impl::apply_pending_things() {
  for (const std::int32_t t : pending_things)
    apply_thing(static_cast<std::size_t>(t), true);
  pending_things.clear();
  for (const std::int32_t o : pending_obstacles)
    apply_obstacle(static_cast<std::size_t>(o));
  pending_obstacles.clear();
}

std::int32_t Simulation::Impl::request_add_thing(const void* impl, const ThingSpec& spec,
                                                 const char* id, std::size_t id_size) {
  auto& m = *static_cast<Simulation::Impl*>(const_cast<void*>(impl));
  return m.take_spare_thing(spec, std::string_view(id, id_size));
}

void Simulation::Impl::request_delete_thing(const void* impl, std::int32_t body) {
  auto& m = *static_cast<Simulation::Impl*>(const_cast<void*>(impl));
  m.mark_thing_deleted(body);
}

void Simulation::Impl::declare_things_state() {
  if (!obstacle_present.empty())
    layout.add(
        "obstacles", obstacle_present.size(),
        [this](double* out) {
          for (const char present : obstacle_present)
            *out++ = present ? 1.0 : 0.0;
        },
        [this](const double* in, std::size_t) {
          for (std::size_t o = 0; o < obstacle_present.size(); ++o) {
            obstacle_present[o] = in[o] != 0 ? 1 : 0;
            apply_obstacle(o);
          }
        });
  if (scene.runtime_things.empty() && scene.things.empty()) return;
  layout.add(
      "things", kThingNumbers * thing_views.size(),
      [this](double* out) {
        for (const ThingView& v : thing_views) {
          const double numbers[kThingNumbers] = {
              v.present ? 1.0 : 0.0, static_cast<double>(v.spec.shape),
              v.spec.size_m.x,       v.spec.size_m.y,
              v.spec.size_m.z,       v.spec.mass_kg,
              v.spec.rgb[0],         v.spec.rgb[1],
              v.spec.rgb[2],         v.spec.fixed ? 1.0 : 0.0};
          std::copy(numbers, numbers + kThingNumbers, out);
          out += kThingNumbers;
        }
      },
      [this](const double* in, std::size_t) {
        for (std::size_t t = 0; t < thing_views.size(); ++t, in += kThingNumbers) {
          ThingView& v = thing_views[t];
          v.present = in[0] != 0;
          v.spec.shape = static_cast<ThingShape>(static_cast<int>(in[1]));
          v.spec.size_m = {in[2], in[3], in[4]};
          v.spec.mass_kg = in[5];
          std::copy(in + 6, in + 9, v.spec.rgb);
          v.spec.fixed = in[9] != 0;
          apply_thing(t, false);  // the poses are the multibody's segments
        }
      });
  // The added things' IDs: per spare body its length, then its characters.
  auto ids_size = [this] {
    std::size_t n = 0;
    for (std::size_t t = scene.things.size(); t < thing_views.size(); ++t)
      n += 1 + thing_views[t].id.size();
    return n;
  };
  if (scene.runtime_things.empty()) return;
  layout.add_variable(
      "things/ids", 1, ids_size,
      [this](double* out) {
        for (std::size_t t = scene.things.size(); t < thing_views.size(); ++t) {
          const std::string& id = thing_views[t].id;
          *out++ = static_cast<double>(id.size());
          for (const char c : id)
            *out++ = static_cast<double>(static_cast<unsigned char>(c));
        }
      },
      [this](const double* in, std::size_t count) {
        const double* end = in + count;
        for (std::size_t t = scene.things.size(); t < thing_views.size(); ++t) {
          std::string& id = thing_views[t].id;
          id.clear();
          if (in == end) continue;  // a shorter segment: the rest have none
          const auto n = static_cast<std::size_t>(*in++);
          for (std::size_t k = 0; k < n && in < end; ++k)
            id.push_back(static_cast<char>(static_cast<int>(*in++)));
        }
      });
}

void Simulation::Impl::apply_obstacle(std::size_t o) {
  const std::int32_t shape = shapes->statics()[o];
  contacts->set_shape_parked(shape, !obstacle_present[o]);
  ray_caster->set_shape_parked(shape, !obstacle_present[o]);
}

void Simulation::Impl::mark_obstacle_deleted(int index) {
  if (index < 0 || index >= static_cast<int>(obstacle_present.size()))
    throw Error(ErrorKind::usage, "delete_obstacle: no obstacle " + std::to_string(index) +
                                      " (the scene has " + std::to_string(obstacle_present.size()) +
                                      ")");
  if (!obstacle_present[static_cast<std::size_t>(index)]) return;
  obstacle_present[static_cast<std::size_t>(index)] = 0;
  pending_obstacles.push_back(index);
}

void Simulation::Impl::request_delete_obstacle(const void* impl, std::int32_t obstacle) {
  auto& m = *static_cast<Simulation::Impl*>(const_cast<void*>(impl));
  m.mark_obstacle_deleted(obstacle);
}

void Simulation::delete_obstacle(int index) {
  Impl& m = *impl_;
  m.mark_obstacle_deleted(index);
  m.apply_pending_things();
  m.changed();
}

bool Simulation::obstacle_present(int index) const {
  const auto& present = impl_->obstacle_present;
  return index >= 0 && index < static_cast<int>(present.size()) &&
         present[static_cast<std::size_t>(index)] != 0;
}

int Simulation::add_thing(const ThingSpec& spec, std::string_view id) {
  Impl& m = *impl_;
  const int body = m.take_spare_thing(spec, id);
  m.apply_pending_things();
  m.refresh();
  m.changed();
  return body;
}

void Simulation::delete_thing(int body) {
  Impl& m = *impl_;
  m.mark_thing_deleted(body);
  m.apply_pending_things();
  m.refresh();
  m.changed();
}

const std::vector<ThingView>& Simulation::things() const {
  return impl_->thing_views;
}

}  // namespace s2sim
