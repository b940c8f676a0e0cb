// SimTwo's spray-painting routines (simtwo-script-api.md §4; docs/models/sensors.md, "Spray
// painting"): the guns are the `spraygun` sensors of SimTwo's world-wide list in its order,
// the targets the scene's painting targets (ConfigureContext::painting_targets). A target's
// paint is read from the guns' signals `paint/<k>/<t>` and summed; the statistics are
// SimTwo's: over every triangle unweighted, the Pos ones over the painted (thickness > 0).
#include "script_controller.hpp"

#include <algorithm>
#include <array>
#include <limits>
#include <map>

namespace s2sim::pascal {

namespace {

/// SimTwo's start for a minimum: what PosMin reads when nothing is painted.
constexpr double kSimTwoMinStart = 10000;

/// Per triangle of `vertices`, the others that share a vertex with it (by exact position),
/// in increasing order.
void vertex_neighbours(const std::vector<Vec3>& vertices, std::vector<int>& of,
                       std::vector<int>& list) {
  std::map<std::array<double, 3>, std::vector<int>> at;
  const int count = static_cast<int>(vertices.size() / 3);
  for (int t = 0; t < count; ++t)
    for (int v = 0; v < 3; ++v) {
      const Vec3& p = vertices[static_cast<std::size_t>(3 * t + v)];
      std::vector<int>& ts = at[{p.x, p.y, p.z}];
      if (ts.empty() || ts.back() != t) ts.push_back(t);
    }
  of.assign(1, 0);
  std::vector<int> mine;
  for (int t = 0; t < count; ++t) {
    mine.clear();
    for (int v = 0; v < 3; ++v) {
      const Vec3& p = vertices[static_cast<std::size_t>(3 * t + v)];
      for (int u : at[{p.x, p.y, p.z}])
        if (u != t) mine.push_back(u);
    }
    std::sort(mine.begin(), mine.end());
    mine.erase(std::unique(mine.begin(), mine.end()), mine.end());
    list.insert(list.end(), mine.begin(), mine.end());
    of.push_back(static_cast<int>(list.size()));
  }
}

}  // namespace

void ScriptController::configure_paint(ConfigureContext& ctx) {
  std::size_t largest = 0;
  for (PaintingTarget& pt : ctx.painting_targets()) {
    PaintTargetRef t;
    t.id = pt.id;
    t.body = pt.body;
    t.vertices = std::move(pt.vertices_m);
    vertex_neighbours(t.vertices, t.neighbors_of, t.neighbors);
    largest = std::max(largest, t.vertices.size() / 3);
    paint_targets_.push_back(std::move(t));
  }
  paint_scratch_.assign(largest, 0.0);
  for (std::size_t k = 0; k < paint_targets_.size(); ++k) {
    const std::string name = "paint_targets/" + std::to_string(k) + "/resets";
    if (!ctx.input_names(name).empty()) paint_targets_[k].resets = ctx.input(name);
  }
  for (const SensorRef& s : sensors_) {
    if (s.kind != "spraygun") continue;
    SprayGunRef g;
    g.prefix = s.prefix;
    if (!ctx.input_names(s.prefix + "/on").empty()) {  // else no plugin gives the kind
      g.on = ctx.input(s.prefix + "/on");
      g.min_dist = ctx.published_signal(s.prefix + "/min_dist");
      for (std::size_t k = 0; k < paint_targets_.size(); ++k) {
        const std::string key = s.prefix + "/paint/" + std::to_string(k) + "/";
        g.resets_seen.push_back(ctx.published_signal(key + "resets"));
        std::vector<SignalHandle> per_triangle;
        for (int t = 0; t < paint_targets_[k].count(); ++t)
          per_triangle.push_back(ctx.published_signal(key + std::to_string(t)));
        g.thickness.push_back(std::move(per_triangle));
      }
    }
    spray_guns_.push_back(std::move(g));
  }
}

SprayGunRef& ScriptController::spray_gun(double i) {
  if (i < 0 || i >= static_cast<double>(spray_guns_.size())) fail(index_error(i));
  SprayGunRef& g = spray_guns_[static_cast<std::size_t>(i)];
  if (g.on.index < 0) fail("spray gun " + g.prefix + " is inert: no plugin gives 'spraygun'");
  return g;
}

PaintTargetRef& ScriptController::paint_target(double i) {
  if (i < 0 || i >= static_cast<double>(paint_targets_.size())) fail(index_error(i));
  return paint_targets_[static_cast<std::size_t>(i)];
}

const double* ScriptController::paint_of(std::size_t k) {
  const PaintTargetRef& t = paint_targets_[k];
  double* out = paint_scratch_.data();
  std::fill(out, out + t.count(), 0.0);
  const double asked = t.resets.index >= 0 ? ctx_->input(t.resets) : 0.0;
  for (const SprayGunRef& g : spray_guns_) {
    if (g.on.index < 0 || ctx_->signal(g.resets_seen[k]) != asked) continue;
    const std::vector<SignalHandle>& mine = g.thickness[k];
    for (int i = 0; i < t.count(); ++i)
      out[i] += ctx_->signal(mine[static_cast<std::size_t>(i)]);
  }
  return out;
}

double ScriptController::call_paint(HostFn fn, const double* a, int n) {
  StepContext& ctx = *ctx_;
  require_arguments(fn, n, 1);
  switch (fn) {
    case HostFn::SetSprayGunOn:
      ctx.set_input(spray_gun(a[0]).on, 1);
      return 0;
    case HostFn::SetSprayGunOff:
      ctx.set_input(spray_gun(a[0]).on, 0);
      return 0;
    case HostFn::GetPaintGunMinDist:
      return ctx.signal(spray_gun(a[0]).min_dist);
    case HostFn::ResetPaintTargetPaint: {
      const PaintTargetRef& t = paint_target(a[0]);
      if (t.resets.index >= 0) ctx.set_input(t.resets, ctx.input(t.resets) + 1);
      return 0;
    }
    case HostFn::SetPaintTargetPaintMode: {
      require_arguments(fn, n, 2);
      paint_target(a[0]);
      if (a[1] != 0 && a[1] != 1 && a[1] != 2)
        fail("SetPaintTargetPaintMode: paint mode " + number_text(a[1]) +
             " is none of pmPaint, pmHeatmap, pmResult");
      return 0;  // the viewer does not colour triangles (docs/models/sensors.md)
    }
    case HostFn::SetResultTrianglesColor: {
      require_arguments(fn, n, 2);
      const PaintTargetRef& t = paint_target(a[0]);
      const double colours = a[1];
      if (colours != static_cast<double>(t.count()))
        fail("SetResultTrianglesColor: " + number_text(colours) + " colours for the " +
             std::to_string(t.count()) + " triangles of painting target " + t.id +
             " (SimTwo: length(colors) <> length(meshTriangles))");
      require_arguments(fn, n, 2 + 3 * t.count());
      return 0;  // the viewer does not colour triangles (docs/models/sensors.md)
    }
    case HostFn::GetPaintTargetExtents: {
      const PaintTargetRef& t = paint_target(a[0]);
      const Pose& body = ctx.body_pose(t.body);
      Vec3 lo = body * t.vertices.front(), hi = lo;
      for (const Vec3& v : t.vertices) {
        const Vec3 w = body * v;
        lo = {std::min(lo.x, w.x), std::min(lo.y, w.y), std::min(lo.z, w.z)};
        hi = {std::max(hi.x, w.x), std::max(hi.y, w.y), std::max(hi.z, w.z)};
      }
      numbers_.assign({lo.x, lo.y, lo.z, hi.x, hi.y, hi.z});
      return 0;
    }
    case HostFn::GetPaintTargetTriangles: {
      const PaintTargetRef& t = paint_target(a[0]);
      numbers_.clear();
      numbers_.push_back(t.count());
      for (int i = 0; i < t.count(); ++i) {
        const Vec3* v = &t.vertices[static_cast<std::size_t>(3 * i)];
        const Vec3 centre = (v[0] + v[1] + v[2]) * (1.0 / 3);
        const Vec3 n2 = cross(v[1] - v[0], v[2] - v[0]);
        const double twice = norm(n2);
        const Vec3 normal = twice > 0 ? n2 * (1 / twice) : Vec3{};
        for (const Vec3& p : {v[0], v[1], v[2], centre, normal})
          numbers_.insert(numbers_.end(), {p.x, p.y, p.z});
        numbers_.push_back(twice / 2);
        const int first = t.neighbors_of[static_cast<std::size_t>(i)];
        const int last = t.neighbors_of[static_cast<std::size_t>(i) + 1];
        numbers_.push_back(last - first);
        for (int k = first; k < last; ++k)
          numbers_.push_back(t.neighbors[static_cast<std::size_t>(k)]);
      }
      return 0;
    }
    default:
      break;
  }
  // The statistics of one target's paint.
  const PaintTargetRef& t = paint_target(a[0]);
  const std::size_t k = static_cast<std::size_t>(&t - paint_targets_.data());
  const double* paint = paint_of(k);
  const int count = t.count();
  double sum = 0, pos_sum = 0, min = kSimTwoMinStart, pos_min = kSimTwoMinStart, max = 0;
  int painted = 0;
  for (int i = 0; i < count; ++i) {
    const double v = paint[i];
    sum += v;
    min = std::min(min, v);
    max = std::max(max, v);
    if (v > 0) {
      ++painted;
      pos_sum += v;
      pos_min = std::min(pos_min, v);
    }
  }
  const double avg = sum / count;
  const double pos_avg = painted > 0 ? pos_sum / painted : 0;
  auto spread = [&](double about, bool painted_only) {
    double s = 0;
    int m = 0;
    for (int i = 0; i < count; ++i) {
      if (painted_only && !(paint[i] > 0)) continue;
      s += (paint[i] - about) * (paint[i] - about);
      ++m;
    }
    return m > 0 ? std::sqrt(s / m) : 0.0;
  };
  switch (fn) {
    case HostFn::CalculateAvgSprayThickness:
      return avg;
    case HostFn::CalculateSDSprayThickness:
      return spread(avg, false);
    case HostFn::CalculatePosAvgSprayThickness:
      return pos_avg;
    case HostFn::CalculatePosSDSprayThickness:
      return spread(pos_avg, true);
    case HostFn::CalculatePosMinSprayThickness:
      return pos_min;
    case HostFn::CalculateMinSprayThickness:
      return min;
    case HostFn::CalculateMaxSprayThickness:
      return max;
    case HostFn::CalculateSprayCoverage:
      return static_cast<double>(painted) / count;
    case HostFn::CalculateSprayThicknessHistogram: {
      require_arguments(fn, n, 2);
      if (!(a[1] >= 1) || a[1] > kMaxNumbers)
        fail("CalculateSprayThicknessHistogram: numberOfBins must be from 1 to " +
             std::to_string(kMaxNumbers) + ", got " + number_text(a[1]));
      const int bins = static_cast<int>(a[1]);
      // Equal bins from the least to the greatest thickness; each triangle in the first bin
      // whose upper limit it does not exceed (the last one's limit is the greatest).
      double lo = std::numeric_limits<double>::infinity();
      for (int i = 0; i < count; ++i)
        lo = std::min(lo, paint[i]);
      const double hi = max > lo ? max : lo;
      const double width = (hi - lo) / bins;
      numbers_.assign(static_cast<std::size_t>(1 + 2 * bins), 0.0);
      numbers_[0] = bins;
      for (int b = 0; b < bins; ++b)
        numbers_[static_cast<std::size_t>(1 + b)] = b == bins - 1 ? hi : lo + (b + 1) * width;
      for (int i = 0; i < count; ++i) {
        int b = width > 0 ? static_cast<int>(std::ceil((paint[i] - lo) / width)) - 1 : 0;
        b = std::clamp(b, 0, bins - 1);
        while (b > 0 && paint[i] <= numbers_[static_cast<std::size_t>(b)])
          --b;  // the division rounded up past the limit it lies on
        while (b < bins - 1 && paint[i] > numbers_[static_cast<std::size_t>(1 + b)])
          ++b;
        numbers_[static_cast<std::size_t>(1 + bins + b)] += 1;
      }
      return 0;
    }
    default:
      break;
  }
  fail("invalid host call");
}

}  // namespace s2sim::pascal
