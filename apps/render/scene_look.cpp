#include "scene_look.hpp"

#include "floor_look.hpp"

namespace s2sim::render {

void apply_scene_look(const std::filesystem::path& folder, bool shadows_allowed, Renderer& renderer,
                      RenderSettings& settings, std::vector<std::string>& warnings,
                      std::vector<std::string>& notes) {
  const RenderSettings defaults;
  const FloorLook look = read_floor_look(folder, warnings);
  for (int i = 0; i < 3; ++i)
    settings.floor_color[i] = look.color ? (*look.color)[i] : defaults.floor_color[i];
  settings.grid = look.grid.value_or(defaults.grid);
  settings.sky = look.sky.value_or(defaults.sky);
  settings.shadows = shadows_allowed && look.shadows.value_or(defaults.shadows);
  settings.floor_texture = 0;
  settings.floor_texture_tile_m = look.texture_tile_m;
  if (!look.texture_file.empty()) {
    std::string error;
    settings.floor_texture = renderer.texture(look.texture_file, error);
    if (settings.floor_texture == 0)
      warnings.push_back(look.texture_source + ": the floor texture " +
                         (error.empty() ? look.texture_file.string() + ": cannot read it" : error) +
                         "; the floor keeps its colour");
  }
  if (look.sources.empty()) return;
  std::string note = "floor and sky from";
  for (std::size_t i = 0; i < look.sources.size(); ++i)
    note += (i ? ", " : " ") + look.sources[i];
  note += std::string(": grid ") + (settings.grid ? "on" : "off") + ", shadows " +
          (settings.shadows ? "on" : "off") + ", sky " + (settings.sky ? "on" : "off") +
          (settings.floor_texture ? ", texture " + look.texture_file.filename().string() : "");
  notes.push_back(note);
}

}  // namespace s2sim::render
