// The host functions that draw or report beside the physics (simtwo-script-api.md §3.6-§3.8):
// trails and chart series (published as annotations for the viewer), the sheet's colours,
// UDP packets one by one.
#include "script_controller.hpp"

namespace s2sim::pascal {

double ScriptController::call_annotations(HostFn fn, const double* a, int n) {
  StepContext& ctx = *ctx_;
  auto need = [&](int count) { require_arguments(fn, n, count); };
  auto trail = [&](double t) -> std::deque<Vec3>& {
    if (t < 0 || t > kMaxTrails) fail(index_error(t));
    return trails_[static_cast<std::size_t>(t)];
  };
  auto chart = [&](double c) -> int& {
    if (c < 0 || c >= kMaxCharts) fail(index_error(c));
    return chart_series_count_[static_cast<std::size_t>(c)];
  };
  switch (fn) {
    case HostFn::ChartSeriesSetCount:
      need(2);
      if (a[1] < 0 || a[1] > kMaxChartSeries) fail(index_error(a[1]));
      chart(a[0]) = static_cast<int>(a[1]);
      return 0;
    case HostFn::ChartSeriesSetColor:
      need(3);
      (void)chart_series(a[0], a[1]);
      return 0;  // the viewer colours series itself (docs/scripting.md)
    case HostFn::ChartSeriesClear:
      need(2);
      ctx.clear_xy_series(chart_series(a[0], a[1]));
      return 0;
    case HostFn::ChartSeriesAddXY:
      need(4);
      ctx.add_xy_point(chart_series(a[0], a[1]), a[2], a[3]);
      return 0;
    case HostFn::ChartSetAxisMinMax:
      need(5);
      (void)chart(a[0]);
      if (a[1] >= a[2] || a[3] >= a[4])
        fail("ChartSetAxisMinMax: each minimum must be below its maximum");
      return 0;  // the viewer's XY chart scales itself (docs/scripting.md)
    case HostFn::ChartSeriesGetCount:
      need(1);
      return chart(a[0]);
    case HostFn::ChartSeriesCreate: {
      need(1);
      int& count = chart(a[0]);
      if (count >= kMaxChartSeries) fail(index_error(count));
      return count++;
    }
    case HostFn::ChartSeriesDeleteAll: {
      need(1);
      int& count = chart(a[0]);
      for (int s = 0; s < kMaxChartSeries; ++s)
        ctx.clear_xy_series(chart_series(a[0], s));
      count = 0;
      return 0;
    }
    case HostFn::AddTrailNode: {
      need(4);
      std::deque<Vec3>& nodes = trail(a[0]);
      nodes.push_back(Vec3{a[1], a[2], a[3]});
      if (nodes.size() > kMaxTrailNodes) nodes.pop_front();
      ctx.add_trail_point(static_cast<int>(a[0]), nodes.back());
      return 0;
    }
    case HostFn::ClearTrail:
      need(1);
      trail(a[0]).clear();
      ctx.clear_trail(static_cast<int>(a[0]));
      return 0;
    case HostFn::DelTrailNode: {
      // The oldest node goes; the viewer's trail is drawn again from the rest.
      need(1);
      std::deque<Vec3>& nodes = trail(a[0]);
      if (nodes.empty()) return 0;
      nodes.pop_front();
      ctx.clear_trail(static_cast<int>(a[0]));
      for (const Vec3& p : nodes)
        ctx.add_trail_point(static_cast<int>(a[0]), p);
      return 0;
    }
    case HostFn::SetTrailColor:
      need(4);
      (void)trail(a[0]);
      return 0;  // the viewer draws every trail red (docs/scripting.md)
    case HostFn::SetRCBackColor:
      need(3);
      if (a[0] < 0 || a[1] < 0) fail(index_error(a[0] < 0 ? a[0] : a[1]));
      return 0;  // the viewer's sheet has no cell colours (docs/scripting.md)
    case HostFn::ReadUDPPacket:
      text_result_ = udp().receive_packet();
      return 0;
    case HostFn::GetUDPPacketCount:
      return udp().packet_count();
    default:
      fail("invalid host call");
  }
}

}  // namespace s2sim::pascal
