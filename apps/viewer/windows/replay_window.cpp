// The Run window of a replay (s2sim-view --replay FILE): play or pause, forwards or
// backwards at any speed, frame by frame, and the timeline that scrubs the recording.
#include "windows.hpp"

#include <imgui.h>

#include <cmath>
#include <cstdio>
#include <filesystem>

namespace s2sim::viewer {

void draw_replay_controls(ViewerState& state) {
  Replay& replay = *state.replay;
  if (replay.playing) {
    if (button(state, "Pause")) replay.playing = false;
  } else if (button(state, "Play")) {
    // From an end, play away from it.
    if (replay.speed > 0 && replay.time_s() >= replay.end_s()) replay.seek(replay.start_s());
    if (replay.speed < 0 && replay.time_s() <= replay.start_s()) replay.seek(replay.end_s());
    replay.playing = true;
  }
  ImGui::SameLine();
  if (button(state, "|<")) replay.seek(replay.start_s());
  ImGui::SameLine();
  if (button(state, "<")) replay.step_frames(-1);
  ImGui::SameLine();
  if (button(state, ">")) replay.step_frames(1);
  ImGui::SameLine();
  if (button(state, ">|")) replay.seek(replay.end_s());
  ImGui::SameLine();
  bool backwards = replay.speed < 0;
  if (ImGui::Checkbox("Backwards", &backwards)) replay.speed = -replay.speed;
  // Logarithmic: 0.01x to 100x in one slider; the sign is the direction.
  float speed = static_cast<float>(std::abs(replay.speed));
  if (ImGui::SliderFloat("Speed", &speed, 0.01f, 100.0f, "%.2fx", ImGuiSliderFlags_Logarithmic))
    replay.speed = backwards ? -speed : speed;
  // The timeline: dragging it scrubs (the replay pauses while it is held).
  float t = static_cast<float>(replay.time_s());
  ImGui::SetNextItemWidth(-1);
  if (ImGui::SliderFloat("##timeline", &t, static_cast<float>(replay.start_s()),
                         static_cast<float>(replay.end_s()), "%.3f s")) {
    replay.seek(t);
  }
  if (ImGui::IsItemActive()) replay.playing = false;
  const auto& rec = replay.recording();
  ImGui::Text("t = %.3f s of %.3f s   frame %zu of %zu", rec.times_s[replay.frame()],
              replay.end_s(), replay.frame() + 1, rec.frame_count());
  char status[160];
  std::snprintf(status, sizeof status, "replay of %s, %s",
                std::filesystem::path(rec.file).filename().string().c_str(),
                replay.playing ? (replay.speed < 0 ? "playing backwards" : "playing") : "paused");
  state.run_status_text = status;
  ImGui::TextUnformatted(status);
}

}  // namespace s2sim::viewer
