#include "scene_drawables.hpp"

#include <s2sim/error.hpp>

#include <algorithm>
#include <limits>
#include <map>

namespace s2sim::render {
namespace {

void set_color(DrawItem& item, const scene::Color& c) {
  item.color[0] = static_cast<float>(c.r);
  item.color[1] = static_cast<float>(c.g);
  item.color[2] = static_cast<float>(c.b);
  item.color[3] = static_cast<float>(c.a);
}

/// A frame whose local X is `axis` (unit), at `origin`.
Pose frame_along(const Vec3& origin, const Vec3& axis) {
  const Vec3 helper = std::abs(axis.z) < 0.9 ? Vec3{0, 0, 1} : Vec3{1, 0, 0};
  const Vec3 y = cross(helper, axis) / norm(cross(helper, axis));
  const Vec3 z = cross(axis, y);
  Pose p;
  p.position = origin;
  for (int i = 0; i < 3; ++i) {
    const double col[3][3] = {{axis.x, axis.y, axis.z}, {y.x, y.y, y.z}, {z.x, z.y, z.z}};
    p.rotation.m[0][i] = col[i][0];
    p.rotation.m[1][i] = col[i][1];
    p.rotation.m[2][i] = col[i][2];
  }
  return p;
}

/// Z of a cylinder mesh turned onto local X (beams and joint markers use X as their axis).
Mat4 z_to_x() {
  Mat4 r;
  r.at(0, 0) = 0;
  r.at(0, 2) = 1;
  r.at(2, 0) = -1;
  r.at(2, 2) = 0;
  return r;
}

}  // namespace

void SceneDrawables::build(const scene::Scene& scene, Renderer& renderer,
                           std::vector<std::string>& warnings) {
  drawables_.clear();
  if (box_ < 0) {
    box_ = renderer.upload(unit_box());
    cylinder_ = renderer.upload(unit_cylinder());
    sphere_ = renderer.upload(unit_sphere());
    // Coarse versions for what is small on screen and for shadows (llvmpipe transforms
    // vertices on one thread: a pile of 50 spheres was 100 000 triangles a frame).
    cylinder_coarse_ = renderer.upload(unit_cylinder(12));
    sphere_coarse_ = renderer.upload(unit_sphere(6, 12));
  }
  mesh_cache_.clear();
  meshes_version_ = 0;

  for (const CanvasTexture& t : canvases_)  // the scene's before, when it is loaded again
    renderer.release_image_texture(t.texture);
  canvases_.clear();
  if (canvas_square_ < 0) canvas_square_ = renderer.upload(unit_canvas_square());
  // SimTwo's canvas covers the box's local +Z face (simtwo-script-api.md §3.8): a square a
  // hair above it (so that it wins the depth test), in the unit frame of the box's drawable.
  auto add_canvas = [&](const scene::Geom& g, int body, Drawable::Kind kind, int index) {
    Drawable c;
    c.kind = Drawable::Kind::canvas;
    c.body = body;
    c.index = index;
    c.owner = static_cast<int>(drawables_.size()) - 1;
    c.canvas = static_cast<int>(canvases_.size());
    constexpr double kLift_m = 2e-4;
    const double height = std::max(g.shape.size_m.z, 1e-6);
    c.frame = translation({0, 0, static_cast<float>(0.5 + kLift_m / height)});
    c.item.mesh = canvas_square_;
    c.item.casts_shadow = false;
    c.box_min = {-0.5f, -0.5f, 0};
    c.box_max = {0.5f, 0.5f, 0};
    const float white[4] = {1, 1, 1, 1};
    std::copy(white, white + 4, c.item.color);
    CanvasTexture t;
    t.body = kind == Drawable::Kind::obstacle ? 0 : body;
    t.obstacle = kind == Drawable::Kind::obstacle ? index : -1;
    canvases_.push_back(t);
    drawables_.push_back(c);
  };
  auto add_geom = [&](const scene::Geom& g, int body, Drawable::Kind kind, int index) {
    Drawable d;
    d.kind = kind;
    d.body = body;
    d.index = index;
    set_color(d.item, g.visual.color);
    if (!g.visual.texture.empty()) {
      std::string error;
      d.item.texture = renderer.texture(g.visual.texture, error);
      d.item.texture_scale = static_cast<float>(g.visual.texture_scale);
      if (!error.empty()) warnings.push_back(error);
    }
    const scene::Mesh& mesh = g.visual.mesh;
    if (!mesh.file.empty()) {
      const LoadedMesh loaded = load_mesh(renderer, mesh.file, mesh.scale, warnings);
      if (loaded.mesh >= 0) {
        // The mesh replaces the primitive on screen; its offset is in the body frame.
        Pose rotation_only = g.pose;
        rotation_only.position = {};
        d.local = translation(to_f(g.pose.position + mesh.offset_m)) * to_mat4(rotation_only);
        d.frame = to_mat4(g.pose);  // where a mesh chosen while running goes
        take_mesh(d, loaded, mesh.shadow, renderer, mesh.shadow_file, mesh.scale, warnings);
        drawables_.push_back(d);
        return;
      }
    }
    d.local = to_mat4(g.pose);
    d.frame = d.local;
    d.primitive = true;
    d.shape = g.shape.type;
    take_primitive(d, g.shape);
    d.loaded_local = d.local;
    drawables_.push_back(d);
    const bool own = kind == Drawable::Kind::solid || kind == Drawable::Kind::obstacle;
    if (own && g.visual.canvas && g.shape.type == scene::ShapeType::box)
      add_canvas(g, body, kind, index);
  };

  for (std::size_t b = 0; b < scene.bodies.size(); ++b) {
    // An imported link's visual geometry replaces its collision geometry on screen.
    const auto& drawn =
        scene.bodies[b].visuals.empty() ? scene.bodies[b].geoms : scene.bodies[b].visuals;
    for (std::size_t k = 0; k < drawn.size(); ++k)
      add_geom(drawn[k], static_cast<int>(b) + 1,
               k == 0 ? Drawable::Kind::solid : Drawable::Kind::shell, static_cast<int>(k));
  }
  for (std::size_t o = 0; o < scene.obstacles.size(); ++o)
    add_geom(scene.obstacles[o], 0, Drawable::Kind::obstacle, static_cast<int>(o));

  for (const auto& t : scene.tracks) {
    Drawable d;
    d.kind = Drawable::Kind::track;
    d.body = 0;
    // A millimetre above the floor so the polygon wins the depth test against it.
    d.local = translation({0, 0, static_cast<float>(t.z_m) + 0.001f});
    d.item.mesh = renderer.upload(flat_polygon(t.vertices));
    d.item.two_sided = true;
    d.item.casts_shadow = false;
    set_color(d.item, t.color);
    float lo_x = 1e30f, lo_y = 1e30f, hi_x = -1e30f, hi_y = -1e30f;
    for (const auto& [x, y] : t.vertices) {
      lo_x = std::min(lo_x, static_cast<float>(x));
      lo_y = std::min(lo_y, static_cast<float>(y));
      hi_x = std::max(hi_x, static_cast<float>(x));
      hi_y = std::max(hi_y, static_cast<float>(y));
    }
    d.box_min = {lo_x, lo_y, -0.001f};
    d.box_max = {hi_x, hi_y, 0.001f};
    drawables_.push_back(d);
  }

  for (const auto& s : scene.sensors) {
    if (s.beam.length_m <= 0) continue;
    Drawable d;
    d.kind = Drawable::Kind::beam;
    d.index = static_cast<int>(&s - scene.sensors.data());
    d.body = s.body >= 0 ? s.body + 1 : 0;
    // A thin translucent slab along the sensor's +X, as wide as the beam at its far end.
    const auto length = static_cast<float>(s.beam.length_m);
    const auto width = static_cast<float>(std::max(s.beam.final_width_m, 0.002));
    d.local =
        to_mat4(s.pose) * translation({length / 2, 0, 0}) * scale_matrix({length, width, 0.002f});
    d.item.mesh = box_;
    set_color(d.item, s.color);
    d.item.color[3] = 0.45f;
    d.item.lit = false;
    d.item.casts_shadow = false;
    drawables_.push_back(d);
  }

  for (const auto& j : scene.joints) {
    if (j.draw.radius_m <= 0) continue;
    Drawable d;
    d.kind = Drawable::Kind::joint;
    d.body = j.body1 >= 0 ? j.body1 + 1 : 0;
    // The marker rides on body1: its load-time world frame expressed in body1's frame.
    const Pose world = frame_along(j.anchor_m, j.axis1);
    const Pose body_at_load = j.body1 >= 0 ? scene.bodies[j.body1].pose : Pose{};
    const auto r = static_cast<float>(j.draw.radius_m);
    d.local = to_mat4(body_at_load.inverse() * world) * z_to_x() *
              scale_matrix({r, r, static_cast<float>(j.draw.height_m)});
    d.item.mesh = cylinder_;
    d.box_min = {-1, -1, -0.5f};
    d.box_max = {1, 1, 0.5f};
    set_color(d.item, j.draw.color);
    drawables_.push_back(d);
  }
  for (auto& d : drawables_)
    std::copy(d.item.color, d.item.color + 4, d.scene_color);
  std::vector<int> thing_of_body(scene.bodies.size() + 1, -1);
  for (std::size_t t = 0; t < scene.things.size(); ++t)
    thing_of_body[static_cast<std::size_t>(scene.things[t]) + 1] = static_cast<int>(t);
  for (std::size_t k = 0; k < scene.runtime_things.size(); ++k)
    thing_of_body[static_cast<std::size_t>(scene.runtime_things[k]) + 1] =
        static_cast<int>(scene.things.size() + k);
  for (auto& d : drawables_)
    if (d.kind == Drawable::Kind::solid || d.kind == Drawable::Kind::shell)
      d.thing = thing_of_body[static_cast<std::size_t>(d.body)];
}

SceneDrawables::LoadedMesh SceneDrawables::load_mesh(Renderer& renderer,
                                                     const std::filesystem::path& file,
                                                     double scale,
                                                     std::vector<std::string>& warnings) {
  const auto key = std::make_pair(file, scale);
  if (auto it = mesh_cache_.find(key); it != mesh_cache_.end()) return it->second;
  LoadedMesh loaded;
  try {
    const MeshData data = load_mesh_file(file, scale);
    Vec3f lo, hi;
    vertex_bounds(data, lo, hi);
    loaded = {renderer.upload(data), lo, hi};
  } catch (const Error& e) {
    warnings.push_back(e.what());  // once per file: the failure is cached too
  }
  mesh_cache_.emplace(key, loaded);
  return loaded;
}

void SceneDrawables::take_mesh(Drawable& d, const LoadedMesh& loaded, bool casts_shadow,
                               Renderer& renderer, const std::filesystem::path& shadow_file,
                               double scale, std::vector<std::string>& warnings) {
  d.item.mesh = loaded.mesh;
  // A coarser mesh of the same thing casts the shadow and stands in when small on screen.
  d.item.coarse_mesh =
      shadow_file.empty() ? -1 : load_mesh(renderer, shadow_file, scale, warnings).mesh;
  d.box_min = loaded.lo;
  d.box_max = loaded.hi;
  d.item.two_sided = true;
  d.item.casts_shadow = casts_shadow;
}

void SceneDrawables::take_meshes(const Simulation& sim, Renderer& renderer,
                                 std::vector<std::string>& warnings) {
  const Annotations& notes = sim.annotations();
  if (notes.version == meshes_version_) return;
  meshes_version_ = notes.version;
  for (auto& d : drawables_) {
    if (d.kind != Drawable::Kind::solid) continue;
    const Annotations::BodyMesh* wanted = notes.body_mesh(d.body);
    const LoadedMesh loaded =
        wanted ? load_mesh(renderer, wanted->file, wanted->scale, warnings) : LoadedMesh{};
    if (loaded.mesh < 0) {
      if (d.run_time_mesh) {  // back to what the scene drew
        d.item = d.scene_item;
        d.box_min = d.scene_box_min;
        d.box_max = d.scene_box_max;
        d.local = d.scene_local;
        d.run_time_mesh = false;
      }
      continue;
    }
    if (!d.run_time_mesh) {
      d.scene_item = d.item;
      d.scene_box_min = d.box_min;
      d.scene_box_max = d.box_max;
      d.scene_local = d.local;
      d.run_time_mesh = true;
    }
    d.local = d.frame;
    take_mesh(d, loaded, wanted->casts_shadow, renderer, wanted->shadow_file, wanted->scale,
              warnings);
  }
}

void SceneDrawables::take_canvases(const Simulation& sim, Renderer& renderer) {
  for (CanvasTexture& t : canvases_) {
    if (!t.looked_up) {
      t.looked_up = true;
      const std::string name = t.obstacle >= 0
                                   ? "obstacles/" + std::to_string(t.obstacle) + "/canvas"
                                   : sim.body_path(t.body) + "/canvas";
      const std::vector<std::string> names = sim.image_names();
      if (std::find(names.begin(), names.end(), name) != names.end()) t.image = &sim.image(name);
    }
    if (t.image == nullptr || (t.uploaded && t.image->frame == t.uploaded_frame)) continue;
    t.texture = renderer.image_texture(*t.image, t.texture);
    t.uploaded_frame = t.image->frame;
    t.uploaded = true;
  }
  for (Drawable& d : drawables_)
    if (d.kind == Drawable::Kind::canvas)
      d.item.texture = canvases_[static_cast<std::size_t>(d.canvas)].texture;
}

void SceneDrawables::place_fire(const Simulation& sim, const Pose* body_poses, int body_count) {
  const Annotations::Fire& fire = sim.annotations().fire;
  burning_ = fire.burning;
  if (!burning_) return;
  const Pose on = fire.body > 0 && fire.body < body_count ? body_poses[fire.body] : Pose{};
  const Vec3 base = on.position + on.rotation * fire.position_m;
  // Three unlit, translucent blobs stacked upwards, from orange to yellow, flickering.
  const float sizes[kFlames] = {0.06f, 0.045f, 0.03f};
  const float heights[kFlames] = {0.05f, 0.11f, 0.16f};
  const float colors[kFlames][4] = {
      {1, 0.35f, 0.05f, 0.75f}, {1, 0.6f, 0.1f, 0.6f}, {1, 0.9f, 0.35f, 0.5f}};
  const Vec3f scale = to_f(fire.scale);
  const double t = sim.time_s();
  for (int k = 0; k < kFlames; ++k) {
    const float flicker = 1 + 0.15f * static_cast<float>(std::sin(37 * t + 2.1 * k));
    DrawItem& item = flames_[k];
    item.mesh = sphere_;
    item.coarse_mesh = sphere_coarse_;
    item.lit = false;
    item.casts_shadow = false;
    item.sensed = false;
    item.body = fire.body;
    std::copy(colors[k], colors[k] + 4, item.color);
    const float r = sizes[k] * flicker;
    item.model = translation(to_f(base) + Vec3f{0, 0, heights[k] * scale.z}) *
                 scale_matrix({r * scale.x, r * scale.y, 1.4f * r * scale.z});
  }
}

void SceneDrawables::place_liquids(const Simulation& sim, float half_size_m) {
  liquid_count_ = 0;
  for (const Annotations::LiquidSurface& surface : sim.annotations().liquid_surfaces) {
    const auto z = static_cast<float>(surface.z_m);
    bool shown = false;
    for (int k = 0; k < liquid_count_; ++k)
      shown = shown || liquid_z_m_[k] == z;
    if (shown || liquid_count_ == kMaxLiquids) continue;
    liquid_z_m_[liquid_count_] = z;
    DrawItem& item = liquids_[liquid_count_++];
    item.mesh = box_;
    item.casts_shadow = false;
    for (int c = 0; c < 4; ++c)
      item.color[c] = static_cast<float>(surface.rgba[c]);
    // A slab whose top is the surface, a millimetre thick so that it has no seam.
    constexpr float thickness_m = 0.001f;
    item.model = translation({0, 0, z - 0.5f * thickness_m}) *
                 scale_matrix({2 * half_size_m, 2 * half_size_m, thickness_m});
  }
}

void SceneDrawables::take_primitive(Drawable& d, const scene::Shape& s) const {
  d.item.coarse_mesh = -1;
  d.box_min = {-0.5f, -0.5f, -0.5f};
  d.box_max = {0.5f, 0.5f, 0.5f};
  switch (s.type) {
    case scene::ShapeType::box:
    case scene::ShapeType::convex:  // a hull without its mesh: drawn as its bounding box
      d.item.mesh = box_;
      d.local = d.local * scale_matrix(to_f(s.size_m));
      break;
    case scene::ShapeType::cylinder: {
      d.item.mesh = cylinder_;
      d.item.coarse_mesh = cylinder_coarse_;
      const auto r = static_cast<float>(s.radius_m);
      d.local = d.local * scale_matrix({r, r, static_cast<float>(s.length_m)});
      d.box_min = {-1, -1, -0.5f};
      d.box_max = {1, 1, 0.5f};
      break;
    }
    case scene::ShapeType::sphere: {
      d.item.mesh = sphere_;
      d.item.coarse_mesh = sphere_coarse_;
      const auto r = static_cast<float>(s.radius_m);
      d.local = d.local * scale_matrix({r, r, r});
      d.box_min = {-1, -1, -1};
      d.box_max = {1, 1, 1};
      break;
    }
  }
}

void SceneDrawables::take_thing_shape(Drawable& d, const ThingView& thing) {
  const ThingSpec& spec = thing.spec;
  for (int k = 0; k < 3; ++k)
    d.scene_color[k] = static_cast<float>(spec.rgb[k]);
  d.scene_color[3] = 1;
  if (d.run_time_mesh) return;  // drawn as its mesh, in the thing's colour
  scene::Shape shape;
  shape.type = spec.shape == ThingShape::box      ? scene::ShapeType::box
               : spec.shape == ThingShape::sphere ? scene::ShapeType::sphere
                                                  : scene::ShapeType::cylinder;
  shape.size_m = spec.size_m;
  shape.radius_m = spec.size_m.x;
  shape.length_m = spec.size_m.z;
  d.local = Mat4{};
  take_primitive(d, shape);
}

void SceneDrawables::update(const Simulation& sim, const Pose* body_poses, int body_count,
                            float floor_half_size_m) {
  const Annotations& notes = sim.annotations();
  place_fire(sim, body_poses, body_count);
  place_liquids(sim, floor_half_size_m);
  const std::vector<ThingView>& things = sim.things();
  for (auto& d : drawables_) {
    if (d.kind == Drawable::Kind::canvas) {  // on its box, which comes first
      const Drawable& box = drawables_[static_cast<std::size_t>(d.owner)];
      d.hidden = box.hidden || box.run_time_mesh || d.item.texture == 0;
      d.item.model = box.item.model * d.frame;
      continue;
    }
    if (d.thing >= 0) {
      const ThingView& thing = things[static_cast<std::size_t>(d.thing)];
      d.hidden = !thing.present;
      if (thing.added && thing.present) take_thing_shape(d, thing);
    } else if (d.kind == Drawable::Kind::obstacle) {
      d.hidden = !sim.obstacle_present(d.index);
    } else {
      d.hidden = false;
    }
    const bool scene_solid = d.kind == Drawable::Kind::solid && d.primitive && !d.run_time_mesh &&
                             (d.thing < 0 || !things[static_cast<std::size_t>(d.thing)].added);
    if (scene_solid) {
      if (const std::optional<Vec3> size = sim.resized(d.body)) {
        const Vec3f s = to_f(*size);
        d.local = d.frame * (d.shape == scene::ShapeType::sphere     ? scale_matrix({s.x, s.x, s.x})
                             : d.shape == scene::ShapeType::cylinder ? scale_matrix({s.x, s.x, s.z})
                                                                     : scale_matrix(s));
      } else {
        d.local = d.loaded_local;
      }
    }
    if (d.body >= body_count) {
      d.hidden = true;
      continue;
    }
    d.item.model = d.body == 0 ? d.local : to_mat4(body_poses[d.body]) * d.local;
    // A run-time colour: a solid's, a shell's or an obstacle's, a sensor beam's (its alpha).
    const double* painted = nullptr;
    if (d.kind == Drawable::Kind::solid && !notes.body_colors.empty()) {
      if (const auto* c = notes.body_color(d.body)) painted = c->rgb;
    } else if ((d.kind == Drawable::Kind::shell || d.kind == Drawable::Kind::obstacle) &&
               !notes.shape_colors.empty()) {
      if (const auto* c = notes.shape_color(d.body, d.index)) painted = c->rgb;
    } else if (d.kind == Drawable::Kind::beam && !notes.sensor_colors.empty()) {
      if (const auto* c = notes.sensor_color(d.index)) painted = c->rgb;
    }
    if (d.kind != Drawable::Kind::solid && d.kind != Drawable::Kind::shell &&
        d.kind != Drawable::Kind::obstacle && d.kind != Drawable::Kind::beam)
      continue;
    for (int k = 0; k < 4; ++k)
      d.item.color[k] = painted && k < 3                            ? static_cast<float>(painted[k])
                        : painted && d.kind != Drawable::Kind::beam ? 1.0f
                                                                    : d.scene_color[k];
  }
}

const std::vector<DrawItem>& SceneDrawables::items(bool beams, bool joints, int selected_body) {
  items_.clear();
  for (const auto& d : drawables_) {
    if (d.hidden) continue;
    if (d.kind == Drawable::Kind::beam && !beams) continue;
    if (d.kind == Drawable::Kind::joint && !joints) continue;
    items_.push_back(d.item);
    items_.back().body = d.body;
    items_.back().highlighted =
        selected_body > 0 && d.body == selected_body && d.kind != Drawable::Kind::beam;
  }
  if (burning_) items_.insert(items_.end(), flames_, flames_ + kFlames);
  items_.insert(items_.end(), liquids_, liquids_ + liquid_count_);
  return items_;
}

bool SceneDrawables::bounds(const scene::Scene& scene, int robot, Vec3f& lo, Vec3f& hi) const {
  lo = {1e30f, 1e30f, 1e30f};
  hi = {-1e30f, -1e30f, -1e30f};
  bool any = false;
  for (const auto& d : drawables_) {
    using K = Drawable::Kind;
    if (d.hidden || (d.kind != K::solid && d.kind != K::shell && d.kind != K::obstacle)) continue;
    if (robot >= 0 && (d.body <= 0 || scene.bodies[d.body - 1].robot != robot)) continue;
    for (int corner = 0; corner < 8; ++corner) {
      const Vec3f p = d.item.model.transform_point({corner & 1 ? d.box_max.x : d.box_min.x,
                                                    corner & 2 ? d.box_max.y : d.box_min.y,
                                                    corner & 4 ? d.box_max.z : d.box_min.z});
      lo = {std::min(lo.x, p.x), std::min(lo.y, p.y), std::min(lo.z, p.z)};
      hi = {std::max(hi.x, p.x), std::max(hi.y, p.y), std::max(hi.z, p.z)};
      any = true;
    }
  }
  return any;
}

int SceneDrawables::pick(const Vec3f& origin, const Vec3f& direction, float& distance_m) const {
  int best = -1;
  float best_t = std::numeric_limits<float>::max();
  for (const auto& d : drawables_) {
    if (d.hidden || d.kind == Drawable::Kind::beam || d.kind == Drawable::Kind::track) continue;
    // Slab test in mesh space, where the bounds are an axis-aligned box.
    const Mat4 inv = inverse(d.item.model);
    const Vec3f o = inv.transform_point(origin);
    const Vec3f e = inv.transform_point(origin + direction) - o;
    float t0 = 0, t1 = std::numeric_limits<float>::max();
    const float os[3] = {o.x, o.y, o.z}, es[3] = {e.x, e.y, e.z};
    const float lo[3] = {d.box_min.x, d.box_min.y, d.box_min.z};
    const float hi[3] = {d.box_max.x, d.box_max.y, d.box_max.z};
    bool hit = true;
    for (int a = 0; a < 3 && hit; ++a) {
      if (std::abs(es[a]) < 1e-12f) {
        hit = os[a] >= lo[a] && os[a] <= hi[a];
        continue;
      }
      float ta = (lo[a] - os[a]) / es[a], tb = (hi[a] - os[a]) / es[a];
      if (ta > tb) std::swap(ta, tb);
      t0 = std::max(t0, ta);
      t1 = std::min(t1, tb);
      hit = t0 <= t1;
    }
    // `direction` is unit in the world, so t is a world distance (the model is rigid+scale
    // and t is measured along the same parametrised line).
    if (hit && t0 < best_t) {
      best_t = t0;
      best = d.body;
    }
  }
  distance_m = best_t;
  return best;
}

}  // namespace s2sim::render
