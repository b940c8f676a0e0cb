#include "viewer_state.hpp"

#include "headless_camera_renderer.hpp"
#include "scene_search.hpp"
#include "simulation_options.hpp"

#include <imgui.h>

#include <algorithm>

namespace s2sim::viewer {

bool button(ViewerState& state, const char* label) {
  const bool clicked = ImGui::Button(label);
  auto& pending = state.scripted_clicks;
  const auto it = std::find(pending.begin(), pending.end(), label);
  if (it == pending.end()) return clicked;
  pending.erase(it);
  return true;
}

bool move_body(ViewerState& state, int body, const Vec3& position_m) {
  Pose pose = state.sim->body_pose(body);
  pose.position = position_m;
  try {
    state.sim->place_body(body, pose);
    return true;
  } catch (const std::exception& e) {
    state.log_message(e.what(), true);
    return false;
  }
}

std::unique_ptr<Simulation> load_simulation(const Options& o) {
  SimulationOptions options = apps::simulation_options(o);
  options.sheet_cells = o.sheet_cells;
  auto sim = Simulation::load(apps::find_scene(o.scene), options);
  // Cameras draw on the stepping thread, into a headless context of their own.
  sim->set_camera_renderer(render::headless_camera_renderer_factory());
  for (const auto& [name, value] : o.inputs)
    sim->set_input(name, value);
  return sim;
}

}  // namespace s2sim::viewer
