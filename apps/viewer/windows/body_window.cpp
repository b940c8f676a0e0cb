#include "windows.hpp"

#include <imgui.h>
#include <s2sim/math.hpp>

#include <cmath>

namespace s2sim::viewer {

void draw_body_window(ViewerState& state) {
  // Drawn inside its tab (windows/panels.cpp places it).
  const Simulation& sim = *state.sim;
  const int b = state.selected_body;
  if (b < 0) {
    ImGui::TextWrapped(
        "Click a body in the world view to see its data. Ctrl-drag moves a thing (or a whole "
        "robot by its main body) over the floor.");
  } else if (b == 0) {
    ImGui::Text("the world (an obstacle)");
  } else {
    const scene::Body& body = sim.scene().bodies[b - 1];
    const Pose& p = sim.body_pose(b);
    const Twist& v = sim.body_twist(b);
    const char* owner = body.robot >= 0 ? sim.scene().robots[body.robot].id.c_str() : "(thing)";
    ImGui::Text("%s of %s", body.id.c_str(), owner);
    ImGui::Text("mass %.4g kg   file %s", body.mass_kg, body.where.file.c_str());
    ImGui::Separator();
    ImGui::Text("position  x %9.4f  y %9.4f  z %9.4f m", p.position.x, p.position.y, p.position.z);
    ImGui::Text("yaw %8.2f deg", yaw_of(p.rotation) * 180 / kPi);
    ImGui::Text("velocity  x %9.4f  y %9.4f  z %9.4f m/s", v.linear_m_s.x, v.linear_m_s.y,
                v.linear_m_s.z);
    ImGui::Text("angular   x %9.4f  y %9.4f  z %9.4f rad/s", v.angular_rad_s.x, v.angular_rad_s.y,
                v.angular_rad_s.z);
    if (body.robot >= 0 && button(state, "Follow this robot"))
      state.camera.follow_robot = body.robot;
  }
}

}  // namespace s2sim::viewer
