// The host functions on robots, solids, things and obstacles (simtwo-script-api.md §3.3, §3.4,
// §3.8): poses and velocities read, robots placed, single bodies teleported (SetSolid*: the
// kernel moves a jointed body as close as its joint allows), solids painted, shell tags.
#include "script_controller.hpp"

namespace s2sim::pascal {
namespace {

/// A script error naming `fn` unless a[first..first+count) are all finite.
void require_finite(const char* fn, const double* a, int first, int count) {
  for (int k = first; k < first + count; ++k)
    if (!std::isfinite(a[k]))
      throw Error(ErrorKind::runtime, std::string(fn) + ": argument " + std::to_string(k + 1) +
                                          " is " + number_text(a[k]));
}
double determinant(const Mat3& r) {
  const auto& m = r.m;
  return m[0][0] * (m[1][1] * m[2][2] - m[1][2] * m[2][1]) -
         m[0][1] * (m[1][0] * m[2][2] - m[1][2] * m[2][0]) +
         m[0][2] * (m[1][0] * m[2][1] - m[1][1] * m[2][0]);
}
}  // namespace

Pose& ScriptController::move_of(BodyHandle b) {
  for (auto& [body, pose] : moves_)
    if (body == b.index) return pose;
  moves_.emplace_back(b.index, ctx_->body_pose(b));
  return moves_.back().second;
}
Twist& ScriptController::velocity_of(BodyHandle b) {
  for (auto& [body, twist] : velocities_)
    if (body == b.index) return twist;
  velocities_.emplace_back(b.index, ctx_->body_twist(b));
  return velocities_.back().second;
}

double ScriptController::call_bodies(HostFn fn, const double* a, int n, const std::string& s) {
  StepContext& ctx = *ctx_;
  auto need = [&](int count) { require_arguments(fn, n, count); };
  auto pose_of = [&](BodyHandle b) -> const Pose& { return ctx.body_pose(b); };
  auto point = [&](const Vec3& v) {
    numbers_.assign({v.x, v.y, v.z});
    return 0.0;
  };
  switch (fn) {
    case HostFn::SetRobotPos: {
      need(5);
      RobotRef& rb = robot(a[0]);
      if (!rb.main.valid()) fail("robot '" + rb.id + "' has no main body");
      // SimTwo's re-placement (§3.3, Q4): offsets to the file coordinates, yaw about the main
      // body's file position; the file rotation is the load rotation without the scene's yaw.
      Pose pose;
      pose.position = rb.origin + Vec3{a[1], a[2], a[3]};
      pose.rotation = rot_z(a[4]) * (rot_z(-rb.yaw) * rb.main_load_pose.rotation);
      ctx.request_place(rb.main, pose);
      return 0;
    }
    case HostFn::GetRobotX:
      need(1);
      return pose_of(robot(a[0]).main).position.x;
    case HostFn::GetRobotY:
      need(1);
      return pose_of(robot(a[0]).main).position.y;
    case HostFn::GetRobotTheta: {
      need(1);
      const Mat3& R = pose_of(robot(a[0]).main).rotation;
      return std::atan2(R.m[1][0], R.m[0][0]);
    }
    case HostFn::GetRobotVx:
      need(1);
      return ctx.body_twist(robot(a[0]).main).linear_m_s.x;
    case HostFn::GetRobotVy:
      need(1);
      return ctx.body_twist(robot(a[0]).main).linear_m_s.y;
    case HostFn::GetRobotW:
      need(1);
      return ctx.body_twist(robot(a[0]).main).angular_rad_s.z;
    case HostFn::GetSolidPos:
      need(2);
      return point(pose_of(solid(a[0], a[1]).body).position);
    case HostFn::GetSolidTheta: {
      need(2);
      const Mat3& R = pose_of(solid(a[0], a[1]).body).rotation;
      return std::atan2(R.m[1][0], R.m[0][0]);
    }
    case HostFn::GetSolidRotMat: {
      need(2);
      const Mat3& R = pose_of(solid(a[0], a[1]).body).rotation;
      numbers_.clear();
      for (int r = 0; r < 3; ++r)
        for (int c = 0; c < 3; ++c)
          numbers_.push_back(R.m[r][c]);
      return 3 * 65536 + 3;
    }
    case HostFn::GetSolidLinearVel:
      need(2);
      return point(ctx.body_twist(solid(a[0], a[1]).body).linear_m_s);
    // One body teleported, its speeds kept (§3.3): ODE then pulls the joints together again;
    // S2Sim's joints cannot come apart, so a jointed body goes as close as its joint allows.
    case HostFn::SetSolidPos:
    case HostFn::SetSolidLinearVel:
    case HostFn::SetSolidAngularVel: {
      need(5);
      require_finite(kHostFnNames[static_cast<int>(fn)], a, 2, 3);
      const BodyHandle b = solid(a[0], a[1]).body;
      const Vec3 v{a[2], a[3], a[4]};
      if (fn == HostFn::SetSolidPos) {
        Pose& pose = move_of(b);
        pose.position = v;
        ctx.request_move(b, pose);
      } else {
        Twist& twist = velocity_of(b);
        (fn == HostFn::SetSolidLinearVel ? twist.linear_m_s : twist.angular_rad_s) = v;
        ctx.request_velocity(b, twist);
      }
      return 0;
    }
    case HostFn::SetSolidRotationMat: {
      need(4);
      const BodyHandle b = solid(a[0], a[1]).body;
      if (a[2] < 3 || a[3] < 3 || n < 4 + static_cast<int>(a[2] * a[3]))
        fail("Invalid (row,col) value: SetSolidRotationMat needs a 3x3 matrix");
      const int cols = static_cast<int>(a[3]);
      Mat3 rotation;
      for (int r = 0; r < 3; ++r) {
        require_finite("SetSolidRotationMat", a, 4 + r * cols, 3);
        for (int c = 0; c < 3; ++c)
          rotation.m[r][c] = a[4 + r * cols + c];
      }
      // Not checked for orthonormality, as in SimTwo (the kernel takes the nearest rotation),
      // but a matrix that is no rotation at all (a mirror, a collapse) is refused.
      if (determinant(rotation) < 0.1)
        fail("SetSolidRotationMat: the matrix is not a rotation (determinant " +
             number_text(determinant(rotation)) + ")");
      Pose& pose = move_of(b);
      pose.rotation = rotation;
      ctx.request_move(b, pose);
      return 0;
    }
    case HostFn::SetSolidColor: {  // bytes 0..255, opaque
      need(5);
      SolidRef& sd = solid(a[0], a[1]);
      for (int k = 0; k < 3; ++k)
        sd.look.rgba[k] = a[2 + k] / 255;
      sd.look.rgba[3] = 1;
      ctx.set_body_color(sd.body, a[2] / 255, a[3] / 255, a[4] / 255);
      return 0;
    }
    case HostFn::GetSolidColor: {
      need(2);
      numbers_.clear();
      for (double v : solid(a[0], a[1]).look.rgba)
        numbers_.push_back(std::round(v * 255));
      return 0;
    }
    case HostFn::GetSolidSize:
      need(2);
      return point(solid(a[0], a[1]).look.size);
    case HostFn::GetThingSize:
      need(1);
      return point(thing(a[0]).look.size);
    case HostFn::GetSolidCenterOfMass:
      need(2);
      return point(solid(a[0], a[1]).look.com);
    case HostFn::GetRobotCenterOfMass: {
      // The solids' masses at their centres of mass, in the world.
      need(1);
      Vec3 sum{0, 0, 0};
      double mass = 0;
      for (const SolidRef& sd : robot(a[0]).solids) {
        const double m = ctx.body_mass_kg(sd.body);
        sum = sum + m * (pose_of(sd.body) * sd.look.com);
        mass += m;
      }
      return point(mass > 0 ? (1 / mass) * sum : sum);
    }
    case HostFn::GetShellPos:
    case HostFn::GetShellColor: {
      need(2);
      const RobotRef& rb = robot(a[0]);
      if (a[1] < 0 || a[1] >= static_cast<double>(rb.shells.size())) fail(index_error(a[1]));
      const RobotRef::Shell& shell = rb.shells[static_cast<std::size_t>(a[1])];
      if (fn == HostFn::GetShellPos) return point(pose_of(shell.body) * shell.position);
      numbers_.clear();
      for (double v : shell.rgba)
        numbers_.push_back(std::round(v * 255));
      return 0;
    }
    case HostFn::SetShellColor: {  // bytes 0..255, opaque
      need(5);
      RobotRef& rb = robot(a[0]);
      if (a[1] < 0 || a[1] >= static_cast<double>(rb.shells.size())) fail(index_error(a[1]));
      RobotRef::Shell& shell = rb.shells[static_cast<std::size_t>(a[1])];
      for (int k = 0; k < 3; ++k)
        shell.rgba[k] = a[2 + k] / 255;
      shell.rgba[3] = 1;
      ctx.set_shape_color(shell.body, shell.geom, a[2] / 255, a[3] / 255, a[4] / 255);
      return 0;
    }
    case HostFn::SetObstacleColor: {
      need(4);
      ObstacleRef& ob = obstacle(a[0]);
      for (int k = 0; k < 3; ++k)
        ob.rgba[k] = a[1 + k] / 255;
      ob.rgba[3] = 1;
      if (ob.scene_index >= 0)
        ctx.set_shape_color(BodyHandle{0}, ob.scene_index, a[1] / 255, a[2] / 255, a[3] / 255);
      else
        ctx.set_body_color(ob.body, a[1] / 255, a[2] / 255, a[3] / 255);
      return 0;
    }
    case HostFn::SetSensorColor: {
      need(5);
      const RobotRef& rb = robot(a[0]);
      if (a[1] < 0 || a[1] >= static_cast<double>(rb.sensors.size())) fail(index_error(a[1]));
      const SensorRef& sensor =
          sensors_[static_cast<std::size_t>(rb.sensors[static_cast<std::size_t>(a[1])])];
      ctx.set_sensor_color(sensor.prefix, a[2] / 255, a[3] / 255, a[4] / 255);
      return 0;
    }
    case HostFn::SetBeltSpeed: {  // the belt's surface speed along its +X, the input belt_speed
      need(3);
      const SolidRef& sd = solid(a[0], a[1]);
      if (sd.belt.index < 0) fail("SetBeltSpeed: solid '" + sd.id + "' is not a belt");
      ctx.set_input(sd.belt, a[2]);
      return 0;
    }
    case HostFn::GetBeltSpeed: {
      need(2);
      const SolidRef& sd = solid(a[0], a[1]);
      return sd.belt.index < 0 ? 0 : ctx.input(sd.belt);
    }
    case HostFn::GetSolidTag:
      need(2);
      text_result_ = solid(a[0], a[1]).tag;
      return 0;
    case HostFn::SetSolidTag:
      need(2);
      solid(a[0], a[1]).tag = s;
      return 0;
    case HostFn::GetObstacleColor:
    case HostFn::GetObstacleRotMat: {
      need(1);
      const ObstacleRef& ob = obstacle(a[0]);
      numbers_.clear();
      if (fn == HostFn::GetObstacleColor) {
        for (double v : ob.rgba)
          numbers_.push_back(std::round(v * 255));
        return 0;
      }
      const Mat3& rotation = ob.scene_index >= 0 ? ob.rotation : pose_of(ob.body).rotation;
      for (int r = 0; r < 3; ++r)
        for (int c = 0; c < 3; ++c)
          numbers_.push_back(rotation.m[r][c]);
      return 3 * 65536 + 3;
    }
    case HostFn::SetShellTag: {
      need(2);
      RobotRef& rb = robot(a[0]);
      if (a[1] < 0) fail(index_error(a[1]));
      const auto i = static_cast<std::size_t>(a[1]);
      if (rb.shell_tags.size() <= i) rb.shell_tags.resize(i + 1);
      rb.shell_tags[i] = s;
      return 0;
    }
    case HostFn::GetShellTag: {
      need(2);
      RobotRef& rb = robot(a[0]);
      const auto i = static_cast<std::size_t>(a[1] < 0 ? 0 : a[1]);
      text_result_ = i < rb.shell_tags.size() ? rb.shell_tags[i] : std::string();
      return 0;
    }
    case HostFn::SetThingPos: {
      need(4);
      ThingRef& th = thing(a[0]);
      Pose pose = pose_of(th.body);
      pose.position = {a[1], a[2], a[3]};
      ctx.request_place(th.body, pose);
      return 0;
    }
    case HostFn::GetThingPos:
      need(1);
      return point(pose_of(thing(a[0]).body).position);
    case HostFn::GetThingColor: {
      need(1);
      const ThingRef& th = thing(a[0]);
      numbers_.clear();
      for (double v : th.look.rgba)
        numbers_.push_back(std::round(v * 255));
      return 0;
    }
    case HostFn::GetObstaclePos: {
      need(1);
      const ObstacleRef& ob = obstacle(a[0]);
      return point(ob.scene_index >= 0 ? ob.position : pose_of(ob.body).position);
    }
    case HostFn::GetSolidAngularVel:
      need(2);
      return point(ctx.body_twist(solid(a[0], a[1]).body).angular_rad_s);
    case HostFn::GetSolidMass:
      need(2);
      return ctx.body_mass_kg(solid(a[0], a[1]).body);
    case HostFn::SetSolidForce: {
      // For this tick, at the body frame origin (ODE's force of the next step, at the centre
      // of mass: the same point without massive shells).
      need(5);
      const BodyHandle b = solid(a[0], a[1]).body;
      ctx.apply_force(b, Vec3{a[2], a[3], a[4]}, pose_of(b).position);
      return 0;
    }
    case HostFn::SetThingColor: {  // SimTwo ignores the part index c
      need(5);
      ThingRef& th = thing(a[0]);
      for (int k = 0; k < 3; ++k)
        th.look.rgba[k] = a[2 + k] / 255;
      th.look.rgba[3] = 1;
      ctx.set_body_color(th.body, th.look.rgba[0], th.look.rgba[1], th.look.rgba[2]);
      return 0;
    }
    case HostFn::GetThingRotMat: {
      need(1);
      const Mat3& R = pose_of(thing(a[0]).body).rotation;
      numbers_.clear();
      for (int r = 0; r < 3; ++r)
        for (int c = 0; c < 3; ++c)
          numbers_.push_back(R.m[r][c]);
      return 3 * 65536 + 3;
    }
    case HostFn::SetThingRotationMat: {
      need(3);
      const BodyHandle b = thing(a[0]).body;
      if (a[1] < 3 || a[2] < 3 || n < 3 + static_cast<int>(a[1] * a[2]))
        fail("Invalid (row,col) value: SetThingRotationMat needs a 3x3 matrix");
      const int cols = static_cast<int>(a[2]);
      Mat3 rotation;
      for (int r = 0; r < 3; ++r) {
        require_finite("SetThingRotationMat", a, 3 + r * cols, 3);
        for (int c = 0; c < 3; ++c)
          rotation.m[r][c] = a[3 + r * cols + c];
      }
      if (determinant(rotation) < 0.1)
        fail("SetThingRotationMat: the matrix is not a rotation (determinant " +
             number_text(determinant(rotation)) + ")");
      Pose& pose = move_of(b);
      pose.rotation = rotation;
      ctx.request_move(b, pose);
      return 0;
    }
    case HostFn::GetThingAngularVel:
      need(1);
      return point(ctx.body_twist(thing(a[0]).body).angular_rad_s);
    case HostFn::GetThingSpeed:
      need(1);
      return point(ctx.body_twist(thing(a[0]).body).linear_m_s);
    case HostFn::SetThingSpeed:
    case HostFn::SetThingLinearVel:
    case HostFn::SetThingAngularVel: {
      need(4);
      const BodyHandle b = thing(a[0]).body;
      Twist& twist = velocity_of(b);
      (fn == HostFn::SetThingAngularVel ? twist.angular_rad_s : twist.linear_m_s) =
          Vec3{a[1], a[2], a[3]};
      ctx.request_velocity(b, twist);
      return 0;
    }
    case HostFn::SetThingForce:
    case HostFn::SetThingForceAtRelPos:
    case HostFn::SetThingRelForce:
    case HostFn::SetThingRelForceAtRelPos: {
      // ODE's dBodyAdd(Rel)Force(AtRelPos): a force in the world (Rel: the body's) frame, at the
      // body origin or at a point given in the body's frame; for this tick.
      const bool at_point =
          fn == HostFn::SetThingForceAtRelPos || fn == HostFn::SetThingRelForceAtRelPos;
      need(at_point ? 7 : 4);
      const BodyHandle b = thing(a[0]).body;
      const Pose& pose = pose_of(b);
      Vec3 force{a[1], a[2], a[3]};
      if (fn == HostFn::SetThingRelForce || fn == HostFn::SetThingRelForceAtRelPos)
        force = pose.rotation * force;
      const Vec3 at =
          at_point ? pose.position + pose.rotation * Vec3{a[4], a[5], a[6]} : pose.position;
      ctx.apply_force(b, force, at);
      return 0;
    }
    case HostFn::GetObstacleIndex:
      for (std::size_t i = 0; i < obstacles_.size(); ++i)
        if (obstacles_[i].id == s) return static_cast<double>(i);
      return -1;
    case HostFn::AddOBstacleBox:
    case HostFn::ClearObstacles:
      not_provided(fn, "obstacles are fixed at load");
    default:
      fail("invalid host call");
  }
}

}  // namespace s2sim::pascal
