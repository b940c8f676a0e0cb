#include "windows.hpp"

#include <imgui.h>
#include <imgui_stdlib.h>

#include <algorithm>
#include <cmath>
#include <cstdio>

namespace s2sim::viewer {
namespace {

ImU32 series_colour(std::size_t k) {
  static const ImU32 palette[] = {IM_COL32(31, 119, 180, 255),  IM_COL32(255, 127, 14, 255),
                                  IM_COL32(44, 160, 44, 255),   IM_COL32(214, 39, 40, 255),
                                  IM_COL32(148, 103, 189, 255), IM_COL32(140, 86, 75, 255),
                                  IM_COL32(227, 119, 194, 255), IM_COL32(127, 127, 127, 255),
                                  IM_COL32(188, 189, 34, 255),  IM_COL32(23, 190, 207, 255)};
  return palette[k % (sizeof palette / sizeof palette[0])];
}

/// A "nice" tick spacing (1, 2 or 5 times a power of ten) for about `count` ticks.
double tick_step(double span, int count) {
  const double raw = span / std::max(1, count);
  const double p = std::pow(10.0, std::floor(std::log10(raw)));
  for (double m : {1.0, 2.0, 5.0})
    if (m * p >= raw) return m * p;
  return 10 * p;
}

void signal_chooser(ViewerState& state) {
  Simulation& sim = *state.sim;
  ImGui::SetNextItemWidth(-1);
  ImGui::InputTextWithHint("##filter", "filter signals, e.g. axes", &state.chart_view.filter);
  ImGui::BeginChild("signals", ImVec2(0, 0), true);
  for (std::size_t i = 0; i < sim.signal_count(); ++i) {
    const SignalInfo& info = sim.signal_info(i);
    if (info.name == "time") continue;
    if (!state.chart_view.filter.empty() &&
        info.name.find(state.chart_view.filter) == std::string::npos)
      continue;
    bool on = state.chart.has_signal(i);
    if (ImGui::Checkbox(info.name.c_str(), &on)) {
      if (on)
        state.chart.add_signal(i);
      else
        state.chart.remove_signal(i);
    }
  }
  ImGui::EndChild();
}

void plot(ViewerState& state) {
  const ChartData& chart = state.chart;
  ChartView& view = state.chart_view;
  const Simulation& sim = *state.sim;
  const auto& times = chart.times_s();

  const ImVec2 origin = ImGui::GetCursorScreenPos();
  const ImVec2 avail = ImGui::GetContentRegionAvail();
  const float legend_h = ImGui::GetTextLineHeightWithSpacing() *
                         static_cast<float>(std::max<std::size_t>(1, chart.signals().size()));
  const ImVec2 size(std::max(100.0f, avail.x), std::max(80.0f, avail.y - legend_h - 4));
  ImGui::InvisibleButton("plot", size);
  const bool hovered = ImGui::IsItemHovered();
  // Wheel over the plot zooms the time axis.
  if (hovered && ImGui::GetIO().MouseWheel != 0)
    view.window_s =
        std::clamp(view.window_s * std::pow(0.85, ImGui::GetIO().MouseWheel), 0.01, 1e6);

  // The newest samples at the right edge; before a full span has run, time 0 at the left.
  const double end_s = std::max(view.frozen ? view.frozen_end_s : sim.time_s(), view.window_s);
  const double start_s = end_s - view.window_s;
  const auto first = static_cast<std::size_t>(
      std::lower_bound(times.begin(), times.end(), start_s) - times.begin());
  const auto last =
      static_cast<std::size_t>(std::upper_bound(times.begin(), times.end(), end_s) - times.begin());

  double lo = INFINITY, hi = -INFINITY;
  for (std::size_t k = 0; k < chart.signals().size(); ++k)
    for (std::size_t i = first; i < last; ++i) {
      const double v = chart.values(k)[i];
      if (std::isfinite(v)) {
        lo = std::min(lo, v);
        hi = std::max(hi, v);
      }
    }
  if (!(lo <= hi)) lo = -1, hi = 1;
  if (hi - lo < 1e-12) lo -= 0.5, hi += 0.5;
  const double margin = 0.05 * (hi - lo);
  lo -= margin;
  hi += margin;

  ImDrawList* dl = ImGui::GetWindowDrawList();
  const float left = origin.x + 60, right = origin.x + size.x - 8;
  const float top = origin.y + 6, bottom = origin.y + size.y - 20;
  dl->AddRectFilled(ImVec2(left, top), ImVec2(right, bottom), IM_COL32(255, 255, 255, 255));
  auto x_of = [&](double t) {
    return left + static_cast<float>((t - start_s) / view.window_s) * (right - left);
  };
  auto y_of = [&](double v) {
    return bottom - static_cast<float>((v - lo) / (hi - lo)) * (bottom - top);
  };
  char label[32];
  const double ty = tick_step(hi - lo, 5);
  for (double v = std::ceil(lo / ty) * ty; v <= hi; v += ty) {
    dl->AddLine(ImVec2(left, y_of(v)), ImVec2(right, y_of(v)), IM_COL32(220, 220, 220, 255));
    std::snprintf(label, sizeof label, "%.4g", std::abs(v) < ty * 1e-6 ? 0.0 : v);
    dl->AddText(ImVec2(origin.x + 2, y_of(v) - 7), IM_COL32(230, 230, 230, 255), label);
  }
  const double tx = tick_step(view.window_s, 8);
  for (double t = std::ceil(start_s / tx) * tx; t <= end_s; t += tx) {
    dl->AddLine(ImVec2(x_of(t), top), ImVec2(x_of(t), bottom), IM_COL32(220, 220, 220, 255));
    std::snprintf(label, sizeof label, "%.4g s", t);
    dl->AddText(ImVec2(x_of(t) - 12, bottom + 3), IM_COL32(230, 230, 230, 255), label);
  }
  dl->PushClipRect(ImVec2(left, top), ImVec2(right, bottom), true);
  // At most about two points per pixel column: long histories draw as fast as short ones.
  const std::size_t stride =
      std::max<std::size_t>(1, (last - first) / static_cast<std::size_t>(2 * (right - left)));
  for (std::size_t k = 0; k < chart.signals().size(); ++k) {
    const auto& values = chart.values(k);
    ImVec2 previous;
    bool has_previous = false;
    for (std::size_t i = first; i < last; i += stride) {
      if (!std::isfinite(values[i])) {
        has_previous = false;
        continue;
      }
      const ImVec2 p(x_of(times[i]), y_of(values[i]));
      if (has_previous) dl->AddLine(previous, p, series_colour(k), 1.5f);
      previous = p;
      has_previous = true;
    }
  }
  dl->PopClipRect();
  dl->AddRect(ImVec2(left, top), ImVec2(right, bottom), IM_COL32(90, 90, 90, 255));

  // Legend with each signal's latest shown value.
  for (std::size_t k = 0; k < chart.signals().size(); ++k) {
    const SignalInfo& info = sim.signal_info(chart.signals()[k]);
    const ImVec2 p = ImGui::GetCursorScreenPos();
    const float h = ImGui::GetTextLineHeight();
    dl->AddRectFilled(ImVec2(p.x, p.y + h * 0.3f), ImVec2(p.x + 16, p.y + h * 0.7f),
                      series_colour(k));
    ImGui::Dummy(ImVec2(20, h));
    ImGui::SameLine();
    const double latest = last > first ? chart.values(k)[last - 1] : NAN;
    ImGui::Text("%s [%s]  %.6g", info.name.c_str(), info.unit.c_str(), latest);
  }
}

}  // namespace

void draw_chart_window(ViewerState& state) {
  // Drawn inside its tab (windows/panels.cpp places it).
  ChartView& view = state.chart_view;
  if (button(state, view.frozen ? "Follow" : "Pause chart")) {
    view.frozen = !view.frozen;
    view.frozen_end_s = state.sim->time_s();
  }
  ImGui::SameLine();
  if (button(state, "Clear chart")) state.chart.clear_samples();
  ImGui::SameLine();
  ImGui::SetNextItemWidth(90);
  float window_s = static_cast<float>(view.window_s);
  if (ImGui::DragFloat("span, s", &window_s, 0.05f, 0.01f, 1e6f, "%.2f",
                       ImGuiSliderFlags_Logarithmic))
    view.window_s = window_s;
  ImGui::SameLine();
  ImGui::SetNextItemWidth(180);
  ImGui::InputText("##csv", &view.csv_file);
  ImGui::SameLine();
  if (button(state, "Export CSV")) {
    const std::string error = state.chart.export_csv(view.csv_file, *state.sim);
    view.status = error.empty() ? "wrote " + view.csv_file : error;
    state.log_message("chart: " + view.status, !error.empty());
  }
  if (!view.status.empty()) {
    ImGui::SameLine();
    ImGui::TextDisabled("%s", view.status.c_str());
  }
  if (ImGui::BeginTable("chart_layout", 2, ImGuiTableFlags_Resizable)) {
    ImGui::TableSetupColumn("signals", ImGuiTableColumnFlags_WidthFixed, 250);
    ImGui::TableSetupColumn("plot", ImGuiTableColumnFlags_WidthStretch);
    ImGui::TableNextRow();
    ImGui::TableNextColumn();
    signal_chooser(state);
    ImGui::TableNextColumn();
    plot(state);
    ImGui::EndTable();
  }
}

}  // namespace s2sim::viewer
