#pragma once
/// \file
/// How a scene's floor and sky look, from the scene folder's SimTwo settings: `params.cfg`
/// (`Floor.Diffuse.Color r g b`, 0..1, and S2Sim's `Floor.Texture FILE [TILE_M]`), the check
/// boxes of config_Params.ini (else SimTwo.ini: `CBGrid_Checked`, `CBShadows_Checked`,
/// `CBSkyDome_Checked`) and the project's ground image (`ground.jpg`, `.png` or `.bmp`).
/// Window-free: the renderer loads the texture it names.

#include <array>
#include <filesystem>
#include <optional>
#include <string>
#include <vector>

namespace s2sim::render {

struct FloorLook {
  std::optional<std::array<float, 3>> color;  ///< Floor.Diffuse.Color, 0..1
  std::optional<bool> grid, shadows, sky;     ///< the project's check boxes, when it has them
  std::filesystem::path texture_file;         ///< empty = none
  float texture_tile_m = 1;                   ///< one copy of the image covers this square
  /// Where the texture was named, for warnings ("params.cfg:6", or the folder's ground image).
  std::string texture_source;
  std::vector<std::string> sources;  ///< files read, for the log
};

/// Reads the folder's settings. Malformed rows are reported in `warnings` with file, line and
/// value and otherwise ignored; a folder without settings gives an empty look (the defaults).
FloorLook read_floor_look(const std::filesystem::path& folder, std::vector<std::string>& warnings);

}  // namespace s2sim::render
