// The notice while a component's call has not returned (stuck_window.hpp).
#include "stuck_window.hpp"

#include <imgui.h>

namespace s2sim::viewer {

bool draw_stuck_window(ViewerState& state) {
  const Rect& world = state.layout_rects.world;
  ImGui::SetNextWindowPos(ImVec2(world.x + world.width * 0.5f, world.y + world.height * 0.5f),
                          ImGuiCond_Always, ImVec2(0.5f, 0.5f));
  ImGui::SetNextWindowSize(ImVec2(world.width * 0.6f, 0));
  ImGui::Begin("The simulation does not answer", nullptr,
               ImGuiWindowFlags_NoCollapse | ImGuiWindowFlags_NoSavedSettings);
  ImGui::PushTextWrapPos(0);
  if (state.stuck.component.empty())
    ImGui::Text("The simulation's step has not returned for %.1f s (the kernel's own code).",
                state.stuck.running_s);
  else
    ImGui::Text("%s has not returned from one call for %.1f s.", state.stuck.component.c_str(),
                state.stuck.running_s);
  ImGui::TextDisabled(
      "The simulation goes on if the call returns. Stopping it leaves the call running on its "
      "own thread (native code cannot be stopped safely) and loads the scene again, paused.");
  ImGui::PopTextWrapPos();
  const bool stop = button(state, "Stop the simulation");
  ImGui::End();
  return stop;
}

}  // namespace s2sim::viewer
