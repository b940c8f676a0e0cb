#include <s2sim/kernel/annotations.hpp>

#include "sim/simulation_impl.hpp"

#include <algorithm>
#include <cmath>
#include <string_view>

namespace s2sim {

std::vector<Annotations::Line> Annotations::lines_from(std::uint64_t sequence) const {
  std::vector<Line> out;
  for (const Line& line : lines)
    if (line.sequence >= sequence) out.push_back(line);
  return out;
}

std::string Annotations::hud_text() const {
  std::string text;
  for (const Hud& hud : huds) {
    if (hud.text.empty()) continue;
    if (!text.empty() && text.back() != '\n') text += '\n';
    text += hud.text;
  }
  return text;
}

const Annotations::BodyColor* Annotations::body_color(int body) const {
  for (const BodyColor& c : body_colors)
    if (c.body == body) return &c;
  return nullptr;
}

const Annotations::ShapeColor* Annotations::shape_color(int body, int geom) const {
  for (const ShapeColor& c : shape_colors)
    if (c.body == body && c.geom == geom) return &c;
  return nullptr;
}

const Annotations::SensorColor* Annotations::sensor_color(int sensor) const {
  for (const SensorColor& c : sensor_colors)
    if (c.sensor == sensor) return &c;
  return nullptr;
}

const Annotations::BodyMesh* Annotations::body_mesh(int body) const {
  for (const BodyMesh& m : body_meshes)
    if (m.body == body) return &m;
  return nullptr;
}

void Annotations::forget_body(int body) {
  const auto before = body_colors.size() + shape_colors.size() + body_meshes.size();
  const auto on_body = [body](const auto& entry) { return entry.body == body; };
  body_colors.erase(std::remove_if(body_colors.begin(), body_colors.end(), on_body),
                    body_colors.end());
  shape_colors.erase(std::remove_if(shape_colors.begin(), shape_colors.end(), on_body),
                     shape_colors.end());
  body_meshes.erase(std::remove_if(body_meshes.begin(), body_meshes.end(), on_body),
                    body_meshes.end());
  if (body_colors.size() + shape_colors.size() + body_meshes.size() != before) ++version;
}

void Annotations::clear() {
  body_colors.clear();
  body_meshes.clear();
  liquid_surfaces.clear();
  shape_colors.clear();
  sensor_colors.clear();
  fire = Fire{};
  lines.clear();
  next_sequence = 0;
  huds.clear();
  trails.clear();
  series.clear();
  ++version;
}

namespace {

/// The entry of `list` for (source, id), made when absent and there is room; null otherwise.
template <class T>
T* find_or_add(std::vector<T>& list, const std::string& source, int id, bool add) {
  for (T& item : list)
    if (item.id == id && item.source == source) return &item;
  if (!add || list.size() >= Annotations::kMaxTrailsOrSeries) return nullptr;
  list.push_back(T{source, id, {}});
  return &list.back();
}

/// 0..1 from a component's number; NaN becomes 0.
double unit_interval(double v) {
  return v >= 0 ? (v <= 1 ? v : 1.0) : 0.0;
}

/// Sets the colour of `list`'s entry that `same` picks, made when absent; false when unchanged.
template <class T, class Same>
bool paint(std::vector<T>& list, T entry, Same same) {
  for (T& old : list)
    if (same(old)) {
      if (std::equal(entry.rgb, entry.rgb + 3, old.rgb)) return false;
      old = entry;
      return true;
    }
  list.push_back(entry);
  return true;
}

/// `text` as kept: at most Annotations::kMaxTextBytes, cut at a character boundary (UTF-8), with
/// how much was cut.
std::string kept_text(std::string_view text) {
  if (text.size() <= Annotations::kMaxTextBytes) return std::string(text);
  std::size_t keep = Annotations::kMaxTextBytes;
  while (keep > 0 && (static_cast<unsigned char>(text[keep]) & 0xC0) == 0x80)
    --keep;  // not inside a multi-byte character
  return std::string(text.substr(0, keep)) + " [" + std::to_string(text.size() - keep) +
         " bytes cut]";
}

}  // namespace

void Simulation::Impl::annotate(const void* impl, std::int32_t component, std::int32_t what,
                                std::int32_t id, const char* text, std::size_t text_size,
                                const double* values) {
  auto& m = *const_cast<Simulation::Impl*>(static_cast<const Simulation::Impl*>(impl));
  if (component < 0 || static_cast<std::size_t>(component) >= m.components.size()) return;
  const std::string& source = m.components[static_cast<std::size_t>(component)].prefix;
  Annotations& a = m.annotations;
  const std::string_view body(text, text_size);
  switch (static_cast<detail::Annotation>(what)) {
    case detail::Annotation::log_line:
      a.lines.push_back({a.next_sequence++, m.tick * m.tick_s, source, kept_text(body)});
      if (a.lines.size() > Annotations::kMaxLines) a.lines.pop_front();
      break;
    case detail::Annotation::hud_text: {
      auto it = std::find_if(a.huds.begin(), a.huds.end(),
                             [&](const Annotations::Hud& h) { return h.source == source; });
      if (it == a.huds.end()) {
        if (body.empty()) return;
        a.huds.push_back({source, kept_text(body)});
      } else {
        if (it->text == body) return;
        it->text = kept_text(body);
      }
      break;
    }
    case detail::Annotation::trail_point:
      if (values == nullptr) return;
      if (auto* trail = find_or_add(a.trails, source, id, true)) {
        trail->points_m.push_back(Vec3{values[0], values[1], values[2]});
        if (trail->points_m.size() > Annotations::kMaxPoints) trail->points_m.pop_front();
      }
      break;
    case detail::Annotation::clear_trail:
      if (auto* trail = find_or_add(a.trails, source, id, false)) trail->points_m.clear();
      break;
    case detail::Annotation::xy_point:
      if (values == nullptr) return;
      if (auto* series = find_or_add(a.series, source, id, true)) {
        series->points.emplace_back(values[0], values[1]);
        if (series->points.size() > Annotations::kMaxPoints) series->points.pop_front();
      }
      break;
    case detail::Annotation::clear_xy:
      if (auto* series = find_or_add(a.series, source, id, false)) series->points.clear();
      break;
    case detail::Annotation::body_color: {
      if (values == nullptr || id <= 0 || id >= static_cast<std::int32_t>(m.poses.size())) return;
      Annotations::BodyColor c{id, {}};
      for (int k = 0; k < 3; ++k)  // NaN becomes 0
        c.rgb[k] = values[k] >= 0 ? (values[k] <= 1 ? values[k] : 1.0) : 0.0;
      const Annotations::BodyColor* old = a.body_color(id);
      if (old == nullptr) {
        a.body_colors.push_back(c);
      } else {
        if (std::equal(c.rgb, c.rgb + 3, old->rgb)) return;
        auto& slot = a.body_colors[static_cast<std::size_t>(old - a.body_colors.data())];
        slot = c;
      }
      break;
    }
    case detail::Annotation::shape_color: {
      if (values == nullptr || id < 0 || id >= static_cast<std::int32_t>(m.poses.size())) return;
      const double geom = values[0];
      const std::size_t geoms = id == 0
                                    ? m.scene.obstacles.size()
                                    : m.scene.bodies[static_cast<std::size_t>(id - 1)].geoms.size();
      if (!(geom >= 0 && geom < static_cast<double>(geoms))) return;
      Annotations::ShapeColor c{id, static_cast<int>(geom), {}};
      for (int k = 0; k < 3; ++k)
        c.rgb[k] = unit_interval(values[1 + k]);
      if (!paint(a.shape_colors, c, [&](const Annotations::ShapeColor& o) {
            return o.body == c.body && o.geom == c.geom;
          }))
        return;
      break;
    }
    case detail::Annotation::fire: {
      if (values == nullptr || id < 0 || id >= static_cast<std::int32_t>(m.poses.size())) return;
      for (int k = 1; k < 7; ++k)
        if (!std::isfinite(values[k])) return;
      a.fire = {
          values[0] != 0, id, {values[1], values[2], values[3]}, {values[4], values[5], values[6]}};
      break;
    }
    case detail::Annotation::body_mesh: {
      if (values == nullptr || id <= 0 || id >= static_cast<std::int32_t>(m.poses.size())) return;
      const std::size_t nul = body.find('\0');
      const std::string_view file = body.substr(0, nul);
      const std::string_view shadow =
          nul == std::string_view::npos ? std::string_view{} : body.substr(nul + 1);
      if (file.empty() || !(values[0] > 0 && std::isfinite(values[0]))) return;
      const auto absolute = [&](std::string_view name) {
        const std::filesystem::path p(name);
        return name.empty() || p.is_absolute() ? p : m.scene.folder / p;
      };
      Annotations::BodyMesh mesh{id, absolute(file), absolute(shadow), values[0], values[1] != 0};
      const auto same = [&](const Annotations::BodyMesh& o) { return o.body == id; };
      auto it = std::find_if(a.body_meshes.begin(), a.body_meshes.end(), same);
      if (it == a.body_meshes.end()) {
        a.body_meshes.push_back(std::move(mesh));
      } else {
        if (it->file == mesh.file && it->shadow_file == mesh.shadow_file &&
            it->scale == mesh.scale && it->casts_shadow == mesh.casts_shadow)
          return;
        *it = std::move(mesh);
      }
      break;
    }
    case detail::Annotation::liquid_surface: {
      if (values == nullptr || !std::isfinite(values[0])) return;
      Annotations::LiquidSurface surface{std::string(source), values[0], {}};
      for (int k = 0; k < 4; ++k)
        surface.rgba[k] = unit_interval(values[1 + k]);
      const auto same = [&](const Annotations::LiquidSurface& o) { return o.source == source; };
      auto it = std::find_if(a.liquid_surfaces.begin(), a.liquid_surfaces.end(), same);
      if (it == a.liquid_surfaces.end()) {
        if (a.liquid_surfaces.size() >= Annotations::kMaxTrailsOrSeries) return;
        a.liquid_surfaces.push_back(std::move(surface));
      } else {
        if (it->z_m == surface.z_m && std::equal(it->rgba, it->rgba + 4, surface.rgba)) return;
        *it = std::move(surface);
      }
      break;
    }
    case detail::Annotation::sensor_color: {
      if (values == nullptr) return;
      int sensor = -1;
      for (const sim::ComponentSlot& slot : m.components)
        if (slot.sensor >= 0 && slot.prefix == body) sensor = slot.sensor;
      if (sensor < 0) return;
      Annotations::SensorColor c{sensor, {}};
      for (int k = 0; k < 3; ++k)
        c.rgb[k] = unit_interval(values[k]);
      if (!paint(a.sensor_colors, c,
                 [&](const Annotations::SensorColor& o) { return o.sensor == c.sensor; }))
        return;
      break;
    }
    default:
      return;  // a kind from a newer SDK: ignored
  }
  ++a.version;
}

const Annotations& Simulation::annotations() const {
  return impl_->annotations;
}

}  // namespace s2sim
