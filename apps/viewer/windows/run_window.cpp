#include "windows.hpp"

#include <imgui.h>

#include <cmath>
#include <cstdio>

namespace s2sim::viewer {

void draw_run_window(ViewerState& state) {
  // Placed at the top of the left column by windows/panels.cpp.
  if (!ImGui::Begin("Run", &state.windows.run,
                    ImGuiWindowFlags_NoMove | ImGuiWindowFlags_NoCollapse |
                        ImGuiWindowFlags_NoResize | ImGuiWindowFlags_NoSavedSettings)) {
    ImGui::End();
    return;
  }
  if (state.replay) {
    draw_replay_controls(state);
    ImGui::End();
    return;
  }
  RunControl& run = state.run;
  if (run.playing) {
    if (button(state, "Pause")) run.playing = false;
  } else {
    if (button(state, "Play")) run.playing = true;
  }
  ImGui::SameLine();
  if (button(state, "Step")) run.request_step(1);
  ImGui::SameLine();
  if (button(state, "Step 10 ms"))
    run.request_step(std::max<std::int64_t>(1, std::llround(0.01 / state.sim->tick_s())));
  ImGui::SameLine();
  if (button(state, "Reset")) run.request_reset();
  ImGui::SameLine();
  ImGui::TextDisabled("(?)");
  if (ImGui::IsItemHovered())
    ImGui::SetTooltip(
        "Keys: space play/pause, S or right arrow step, R reset.\n"
        "Mouse: left drag orbit, right drag pan, wheel zoom, click a body for its data,\n"
        "ctrl + left drag moves a thing.");

  ImGui::Checkbox("As fast as possible", &run.as_fast_as_possible);
  if (!run.as_fast_as_possible) {
    // Logarithmic: the useful range 0.1x..100x in one slider.
    float speed = static_cast<float>(run.speed);
    if (ImGui::SliderFloat("Speed", &speed, 0.1f, 100.0f, "%.2fx", ImGuiSliderFlags_Logarithmic))
      run.speed = speed;
  }
  ImGui::Text("t = %.3f s   tick %lld of %g ms", state.sim->time_s(),
              static_cast<long long>(state.sim->tick()), state.sim->tick_s() * 1e3);
  const double fps = state.frame_time_s > 0 ? 1.0 / state.frame_time_s : 0.0;
  // Kept in the state too, so scripts and tests read exactly what is shown (`print rtf`).
  char status[96];
  if (run.playing)
    std::snprintf(status, sizeof status, "real-time factor %.2fx%s   %.0f fps", run.measured_rtf(),
                  run.falling_behind() ? " (cannot keep up)" : "", fps);
  else
    std::snprintf(status, sizeof status, "paused   %.0f fps", fps);
  state.run_status_text = status;
  ImGui::TextUnformatted(status);
  // The other windows open from the View menu (windows/panels.cpp).
  ImGui::End();
}

}  // namespace s2sim::viewer
