#pragma once
/// \file
/// Images written as files (s2sim-run --save-images): PNG through libpng. Colour (rgb8) is an
/// 8-bit RGB PNG; a body-id image (uint16) a 16-bit grey PNG of the ids; a depth or range
/// image (float32, metres) a 16-bit grey PNG of millimetres, 0 where nothing was hit and
/// 65535 at 65.535 m or more. Point clouds (xyz_float32) are not images a PNG holds.

#include <s2sim/image.hpp>

#include <filesystem>
#include <string>

namespace s2sim::apps {

/// Whether `format` can be written as a PNG.
bool png_holds(PixelFormat format);
/// Writes `image` to `file`; an error text (naming the file) when it cannot, else "".
std::string write_png(const std::filesystem::path& file, const Image& image);

}  // namespace s2sim::apps
