#include "windows.hpp"

#include <imgui.h>

#include <cmath>

namespace s2sim::viewer {

void draw_run_window(ViewerState& state) {
  if (!state.windows.run) return;
  ImGui::SetNextWindowPos(ImVec2(10, 10), ImGuiCond_FirstUseEver);
  ImGui::SetNextWindowSize(ImVec2(430, 150), ImGuiCond_FirstUseEver);
  if (!ImGui::Begin("Run", &state.windows.run)) {
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
  if (run.playing)
    ImGui::Text("real-time factor %.2fx%s   %.0f fps", run.measured_rtf(),
                run.falling_behind() ? " (cannot keep up)" : "", fps);
  else
    ImGui::Text("paused   %.0f fps", fps);
  ImGui::TextDisabled("Windows:");
  ImGui::SameLine();
  ImGui::Checkbox("Config", &state.windows.configuration);
  ImGui::SameLine();
  ImGui::Checkbox("Chart", &state.windows.chart);
  ImGui::SameLine();
  ImGui::Checkbox("Sheet", &state.windows.sheet);
  ImGui::SameLine();
  ImGui::Checkbox("Editor", &state.windows.editor);
  ImGui::SameLine();
  ImGui::Checkbox("Log", &state.windows.log);
  ImGui::End();
}

}  // namespace s2sim::viewer
