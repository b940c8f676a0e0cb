#pragma once
/// \file
/// Saves the current framebuffer as a PNG (stb_image_write).

#include <string>

namespace s2sim::viewer {

/// Reads the back buffer (width x height pixels) and writes it to `file`. Returns an empty
/// string or the error.
std::string save_screenshot(const std::string& file, int width_px, int height_px);

}  // namespace s2sim::viewer
