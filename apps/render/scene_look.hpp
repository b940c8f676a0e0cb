#pragma once
/// \file
/// Applies a scene folder's floor and sky settings (floor_look.hpp) to the renderer: floor
/// colour, grid, texture, shadows and sky, as the SimTwo project's author set them.

#include "renderer.hpp"

#include <filesystem>
#include <string>
#include <vector>

namespace s2sim::render {

/// Reads the folder's settings and sets `settings` from them (what the folder does not set
/// keeps the viewer's default; shadows stay off when `shadows_allowed` is false, i.e.
/// --no-shadows). A texture that cannot be read is a warning naming where it was named, the
/// file and the reason, and the floor keeps its colour. `notes` gets one line for the log
/// saying what was applied, when anything was.
void apply_scene_look(const std::filesystem::path& folder, bool shadows_allowed, Renderer& renderer,
                      RenderSettings& settings, std::vector<std::string>& warnings,
                      std::vector<std::string>& notes);

}  // namespace s2sim::render
