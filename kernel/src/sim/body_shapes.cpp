// A body's primitive resized and its surface set while running (SimTwo's SetSolidSize,
// SetThingSize, SetSolidSurfaceFriction, SetThingSurfaceMu; docs/format.md, "Shapes and
// surfaces set while running"): collision and rays take the new size at once, the mass and
// inertia stay as loaded (SimTwo's rule); contact takes the new friction. A snapshot holds
// both (segment `shapes`), a reset restores the scene's.
#include "scene/limits.hpp"
#include "sim/names.hpp"
#include "sim/simulation_impl.hpp"

#include <cmath>

namespace s2sim {
namespace {

/// Numbers per body in the `shapes` segment: resized, size x, y, z, surfaced, mu, mu2.
constexpr std::size_t kShapeNumbers = 7;

using sim::short_decimal;

}  // namespace

std::int32_t Simulation::Impl::own_shape(int body, const char* call) const {
  const std::int32_t shape =
      body > 0 && body < static_cast<int>(poses.size()) ? shapes->first_shape_of(body) : -1;
  if (shape < 0)
    throw Error(ErrorKind::usage,
                std::string(call) + ": body " + body_label(body) + " has no collision shape");
  return shape;
}

void Simulation::Impl::apply_body_shape(int body) {
  const BodyShape& o = body_shapes[static_cast<std::size_t>(body)];
  const std::int32_t shape = shapes->first_shape_of(body);
  const std::int32_t t = thing_of_body[static_cast<std::size_t>(body)];
  const bool added = t >= 0 && thing_views[static_cast<std::size_t>(t)].added;
  if (!added) {  // an added thing's primitive is its spec's (runtime_things.cpp)
    scene::Geom g = scene.bodies[static_cast<std::size_t>(body - 1)].geoms[0];
    if (o.resized) {
      g.shape.size_m = o.size_m;
      g.shape.radius_m = o.size_m.x;
      g.shape.length_m = o.size_m.z;
    }
    shapes->reshape(shape, g);
    contacts->reshaped(shape);
    ray_caster->reshaped(shape);
  }
  collision::Surface surface = loaded_surfaces[static_cast<std::size_t>(body)];
  if (o.surfaced) {
    surface.has_mu = o.mu >= 0;
    surface.mu = o.mu;
    if (surface.anisotropy != collision::Anisotropy::none) surface.mu2 = o.mu2;
  }
  const collision::Surface& now = shapes->surfaces()[static_cast<std::size_t>(shape)];
  if (now.has_mu == surface.has_mu && now.mu == surface.mu && now.mu2 == surface.mu2) return;
  shapes->set_surface(shape, surface);
  contacts->surface_changed(shape);  // the surface pairs tabulated again
}

void Simulation::Impl::init_body_shapes() {
  body_shapes.assign(poses.size(), BodyShape{});
  pending_body_changes.reserve(3 * poses.size());  // a resize, a surface, a mass
  world.request_resize = &Simulation::Impl::request_resize;
  world.request_surface = &Simulation::Impl::request_surface;
  loaded_surfaces.assign(poses.size(), collision::Surface{});
  for (std::size_t b = 1; b < poses.size(); ++b) {
    const std::int32_t shape = shapes->first_shape_of(static_cast<int>(b));
    if (shape >= 0) loaded_surfaces[b] = shapes->surfaces()[static_cast<std::size_t>(shape)];
  }
}

void Simulation::Impl::reset_body_shapes() {
  for (std::size_t b = 1; b < body_shapes.size(); ++b) {
    BodyShape& o = body_shapes[b];
    if (!o.resized && !o.surfaced) continue;
    o = BodyShape{};
    apply_body_shape(static_cast<int>(b));
  }
}

void Simulation::Impl::declare_body_shapes_state() {
  layout.add(
      "shapes", kShapeNumbers * (body_shapes.size() - 1),
      [this](double* out) {
        for (std::size_t b = 1; b < body_shapes.size(); ++b, out += kShapeNumbers) {
          const BodyShape& o = body_shapes[b];
          const double numbers[kShapeNumbers] = {
              o.resized ? 1.0 : 0.0,  o.size_m.x, o.size_m.y, o.size_m.z,
              o.surfaced ? 1.0 : 0.0, o.mu,       o.mu2};
          std::copy(numbers, numbers + kShapeNumbers, out);
        }
      },
      [this](const double* in, std::size_t) {
        for (std::size_t b = 1; b < body_shapes.size(); ++b, in += kShapeNumbers) {
          const BodyShape o{in[0] != 0, {in[1], in[2], in[3]}, in[4] != 0, in[5], in[6]};
          BodyShape& now = body_shapes[b];
          const bool same = o.resized == now.resized && o.surfaced == now.surfaced &&
                            o.size_m.x == now.size_m.x && o.size_m.y == now.size_m.y &&
                            o.size_m.z == now.size_m.z && o.mu == now.mu && o.mu2 == now.mu2;
          if (same) continue;  // a restore changes nothing it need not (run-ahead restores)
          now = o;
          apply_body_shape(static_cast<int>(b));
        }
      });
}

void Simulation::Impl::check_resize(int body, const Vec3& size_m) const {
  own_shape(body, "resize_body");
  const scene::Body& b = scene.bodies[static_cast<std::size_t>(body - 1)];
  scene::ShapeType type = b.geoms[0].shape.type;
  const std::int32_t t = thing_of_body[static_cast<std::size_t>(body)];
  if (t >= 0 && thing_views[static_cast<std::size_t>(t)].added) {  // its spec's primitive
    const ThingShape shape = thing_views[static_cast<std::size_t>(t)].spec.shape;
    type = shape == ThingShape::box      ? scene::ShapeType::box
           : shape == ThingShape::sphere ? scene::ShapeType::sphere
                                         : scene::ShapeType::cylinder;
  }
  auto ok = [](double v) { return v > 0 && v <= scene::limits::kMaxLength_m; };
  const bool valid = type == scene::ShapeType::box ? ok(size_m.x) && ok(size_m.y) && ok(size_m.z)
                     : type == scene::ShapeType::sphere   ? ok(size_m.x)
                     : type == scene::ShapeType::cylinder ? ok(size_m.x) && ok(size_m.z)
                                                          : false;
  if (type == scene::ShapeType::convex)
    throw Error(ErrorKind::usage, "resize_body: body " + body_label(body) +
                                      " is a mesh's hull, which keeps its size");
  if (!valid)
    throw Error(ErrorKind::usage, "resize_body: body " + body_label(body) +
                                      ": sizes must be positive and at most " +
                                      short_decimal(scene::limits::kMaxLength_m) + " m, got " +
                                      short_decimal(size_m.x) + ", " + short_decimal(size_m.y) +
                                      ", " + short_decimal(size_m.z));
}

void Simulation::Impl::resize_body(int body, const Vec3& size_m) {
  check_resize(body, size_m);
  const std::int32_t t = thing_of_body[static_cast<std::size_t>(body)];
  if (t >= 0 && thing_views[static_cast<std::size_t>(t)].added) {
    // An added thing's size is its spec (its inertia follows, its mass stays).
    ThingView& v = thing_views[static_cast<std::size_t>(t)];
    if (!v.present) return;
    v.spec.size_m = size_m;
    apply_thing(static_cast<std::size_t>(t), false);
    return;
  }
  BodyShape& o = body_shapes[static_cast<std::size_t>(body)];
  o.resized = true;
  o.size_m = size_m;
  apply_body_shape(body);
}

void Simulation::Impl::check_surface(int body, double mu, double mu2) const {
  own_shape(body, "set_body_surface");
  if (!std::isfinite(mu) || !std::isfinite(mu2))
    throw Error(ErrorKind::usage, "set_body_surface: body " + body_label(body) +
                                      ": mu and mu2 must be finite, got " + short_decimal(mu) +
                                      ", " + short_decimal(mu2));
}

void Simulation::Impl::set_body_surface(int body, double mu, double mu2) {
  check_surface(body, mu, mu2);
  BodyShape& o = body_shapes[static_cast<std::size_t>(body)];
  o.surfaced = true;
  o.mu = mu;
  o.mu2 = mu2;
  apply_body_shape(body);
}

void Simulation::Impl::apply_pending_body_changes() {
  for (const PendingBodyChange& p : pending_body_changes) {
    switch (p.kind) {
      case PendingBodyChange::Kind::resize:
        resize_body(p.body, p.values);
        break;
      case PendingBodyChange::Kind::surface:
        set_body_surface(p.body, p.values.x, p.values.y);
        break;
      case PendingBodyChange::Kind::mass:
        set_body_mass(p.body, {p.mass_kg, p.values, p.inertia_kg_m2});
        break;
    }
  }
  pending_body_changes.clear();
}

void Simulation::Impl::request_resize(const void* impl, std::int32_t body, const Vec3& size_m) {
  auto& m = *static_cast<Simulation::Impl*>(const_cast<void*>(impl));
  m.check_resize(body, size_m);  // refused to the component that asked
  if (m.pending_body_changes.size() < m.pending_body_changes.capacity())
    m.pending_body_changes.push_back({PendingBodyChange::Kind::resize, body, size_m, 0, {}});
  else
    m.resize_body(body, size_m);  // more requests than bodies in one stage: at once
}

void Simulation::Impl::request_surface(const void* impl, std::int32_t body, double mu, double mu2) {
  auto& m = *static_cast<Simulation::Impl*>(const_cast<void*>(impl));
  m.check_surface(body, mu, mu2);
  if (m.pending_body_changes.size() < m.pending_body_changes.capacity())
    m.pending_body_changes.push_back({PendingBodyChange::Kind::surface, body, {mu, mu2, 0}, 0, {}});
  else
    m.set_body_surface(body, mu, mu2);
}

void Simulation::resize_body(int body, const Vec3& size_m) {
  impl_->resize_body(body, size_m);
  impl_->changed();
}

void Simulation::set_body_surface(int body, double mu, double mu2) {
  impl_->set_body_surface(body, mu, mu2);
  impl_->changed();
}

std::optional<Vec3> Simulation::resized(int body) const {
  const auto& shapes = impl_->body_shapes;
  if (body <= 0 || body >= static_cast<int>(shapes.size()) ||
      !shapes[static_cast<std::size_t>(body)].resized)
    return std::nullopt;
  return shapes[static_cast<std::size_t>(body)].size_m;
}

}  // namespace s2sim
