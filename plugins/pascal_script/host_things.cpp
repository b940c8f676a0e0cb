// Things and obstacles added and deleted while running (simtwo-script-api.md §3.4;
// docs/scripting.md): SimTwo keeps one list of each, the scene's then the added ones in the
// order they came, and a deletion shifts the later indices down. The kernel holds the bodies
// (StepContext::request_add_thing: an added obstacle is a fixed one); these lists are the
// script's view of them.
#include "script_controller.hpp"

#include <algorithm>
#include <cmath>
#include <filesystem>

namespace s2sim::pascal {
namespace {

/// Delphi's TColor ($00BBGGRR) as 0..1 components.
void color_of(double rgb24, double* rgb) {
  const auto c = static_cast<std::uint32_t>(static_cast<std::int64_t>(rgb24));
  for (int k = 0; k < 3; ++k)
    rgb[k] = static_cast<double>((c >> (8 * k)) & 0xFFu) / 255.0;
}

}  // namespace

double ScriptController::call_things(HostFn fn, const double* a, int n, const std::string& s) {
  StepContext& ctx = *ctx_;
  auto need = [&](int count) { require_arguments(fn, n, count); };
  auto index_of = [&](const std::string& id) {
    for (std::size_t i = 0; i < things_.size(); ++i)
      if (things_[i].id == id) return static_cast<int>(i);
    return -1;
  };
  auto remove = [&](int t) {
    ctx.request_delete_thing(things_[static_cast<std::size_t>(t)].body);
    things_.erase(things_.begin() + t);
  };
  auto remove_obstacle = [&](std::size_t i) {
    const ObstacleRef& ob = obstacles_[i];
    if (ob.scene_index >= 0)
      ctx.request_delete_obstacle(ob.scene_index);
    else
      ctx.request_delete_thing(ob.body);
    obstacles_.erase(obstacles_.begin() + static_cast<std::ptrdiff_t>(i));
  };
  switch (fn) {
    case HostFn::AddThingBox:
    case HostFn::AddThingSphere:
    case HostFn::AddThingCylinder: {
      // Box: mass, x, y, z, sx, sy, sz, rgb; sphere: mass, x, y, z, r, rgb; cylinder: mass,
      // x, y, z, r, length, rgb.
      const int sizes = fn == HostFn::AddThingBox ? 3 : fn == HostFn::AddThingSphere ? 1 : 2;
      need(4 + sizes + 1);
      for (int k = 0; k < 4 + sizes; ++k)
        if (!std::isfinite(a[k]))
          fail(std::string(fn == HostFn::AddThingBox      ? "AddThingBox"
                           : fn == HostFn::AddThingSphere ? "AddThingSphere"
                                                          : "AddThingCylinder") +
               ": argument " + std::to_string(k + 2) + " is " + number_text(a[k]));
      if (index_of(s) >= 0) fail("AddThing Error - Duplicate ID: " + s);
      ThingSpec spec;
      spec.mass_kg = a[0];
      spec.pose.position = {a[1], a[2], a[3]};
      if (fn == HostFn::AddThingBox) {
        spec.shape = ThingShape::box;
        spec.size_m = {a[4], a[5], a[6]};
      } else if (fn == HostFn::AddThingSphere) {
        spec.shape = ThingShape::sphere;
        spec.size_m = {a[4], a[4], a[4]};
      } else {
        spec.shape = ThingShape::cylinder;
        spec.size_m = {a[4], a[4], a[5]};
      }
      color_of(a[4 + sizes], spec.rgb);
      ThingRef th;
      th.id = s;
      try {
        th.body = ctx.request_add_thing(spec, s);
      } catch (const Error& e) {
        fail(e.message());
      }
      for (int k = 0; k < 3; ++k)
        th.look.rgba[k] = th.look.rgba_loaded[k] = spec.rgb[k];
      th.look.rgba[3] = th.look.rgba_loaded[3] = 1;
      th.look.size = spec.size_m;  // SimTwo's GetSize: box edges; r, r, l; r, r, r
      th.look.round = spec.shape == ThingShape::cylinder ? 1
                      : spec.shape == ThingShape::sphere ? 2
                                                         : 0;
      things_.push_back(th);
      return static_cast<double>(things_.size() - 1);
    }
    case HostFn::DeleteThing: {
      const int t = index_of(s);
      if (t >= 0) remove(t);
      return t;
    }
    case HostFn::ClearThings:
      while (!things_.empty())
        remove(static_cast<int>(things_.size()) - 1);
      return 0;
    case HostFn::Fire: {  // 0 scale, 1 position, 2 start, 3 stop, 4 start on a solid, 5 stop it
      need(1);
      const int op = static_cast<int>(a[0]);
      if (op == 0 || op == 1) {
        need(4);
        for (int k = 1; k < 4; ++k)
          if (!std::isfinite(a[k]))
            fail(std::string(op == 0 ? "SetFireScale" : "SetFirePosition") + ": argument " +
                 std::to_string(k) + " is " + number_text(a[k]));
        (op == 0 ? fire_.scale : fire_.position_m) = {a[1], a[2], a[3]};
      } else if (op == 2 || op == 3) {
        fire_.burning = op == 2;
      } else {
        need(3);
        const SolidRef& sd = solid(a[1], a[2]);
        fire_.burning = op == 4;
        fire_.on = op == 4 ? sd.body : BodyHandle{0};  // stopped, the fire leaves the solid
      }
      // On a solid it burns at the solid's origin; else where SetFirePosition put it.
      ctx.set_fire(fire_.burning, fire_.on, fire_.on.index > 0 ? Vec3{} : fire_.position_m,
                   fire_.scale);
      return 0;
    }
    case HostFn::SetSolidMass: {  // SimTwo's: the inertia scales with the mass
      need(3);
      try {
        ctx.request_mass(solid(a[0], a[1]).body, a[2]);
      } catch (const Error& e) {
        fail(std::string("SetSolidMass: ") + e.message());
      }
      return 0;
    }
    case HostFn::SetSolidSize:
    case HostFn::SetThingSize: {  // SimTwo's GetSize convention; the mass stays
      const bool solid_size = fn == HostFn::SetSolidSize;
      need(solid_size ? 5 : 4);
      const int first = solid_size ? 2 : 1;
      Look& look = solid_size ? solid(a[0], a[1]).look : thing(a[0]).look;
      const BodyHandle b = solid_size ? solid(a[0], a[1]).body : thing(a[0]).body;
      const Vec3 size{a[first], a[first + 1], a[first + 2]};
      try {
        ctx.request_resize(b, size);
      } catch (const Error& e) {
        fail(std::string(solid_size ? "SetSolidSize: " : "SetThingSize: ") + e.message());
      }
      // As GetSize reads it back: a cylinder r, r, l; a sphere r, r, r.
      look.size = look.round == 2   ? Vec3{size.x, size.x, size.x}
                  : look.round == 1 ? Vec3{size.x, size.x, size.z}
                                    : size;
      return 0;
    }
    case HostFn::SetSolidSurfaceFriction:
    case HostFn::SetThingSurfaceMu: {
      const bool solid_surface = fn == HostFn::SetSolidSurfaceFriction;
      need(solid_surface ? 4 : 3);
      const int first = solid_surface ? 2 : 1;
      const BodyHandle b = solid_surface ? solid(a[0], a[1]).body : thing(a[0]).body;
      try {
        ctx.request_surface(b, a[first], a[first + 1]);
      } catch (const Error& e) {
        fail(std::string(solid_surface ? "SetSolidSurfaceFriction: " : "SetThingSurfaceMu: ") +
             e.message());
      }
      return 0;
    }
    case HostFn::AddOBstacleBox: {  // x, y, z, sx, sy, sz, rgb: an axis-aligned static box
      need(7);
      for (int k = 0; k < 6; ++k)
        if (!std::isfinite(a[k]))
          fail("AddOBstacleBox: argument " + std::to_string(k + 2) + " is " + number_text(a[k]));
      for (const ObstacleRef& ob : obstacles_)
        if (ob.id == s) fail("AddObstacle Error - Duplicate ID: " + s);
      ThingSpec spec;
      spec.shape = ThingShape::box;
      spec.fixed = true;
      spec.pose.position = {a[0], a[1], a[2]};
      spec.size_m = {a[3], a[4], a[5]};
      color_of(a[6], spec.rgb);
      ObstacleRef ob;
      ob.id = s;
      try {
        ob.body = ctx.request_add_thing(spec, s);
      } catch (const Error& e) {
        fail(e.message());
      }
      ob.position = spec.pose.position;
      for (int k = 0; k < 3; ++k)
        ob.rgba[k] = spec.rgb[k];
      ob.rgba[3] = 1;
      obstacles_.push_back(ob);
      return static_cast<double>(obstacles_.size() - 1);
    }
    case HostFn::DeleteObstacle: {
      for (std::size_t i = 0; i < obstacles_.size(); ++i)
        if (obstacles_[i].id == s) {
          remove_obstacle(i);
          return static_cast<double>(i);
        }
      return -1;
    }
    case HostFn::ClearObstacles:
      while (!obstacles_.empty())
        remove_obstacle(obstacles_.size() - 1);
      return 0;
    case HostFn::SetObstaclePos:
    case HostFn::SetObstacleRotationMat: {
      const char* name = fn == HostFn::SetObstaclePos ? "SetObstaclePos" : "SetObstacleRotationMat";
      need(fn == HostFn::SetObstaclePos ? 4 : 3);
      ObstacleRef& ob = obstacle(a[0]);
      if (ob.scene_index >= 0)
        fail(std::string(name) + ": obstacle '" + ob.id +
             "' is the scene's, static since the load; obstacles added with AddOBstacleBox move");
      Pose pose = ctx.body_pose(ob.body);
      if (fn == HostFn::SetObstaclePos) {
        for (int k = 1; k < 4; ++k)
          if (!std::isfinite(a[k]))
            fail(std::string(name) + ": argument " + std::to_string(k + 1) + " is " +
                 number_text(a[k]));
        pose.position = {a[1], a[2], a[3]};
      } else {
        if (a[1] < 3 || a[2] < 3 || n < 3 + static_cast<int>(a[1] * a[2]))
          fail(std::string("Invalid (row,col) value: ") + name + " needs a 3x3 matrix");
        const int cols = static_cast<int>(a[2]);
        for (int r = 0; r < 3; ++r)
          for (int c = 0; c < 3; ++c) {
            const double v = a[3 + r * cols + c];
            if (!std::isfinite(v)) fail(std::string(name) + ": the matrix holds " + number_text(v));
            pose.rotation.m[r][c] = v;
          }
        const auto& m = pose.rotation.m;
        const double det = m[0][0] * (m[1][1] * m[2][2] - m[1][2] * m[2][1]) -
                           m[0][1] * (m[1][0] * m[2][2] - m[1][2] * m[2][0]) +
                           m[0][2] * (m[1][0] * m[2][1] - m[1][1] * m[2][0]);
        if (det < 0.1)
          fail(std::string(name) + ": the matrix is not a rotation (determinant " +
               number_text(det) + ")");
      }
      ctx.request_place(ob.body, pose);
      ob.position = pose.position;
      ob.rotation = pose.rotation;
      return 0;
    }
    default:
      fail("invalid host call");
  }
}

double ScriptController::mesh_thing(const double* a, int n, const std::string& id,
                                    const std::string& files) {
  require_arguments(HostFn::MeshThing, n, 2);
  const auto it =
      std::find_if(things_.begin(), things_.end(), [&](const ThingRef& t) { return t.id == id; });
  if (it == things_.end()) {  // SimTwo does nothing either; said, not silent
    ctx_->log_line("MeshThing: no thing '" + id + "'; nothing changed");
    return 0;
  }
  if (!(a[0] > 0 && std::isfinite(a[0])))
    fail("MeshThing('" + id + "'): MeshScale must be finite and > 0, got " + number_text(a[0]));
  const std::size_t nul = files.find('\0');
  const std::string file = files.substr(0, nul);
  const std::string shadow = nul == std::string::npos ? std::string() : files.substr(nul + 1);
  auto need_file = [&](const std::string& f) {
    std::error_code ec;
    if (!std::filesystem::is_regular_file(f, ec))
      fail("MeshThing('" + id + "'): cannot find the mesh file '" + f + "'");
  };
  need_file(file);
  if (!shadow.empty()) need_file(shadow);
  ctx_->set_body_mesh(it->body, file, a[0], a[1] != 0, shadow);
  return 0;
}

}  // namespace s2sim::pascal
