#include "windows.hpp"

#include <imgui.h>
#include <s2sim/math.hpp>

#include <cmath>

namespace s2sim::viewer {

void draw_configuration_window(ViewerState& state) {
  // Drawn inside its tab (windows/panels.cpp places it).
  Simulation& sim = *state.sim;
  const scene::Settings& settings = sim.scene().settings;

  if (ImGui::CollapsingHeader("Physics and control", ImGuiTreeNodeFlags_DefaultOpen)) {
    float& step_ms = state.physics_step_ms_edit;
    if (step_ms <= 0) step_ms = static_cast<float>(sim.tick_s() * 1e3);
    ImGui::SetNextItemWidth(120);
    ImGui::InputFloat("physics step, ms", &step_ms, 0, 0, "%.3f");
    ImGui::SameLine();
    if (button(state, "Apply (reloads)")) {
      Options o = state.options;
      o.physics_step_s = step_ms * 1e-3;
      try {
        state.pending_simulation = load_simulation(o);
        state.options = o;
        state.log_message("physics step set to " + std::to_string(step_ms) + " ms");
      } catch (const std::exception& e) {
        state.log_message(e.what(), true);
      }
    }
    ImGui::Text("substeps %d   (settings from %s)", settings.substeps, settings.source.c_str());
    ImGui::Text("controller period %.1f ms", settings.control_period_s * 1e3);
    // Active motor controllers (their period is the drive-train plugin's business).
    for (std::size_t i = 0; i < sim.input_count(); ++i) {
      const std::string& name = sim.input_info(i).name;
      const std::string suffix = "/controller_active";
      if (name.size() > suffix.size() &&
          name.compare(name.size() - suffix.size(), suffix.size(), suffix) == 0 &&
          sim.input(i) != 0)
        ImGui::BulletText("%s: motor controller on",
                          name.substr(0, name.size() - suffix.size()).c_str());
    }
  }

  if (ImGui::CollapsingHeader("Speed and view", ImGuiTreeNodeFlags_DefaultOpen)) {
    ImGui::Checkbox("as fast as possible", &state.run.as_fast_as_possible);
    float speed = static_cast<float>(state.run.speed);
    if (ImGui::SliderFloat("speed", &speed, 0.1f, 100.0f, "%.2fx", ImGuiSliderFlags_Logarithmic))
      state.run.speed = speed;
    ImGui::Checkbox("shadows", &state.render.shadows);
    ImGui::SameLine();
    ImGui::Checkbox("floor grid", &state.render.grid);
    ImGui::SameLine();
    ImGui::Checkbox("sensor beams", &state.show_beams);
    ImGui::SameLine();
    ImGui::Checkbox("joint markers", &state.show_joints);
    ImGui::Checkbox("trails", &state.overlay.trails);
    ImGui::SameLine();
    ImGui::SetNextItemWidth(120);
    ImGui::SliderFloat("trail, s", &state.overlay.trail_length_s, 1, 120, "%.0f",
                       ImGuiSliderFlags_Logarithmic);
    ImGui::Checkbox("names", &state.overlay.labels);
    ImGui::SameLine();
    ImGui::Checkbox("axes", &state.overlay.axes);
    ImGui::SameLine();
    ImGui::Checkbox("scale bar", &state.overlay.scale_bar);
    ImGui::SetNextItemWidth(120);
    ImGui::SliderFloat("font scale", &ImGui::GetIO().FontGlobalScale, 0.5f, 4.0f, "%.2f");
    Camera& cam = state.camera;
    const auto& robots = sim.scene().robots;
    const char* following = cam.follow_robot >= 0 ? robots[cam.follow_robot].id.c_str() : "nothing";
    if (ImGui::BeginCombo("follow", following)) {
      if (ImGui::Selectable("nothing", cam.follow_robot < 0)) cam.follow_robot = -1;
      for (int r = 0; r < static_cast<int>(robots.size()); ++r)
        if (ImGui::Selectable(robots[r].id.c_str(), cam.follow_robot == r)) cam.follow_robot = r;
      ImGui::EndCombo();
    }
    ImGui::Checkbox("keep in view", &cam.keep_in_view);
    if (ImGui::IsItemHovered())
      ImGui::SetTooltip(
          "follow a robot that flies or floats (touches nothing) when it would "
          "leave the view");
    ImGui::DragFloat3("camera target, m", &cam.target_m.x, 0.01f);
    ImGui::DragFloat("camera distance, m", &cam.distance_m, 0.02f, 0.05f, 500.0f);
    float fov_deg = cam.fov_y_rad * 180 / static_cast<float>(kPi);
    if (ImGui::SliderFloat("field of view, deg", &fov_deg, 10, 120))
      cam.fov_y_rad = fov_deg * static_cast<float>(kPi) / 180;
  }

  if (ImGui::CollapsingHeader("Robots", ImGuiTreeNodeFlags_DefaultOpen)) {
    const ImGuiTableFlags flags =
        ImGuiTableFlags_Borders | ImGuiTableFlags_RowBg | ImGuiTableFlags_SizingStretchProp;
    if (ImGui::BeginTable("robots", 7, flags)) {
      for (const char* h : {"robot", "x, m", "y, m", "z, m", "yaw, deg", "speed, m/s", "w, rad/s"})
        ImGui::TableSetupColumn(h);
      ImGui::TableHeadersRow();
      for (const auto& r : sim.scene().robots) {
        if (r.main_body < 0) continue;
        const Pose& p = sim.body_pose(r.main_body + 1);
        const Twist& v = sim.body_twist(r.main_body + 1);
        ImGui::TableNextRow();
        ImGui::TableNextColumn();
        ImGui::TextUnformatted(r.id.c_str());
        const double values[6] = {p.position.x,
                                  p.position.y,
                                  p.position.z,
                                  yaw_of(p.rotation) * 180 / kPi,
                                  std::hypot(v.linear_m_s.x, v.linear_m_s.y),
                                  v.angular_rad_s.z};
        for (double value : values) {
          ImGui::TableNextColumn();
          ImGui::Text("%.3f", value);
        }
      }
      ImGui::EndTable();
    }
  }
}

}  // namespace s2sim::viewer
