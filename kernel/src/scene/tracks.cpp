/// \file
/// Track files (simtwo-format.md §7): floor markings as flat tagged polygons.

#include "scene/limits.hpp"
#include "scene/loading.hpp"
#include "scene/rotation.hpp"
#include "scene/xml.hpp"

#include <cmath>

namespace s2sim::scene::detail {
namespace {

using Vertices = std::vector<std::pair<double, double>>;

/// Appearance and replication shared by lines and arcs.
struct Common {
  std::string tag;
  Color color = color_from_tcolor(0x808080);
  int times = 0;
  double x_disp = 0, y_disp = 0, angle_disp_deg = 0;
  bool hflip = false, vflip = false, hvflip = false;
};

bool read_common(const Reader& r, const Element& c, Common& k) {
  if (c.name == "tag") {
    k.tag = r.text(c, "value", k.tag);
  } else if (c.name == "color") {
    k.color = r.rgb24(c, "rgb24", k.color);
    k.color.a = r.number(c, "alpha", k.color.a);
  } else if (c.name == "repeat") {
    const auto times = r.integer(c, "times", k.times);
    if (times < 0 || times > limits::kMaxTrackRepeats)
      r.fail(c, "times",
             "must be an integer from 0 to " + std::to_string(limits::kMaxTrackRepeats) + ", got " +
                 std::to_string(times));
    k.times = static_cast<int>(times);
    k.x_disp = r.number(c, "x_disp", k.x_disp);
    k.y_disp = r.number(c, "y_disp", k.y_disp);
    k.angle_disp_deg = r.number(c, "angle_disp", k.angle_disp_deg);
  } else if (c.name == "clone_hflip") {
    k.hflip = true;
  } else if (c.name == "clone_vflip") {
    k.vflip = true;
  } else if (c.name == "clone_hvflip") {
    k.hvflip = true;
  } else {
    return false;
  }
  return true;
}

/// Rectangle from its start corner, direction and size; the width extends to the left.
Vertices line_rectangle(double x, double y, double angle_deg, double length, double width) {
  const double dx = cos_deg(angle_deg), dy = sin_deg(angle_deg);  // direction
  const double nx = -dy, ny = dx;                                 // left normal
  return {{x, y},
          {x + length * dx, y + length * dy},
          {x + length * dx + width * nx, y + length * dy + width * ny},
          {x + width * nx, y + width * ny}};
}

/// Annular sector: the outer edge from start to stop every `step` (the last point clamped
/// to stop), then the inner edge back, or the centre when inner <= 0.
Vertices arc_polygon(double cx, double cy, double inner, double outer, double start_deg,
                     double stop_deg, double step_deg) {
  std::vector<double> angles;
  for (int i = 0;; ++i) {
    const double a = start_deg + i * step_deg;
    if (i > 0 && a >= stop_deg - 1e-9) break;
    angles.push_back(a);
  }
  angles.push_back(stop_deg);
  Vertices v;
  for (double a : angles)
    v.emplace_back(cx + outer * cos_deg(a), cy + outer * sin_deg(a));
  if (inner <= 0) {
    v.emplace_back(cx, cy);
  } else {
    for (auto it = angles.rbegin(); it != angles.rend(); ++it)
      v.emplace_back(cx + inner * cos_deg(*it), cy + inner * sin_deg(*it));
  }
  return v;
}

}  // namespace

void load_track_file(LoadContext& ctx, const std::filesystem::path& file,
                     const ConstantTable& globals) {
  Scene& scene = ctx.scene;
  const std::string display = ctx.display(file);
  const Element root = read_xml_file(file, display);
  if (root.name != "track")
    throw Error(ErrorKind::scene, Location{display, root.path, ""},
                "expected a <track> file, found <" + root.name + ">");
  ConstantTable scope = globals;
  const Reader r(display, scope);

  for (const Element& el : root.children) {
    auto emit = [&](const Common& k, double z, Vertices v) {
      scene.tracks.push_back(TrackPolygon{k.tag, k.color, z, std::move(v), r.at(el)});
    };
    if (el.name == "defines") {
      apply_defines(el, r, scope);
    } else if (el.name == "line") {
      Common k;
      double x = 0, y = 0, z = 0, angle = 0, width = 0.1, length = 1;
      for (const Element& c : el.children) {
        if (read_common(r, c, k)) continue;
        if (c.name == "position") {
          x = r.number(c, "x", x);
          y = r.number(c, "y", y);
          z = r.number(c, "z", z);
          angle = r.number(c, "angle", angle);
        } else if (c.name == "size") {
          width = r.number(c, "width", width);
          length = r.number(c, "length", length);
        }
      }
      for (int i = 0; i <= k.times; ++i) {
        const double xi = x + i * k.x_disp, yi = y + i * k.y_disp;
        const double ai = angle + i * k.angle_disp_deg;
        emit(k, z, line_rectangle(xi, yi, ai, length, width));
        // The clone rules are SimTwo's, mirror-exact only for axis-aligned lines.
        if (k.hflip) emit(k, z, line_rectangle(xi, -yi, -ai, length, width));
        if (k.vflip) emit(k, z, line_rectangle(-xi, yi + width, 180 - ai, length, width));
        if (k.hvflip) emit(k, z, line_rectangle(-xi, -yi, ai - 180, length, width));
      }
    } else if (el.name == "arc") {
      Common k;
      double cx = 0, cy = 0, z = 0, inner = 0, outer = 1, start = 0, stop = 180, step = 15;
      for (const Element& c : el.children) {
        if (read_common(r, c, k)) continue;
        if (c.name == "center") {
          cx = r.number(c, "x", cx);
          cy = r.number(c, "y", cy);
          z = r.number(c, "z", z);
        } else if (c.name == "radius") {
          inner = r.number(c, "inner", inner);
          outer = r.number(c, "outer", outer);
        } else if (c.name == "angle_deg") {
          start = r.number(c, "start", start);
          stop = r.number(c, "stop", stop);
          // SimTwo reads only `step`; the shipped fields write `steps`. Accept both.
          const char* attr = r.has(c, "step") ? "step" : "steps";
          step = r.number(c, attr, step);
          if (!(step > 0)) r.fail(c, attr, "must be > 0, got " + format_number(step));
          if (std::abs(stop - start) / step > static_cast<double>(limits::kMaxArcSegments))
            r.fail(c, attr,
                   "makes " + format_number(std::abs(stop - start) / step) +
                       " segments, more than the " + std::to_string(limits::kMaxArcSegments) +
                       " an arc may have");
        }
      }
      for (int i = 0; i <= k.times; ++i) {
        const double xi = cx + i * k.x_disp, yi = cy + i * k.y_disp;
        const double a0 = start + i * k.angle_disp_deg, a1 = stop + i * k.angle_disp_deg;
        emit(k, z, arc_polygon(xi, yi, inner, outer, a0, a1, step));
        if (k.hflip) emit(k, z, arc_polygon(xi, -yi, inner, outer, -a1, -a0, step));
        if (k.vflip) emit(k, z, arc_polygon(-xi, yi, inner, outer, 180 - a1, 180 - a0, step));
        if (k.hvflip) emit(k, z, arc_polygon(-xi, -yi, inner, outer, a0 - 180, a1 - 180, step));
      }
    } else if (el.name == "polygon") {
      Common k;
      Vertices v;
      double z = 0;
      for (const Element& c : el.children) {
        if (c.name == "vertice") {  // sic
          if (v.empty()) z = r.number(c, "z", z);
          v.emplace_back(r.number(c, "x", 0), r.number(c, "y", 0));
        } else {
          read_common(r, c, k);
        }
      }
      if (v.size() < 3) r.fail(el, "", "a polygon needs at least 3 <vertice> elements");
      emit(k, z, std::move(v));
    }
  }
}

}  // namespace s2sim::scene::detail
