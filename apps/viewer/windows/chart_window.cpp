#include "windows.hpp"

#include <imgui.h>
#include <imgui_stdlib.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <string>
#include <utility>
#include <vector>

namespace s2sim::viewer {
namespace {

/// The chart's draw budget per frame (segments of all signals together), and the fewest points
/// a signal is drawn with however many share the budget.
constexpr std::size_t kMaxChartSegments = std::size_t{1} << 16;
constexpr std::size_t kMinChartPointsPerSignal = 64;

ImU32 series_colour(std::size_t k) {
  static const ImU32 palette[] = {IM_COL32(31, 119, 180, 255),  IM_COL32(255, 127, 14, 255),
                                  IM_COL32(44, 160, 44, 255),   IM_COL32(214, 39, 40, 255),
                                  IM_COL32(148, 103, 189, 255), IM_COL32(140, 86, 75, 255),
                                  IM_COL32(227, 119, 194, 255), IM_COL32(127, 127, 127, 255),
                                  IM_COL32(188, 189, 34, 255),  IM_COL32(23, 190, 207, 255)};
  return palette[k % (sizeof palette / sizeof palette[0])];
}

/// A legend entry's coloured swatch for series `k`, the cursor left on its line for the text.
void legend_swatch(ImDrawList* dl, std::size_t k) {
  const ImVec2 p = ImGui::GetCursorScreenPos();
  const float h = ImGui::GetTextLineHeight();
  dl->AddRectFilled(ImVec2(p.x, p.y + h * 0.3f), ImVec2(p.x + 16, p.y + h * 0.7f),
                    series_colour(k));
  ImGui::Dummy(ImVec2(20, h));
  ImGui::SameLine();
}

/// A legend: one entry a series (its swatch and text), laid out in rows that fill the width, so
/// that the plot above keeps as many lines as it can. Past `max_height` it scrolls: every
/// entry stays listed.
class Legend {
 public:
  /// `title` (may be empty) comes first, without a swatch.
  Legend(std::string title, std::vector<std::string> texts, float width)
      : title_(std::move(title)), texts_(std::move(texts)) {
    float x = 0;
    rows_ = texts_.empty() ? 0 : 1;
    for (std::size_t k = 0; k <= texts_.size(); ++k) {
      const float w = entry_width(k);
      if (w == 0) continue;
      if (x > 0 && x + w > width) ++rows_, x = 0;
      x += w;
    }
  }
  /// The height it takes, at most `max_height` (then it scrolls).
  float height(float max_height) const {
    const float all = ImGui::GetTextLineHeightWithSpacing() * static_cast<float>(rows_);
    return std::min(all, std::max(ImGui::GetTextLineHeightWithSpacing(), max_height));
  }
  /// In rows that fill the width, or (`column`) one entry a line, wrapped at the width.
  void draw(float height, bool column = false) const {
    if (texts_.empty()) return;
    ImGui::BeginChild("legend", ImVec2(0, height), false);
    const float width = ImGui::GetContentRegionAvail().x;
    if (column) ImGui::PushTextWrapPos(0.0f);
    float x = 0;
    for (std::size_t k = 0; k <= texts_.size(); ++k) {
      const float w = entry_width(k);
      if (w == 0) continue;
      if (!column && x > 0 && x + w <= width)
        ImGui::SameLine(0, 2 * ImGui::GetStyle().ItemSpacing.x);
      else
        x = 0;
      x += w;
      if (k == 0) {
        ImGui::TextDisabled("%s", title_.c_str());
        continue;
      }
      legend_swatch(ImGui::GetWindowDrawList(), k - 1);
      ImGui::TextUnformatted(texts_[k - 1].c_str());
    }
    if (column) ImGui::PopTextWrapPos();
    ImGui::EndChild();
  }

 private:
  static constexpr float kSwatchWidth = 20;
  /// Entry 0 is the title (0 wide when there is none), entry k the series k - 1.
  float entry_width(std::size_t k) const {
    const float gap = 2 * ImGui::GetStyle().ItemSpacing.x;
    if (k == 0) return title_.empty() ? 0 : ImGui::CalcTextSize(title_.c_str()).x + gap;
    return kSwatchWidth + ImGui::CalcTextSize(texts_[k - 1].c_str()).x + gap;
  }

  std::string title_;
  std::vector<std::string> texts_;
  int rows_ = 0;
};

/// The length of the folders (up to and with a '/') that the names of all `signals` begin
/// with, when there are two or more.
std::size_t shared_folders(const Simulation& sim, const std::vector<std::size_t>& signals) {
  if (signals.size() < 2) return 0;
  const std::string& first = sim.signal_info(signals[0]).name;
  std::size_t common = first.size();
  for (std::size_t i : signals) {
    const std::string& name = sim.signal_info(i).name;
    std::size_t n = 0;
    while (n < common && n < name.size() && name[n] == first[n])
      ++n;
    common = n;
  }
  const std::size_t slash = first.rfind('/', common == 0 ? 0 : common - 1);
  return common == 0 || slash == std::string::npos ? 0 : slash + 1;
}

/// The plot's and the legend's heights in `avail_h`: the legend takes what its rows need, up to
/// 40 % of the height (then it scrolls); the plot the rest.
std::pair<float, float> plot_and_legend_heights(const Legend& legend, float avail_h) {
  const float legend_h = legend.height(0.4f * avail_h);
  return {std::max(60.0f, avail_h - legend_h - ImGui::GetStyle().ItemSpacing.y), legend_h};
}

/// How many ticks an axis of `length_px` has room for, a label every `label_px` at most (2 to
/// 8 ticks).
int ticks_along(float length_px, float label_px) {
  return std::clamp(static_cast<int>(length_px / label_px), 2, 8);
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
  const auto times = chart.times_s();

  // The newest samples at the right edge; before a full span has run, time 0 at the left.
  const double end_s = std::max(view.frozen ? view.frozen_end_s : sim.time_s(), view.window_s);
  const double start_s = end_s - view.window_s;
  const auto first = static_cast<std::size_t>(
      std::lower_bound(times.begin(), times.end(), start_s) - times.begin());
  const auto last =
      static_cast<std::size_t>(std::upper_bound(times.begin(), times.end(), end_s) - times.begin());

  // Each signal's legend entry with its latest shown value; the folders that all the names
  // share are said once, so that more entries fit on a row.
  const std::size_t shared = shared_folders(sim, chart.signals());
  std::vector<std::string> entries;
  for (std::size_t k = 0; k < chart.signals().size(); ++k) {
    const SignalInfo& info = sim.signal_info(chart.signals()[k]);
    char value[32];
    std::snprintf(value, sizeof value, "%.5g", last > first ? chart.values(k)[last - 1] : NAN);
    entries.push_back(info.name.substr(shared) + " [" + info.unit + "]  " + value);
  }
  const std::string title =
      shared > 0 ? sim.signal_info(chart.signals()[0]).name.substr(0, shared) : "";
  const ImVec2 origin = ImGui::GetCursorScreenPos();
  const ImVec2 avail = ImGui::GetContentRegionAvail();
  const Legend legend(title, std::move(entries), avail.x);
  const auto [plot_h, legend_h] = plot_and_legend_heights(legend, avail.y);
  const ImVec2 size(std::max(100.0f, avail.x), plot_h);
  ImGui::InvisibleButton("plot", size);
  const bool hovered = ImGui::IsItemHovered();
  // Wheel over the plot zooms the time axis.
  if (hovered && ImGui::GetIO().MouseWheel != 0)
    view.window_s =
        std::clamp(view.window_s * std::pow(0.85, ImGui::GetIO().MouseWheel), 0.01, 1e6);

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
  const double ty = tick_step(hi - lo, ticks_along(bottom - top, 25));
  for (double v = std::ceil(lo / ty) * ty; v <= hi; v += ty) {
    dl->AddLine(ImVec2(left, y_of(v)), ImVec2(right, y_of(v)), IM_COL32(220, 220, 220, 255));
    std::snprintf(label, sizeof label, "%.4g", std::abs(v) < ty * 1e-6 ? 0.0 : v);
    dl->AddText(ImVec2(origin.x + 2, y_of(v) - 7), IM_COL32(230, 230, 230, 255), label);
  }
  const double tx = tick_step(view.window_s, ticks_along(right - left, 70));
  for (double t = std::ceil(start_s / tx) * tx; t <= end_s; t += tx) {
    dl->AddLine(ImVec2(x_of(t), top), ImVec2(x_of(t), bottom), IM_COL32(220, 220, 220, 255));
    std::snprintf(label, sizeof label, "%.4g s", t);
    dl->AddText(ImVec2(x_of(t) - 12, bottom + 3), IM_COL32(230, 230, 230, 255), label);
  }
  dl->PushClipRect(ImVec2(left, top), ImVec2(right, bottom), true);
  // At most about two points per pixel column, so long histories draw as fast as short ones,
  // and at most kMaxChartSegments segments for all the signals together: each segment is
  // ImGui draw data (about 100 bytes), which 881 signals at two points a column made 650 MB.
  const std::size_t columns = static_cast<std::size_t>(2 * std::max(1.0f, right - left));
  const std::size_t per_signal =
      std::max<std::size_t>(kMinChartPointsPerSignal,
                            kMaxChartSegments / std::max<std::size_t>(1, chart.signals().size()));
  const std::size_t stride =
      std::max<std::size_t>(1, (last - first) / std::min(columns, per_signal));
  // One polyline per finite run (half the vertices of a line per segment), one pixel wide so
  // that ImGui draws it anti-aliased from its texture: two triangles a segment.
  static std::vector<ImVec2> run;  // the UI thread's scratch, kept between frames
  run.reserve(kMaxChartSegments);
  auto flush = [&](std::size_t k) {
    if (run.size() >= 2)
      dl->AddPolyline(run.data(), static_cast<int>(run.size()), series_colour(k), 0, 1.0f);
    run.clear();
  };
  for (std::size_t k = 0; k < chart.signals().size(); ++k) {
    const auto values = chart.values(k);
    for (std::size_t i = first; i < last; i += stride) {
      if (!std::isfinite(values[i])) {
        flush(k);
        continue;
      }
      run.emplace_back(x_of(times[i]), y_of(values[i]));
    }
    flush(k);
  }
  dl->PopClipRect();
  dl->AddRect(ImVec2(left, top), ImVec2(right, bottom), IM_COL32(90, 90, 90, 255));

  legend.draw(legend_h);
}

/// XY mode: one charted signal against another over the visible time span (a trajectory),
/// and the XY series a SimTwo script publishes (ChartSeriesAddXY), each axis scaled to its
/// data with equal metres per pixel when both share a unit (a path keeps its shape).
void plot_xy(ViewerState& state) {
  const ChartData& chart = state.chart;
  ChartView& view = state.chart_view;
  const Simulation& sim = *state.sim;
  const auto& signals = chart.signals();
  auto chooser = [&](const char* label, int& series) {
    const char* current =
        series >= 0 && series < static_cast<int>(signals.size())
            ? sim.signal_info(signals[static_cast<std::size_t>(series)]).name.c_str()
            : "(tick a signal)";
    ImGui::SetNextItemWidth(220);
    if (ImGui::BeginCombo(label, current)) {
      for (std::size_t k = 0; k < signals.size(); ++k)
        if (ImGui::Selectable(sim.signal_info(signals[k]).name.c_str(),
                              static_cast<int>(k) == series))
          series = static_cast<int>(k);
      ImGui::EndCombo();
    }
  };
  chooser("X##xy", view.x_series);
  ImGui::SameLine();
  chooser("Y##xy", view.y_series);

  // The curves: (x, y) pairs, the charted pair first, then the script's series.
  struct Curve {
    std::vector<std::pair<double, double>> points;
    std::string name;
  };
  std::vector<Curve> curves;
  const bool pair_ok = view.x_series >= 0 && view.y_series >= 0 &&
                       view.x_series < static_cast<int>(signals.size()) &&
                       view.y_series < static_cast<int>(signals.size());
  std::string unit_x, unit_y;
  if (pair_ok) {
    const auto times = chart.times_s();
    const double end_s = view.frozen ? view.frozen_end_s : sim.time_s();
    const auto first = static_cast<std::size_t>(
        std::lower_bound(times.begin(), times.end(), end_s - view.window_s) - times.begin());
    const auto xs = chart.values(static_cast<std::size_t>(view.x_series));
    const auto ys = chart.values(static_cast<std::size_t>(view.y_series));
    Curve c;
    const SignalInfo& ix = sim.signal_info(signals[static_cast<std::size_t>(view.x_series)]);
    const SignalInfo& iy = sim.signal_info(signals[static_cast<std::size_t>(view.y_series)]);
    unit_x = ix.unit, unit_y = iy.unit;
    c.name = iy.name + " against " + ix.name;
    const std::size_t stride = std::max<std::size_t>(1, (times.size() - first) / 4000);
    for (std::size_t i = first; i < times.size(); i += stride)
      if (std::isfinite(xs[i]) && std::isfinite(ys[i])) c.points.emplace_back(xs[i], ys[i]);
    curves.push_back(std::move(c));
  }
  for (const auto& series : sim.annotations().series) {
    Curve c;
    c.name = series.source + " series " + std::to_string(series.id);
    c.points.assign(series.points.begin(), series.points.end());
    curves.push_back(std::move(c));
  }

  std::vector<std::string> entries;
  for (const Curve& c : curves)
    entries.push_back(c.name + "  (" + std::to_string(c.points.size()) + " points)");
  const ImVec2 origin = ImGui::GetCursorScreenPos();
  const ImVec2 avail = ImGui::GetContentRegionAvail();
  const Legend legend("", std::move(entries), avail.x);
  const float hint_h = curves.empty() ? ImGui::GetTextLineHeightWithSpacing() : 0;
  // A short, wide space (the bottom row): the legend beside the plot, which keeps the whole
  // height, as a path needs it (same unit, same scale); otherwise under it.
  const bool beside = avail.x > 3 * avail.y;
  const float beside_w = beside ? std::clamp(2.0f * avail.y, 200.0f, 0.6f * avail.x) : 0;
  const auto [plot_h, legend_h] =
      beside ? std::pair<float, float>{std::max(60.0f, avail.y - hint_h), avail.y - hint_h}
             : plot_and_legend_heights(legend, avail.y - hint_h);
  const ImVec2 size(beside ? beside_w : std::max(100.0f, avail.x), plot_h);
  ImGui::InvisibleButton("xyplot", size);
  double x0 = INFINITY, x1 = -INFINITY, y0 = INFINITY, y1 = -INFINITY;
  for (const Curve& c : curves)
    for (const auto& [x, y] : c.points) {
      x0 = std::min(x0, x), x1 = std::max(x1, x), y0 = std::min(y0, y), y1 = std::max(y1, y);
    }
  if (!(x0 <= x1)) x0 = -1, x1 = 1, y0 = -1, y1 = 1;
  if (x1 - x0 < 1e-12) x0 -= 0.5, x1 += 0.5;
  if (y1 - y0 < 1e-12) y0 -= 0.5, y1 += 0.5;
  ImDrawList* dl = ImGui::GetWindowDrawList();
  const float left = origin.x + 60, right = origin.x + size.x - 8;
  const float top = origin.y + 6, bottom = origin.y + size.y - 20;
  // Same unit on both axes: the same scale, so a path keeps its shape.
  if (unit_x == unit_y || unit_x.empty()) {
    const double per_px = std::max((x1 - x0) / (right - left), (y1 - y0) / (bottom - top));
    const double cx = 0.5 * (x0 + x1), cy = 0.5 * (y0 + y1);
    x0 = cx - 0.5 * per_px * (right - left), x1 = cx + 0.5 * per_px * (right - left);
    y0 = cy - 0.5 * per_px * (bottom - top), y1 = cy + 0.5 * per_px * (bottom - top);
  }
  const double mx = 0.05 * (x1 - x0), my = 0.05 * (y1 - y0);
  x0 -= mx, x1 += mx, y0 -= my, y1 += my;
  auto px = [&](double x) {
    return left + static_cast<float>((x - x0) / (x1 - x0)) * (right - left);
  };
  auto py = [&](double y) {
    return bottom - static_cast<float>((y - y0) / (y1 - y0)) * (bottom - top);
  };
  dl->AddRectFilled(ImVec2(left, top), ImVec2(right, bottom), IM_COL32(255, 255, 255, 255));
  char label[32];
  const double ty = tick_step(y1 - y0, ticks_along(bottom - top, 25));
  const double tx = tick_step(x1 - x0, ticks_along(right - left, 70));
  for (double v = std::ceil(y0 / ty) * ty; v <= y1; v += ty) {
    dl->AddLine(ImVec2(left, py(v)), ImVec2(right, py(v)), IM_COL32(220, 220, 220, 255));
    std::snprintf(label, sizeof label, "%.4g", std::abs(v) < ty * 1e-6 ? 0.0 : v);
    dl->AddText(ImVec2(origin.x + 2, py(v) - 7), IM_COL32(230, 230, 230, 255), label);
  }
  for (double v = std::ceil(x0 / tx) * tx; v <= x1; v += tx) {
    dl->AddLine(ImVec2(px(v), top), ImVec2(px(v), bottom), IM_COL32(220, 220, 220, 255));
    std::snprintf(label, sizeof label, "%.4g", std::abs(v) < tx * 1e-6 ? 0.0 : v);
    dl->AddText(ImVec2(px(v) - 12, bottom + 3), IM_COL32(230, 230, 230, 255), label);
  }
  dl->PushClipRect(ImVec2(left, top), ImVec2(right, bottom), true);
  for (std::size_t k = 0; k < curves.size(); ++k) {
    const auto& points = curves[k].points;
    for (std::size_t i = 1; i < points.size(); ++i)
      dl->AddLine(ImVec2(px(points[i - 1].first), py(points[i - 1].second)),
                  ImVec2(px(points[i].first), py(points[i].second)), series_colour(k), 1.5f);
    if (!points.empty())  // where it is now
      dl->AddCircleFilled(ImVec2(px(points.back().first), py(points.back().second)), 4,
                          series_colour(k));
  }
  dl->PopClipRect();
  dl->AddRect(ImVec2(left, top), ImVec2(right, bottom), IM_COL32(90, 90, 90, 255));
  if (beside) ImGui::SameLine();
  legend.draw(legend_h, beside);
  if (curves.empty())
    ImGui::TextDisabled(
        "Tick two signals, then choose X and Y (or run a script that calls "
        "ChartSeriesAddXY).");
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
  ImGui::Checkbox("XY", &view.xy);
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
    if (state.chart_view.xy)
      plot_xy(state);
    else
      plot(state);
    ImGui::EndTable();
  }
}

}  // namespace s2sim::viewer
