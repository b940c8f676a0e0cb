#pragma once
/// \file
/// scenes/canvas (a board robot and a sign obstacle, each with a `<canvas>`, and the script
/// that draws on them) copied into the test process's temporary folder, and its canvas images'
/// pixels.

#include <s2sim/image.hpp>
#include <s2sim/kernel/simulation.hpp>

#include "common/temp_dir.hpp"

#include <array>
#include <cstdint>
#include <filesystem>
#include <memory>
#include <string>

namespace s2sim::test {

inline const std::string kBoardCanvas = "robots/board/solids/board/canvas";
inline const std::string kSignCanvas = "obstacles/0/canvas";

/// A copy of scenes/canvas under `name`.
inline std::filesystem::path copy_canvas_scene(const std::string& name) {
  const std::filesystem::path dir = process_temp_dir() / name;
  std::filesystem::remove_all(dir);
  std::filesystem::copy(std::filesystem::path(S2SIM_SOURCE_DIR) / "scenes" / "canvas", dir);
  return dir;
}

/// The scene loaded with its script (the plugins of the build).
inline std::unique_ptr<Simulation> load_canvas_scene(const std::string& name) {
  SimulationOptions o;
  o.plugin_path = {std::filesystem::path(S2SIM_PLUGIN_DIR)};
  o.script_mode = ScriptMode::always;
  return Simulation::load(copy_canvas_scene(name), o);
}

/// The red, green and blue bytes of an rgb8 image's pixel.
inline std::array<int, 3> rgb_at(const Image& image, int x, int y) {
  const std::uint8_t* p = image.row(y) + 3 * x;
  return {p[0], p[1], p[2]};
}

}  // namespace s2sim::test
