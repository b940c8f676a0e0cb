// A flying or floating robot about to leave the view (keep_in_view.hpp).
#include "keep_in_view.hpp"

#include <cmath>

namespace s2sim::viewer {

namespace {

/// Whether a contact has a body of robot `r` on either side.
bool touches_something(const Simulation& sim, int r) {
  const auto& bodies = sim.scene().bodies;
  auto of_robot = [&](int index) {  // a simulation body index; 0 is the world
    return index >= 1 && index <= static_cast<int>(bodies.size()) &&
           bodies[static_cast<std::size_t>(index - 1)].robot == r;
  };
  for (std::size_t c = 0; c < sim.contact_count(); ++c) {
    const ContactInfo& contact = sim.contact(c);
    if (of_robot(contact.body_a.index) || of_robot(contact.body_b.index)) return true;
  }
  return false;
}

/// Whether a joint holds one of robot `r`'s bodies to the world (an arm, a pendulum): such a
/// robot does not fly away, however little it touches.
bool held_by_the_world(const Simulation& sim, int r) {
  for (const scene::Joint& joint : sim.scene().joints)
    if (joint.robot == r && (joint.body1 < 0 || joint.body2 < 0)) return true;
  return false;
}

}  // namespace

int robot_leaving_view(const Simulation& sim, const Mat4& view_projection,
                       const std::vector<bool>& declined) {
  const auto& robots = sim.scene().robots;
  for (std::size_t r = 0; r < robots.size(); ++r) {
    if (robots[r].main_body < 0 || (r < declined.size() && declined[r])) continue;
    const Vec3f p = to_f(sim.body_pose(robots[r].main_body + 1).position);
    const Vec4f clip = view_projection * Vec4f{p.x, p.y, p.z, 1};
    const bool inside = clip.w > 0 && std::abs(clip.x / clip.w) < kKeepInViewFill &&
                        std::abs(clip.y / clip.w) < kKeepInViewFill;
    const int robot = static_cast<int>(r);
    if (!inside && !held_by_the_world(sim, robot) && !touches_something(sim, robot)) return robot;
  }
  return -1;
}

}  // namespace s2sim::viewer
