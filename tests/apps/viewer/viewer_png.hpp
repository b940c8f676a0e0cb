#pragma once
/// \file
/// Reading the viewer's screenshots for pixel checks (stb_image, Debian's libstb-dev).

#include <stb/stb_image.h>

#include <cstddef>
#include <filesystem>
#include <vector>

namespace viewer_test {

/// An RGB image, rows from the top.
struct Image {
  int width = 0, height = 0;
  std::vector<unsigned char> rgb;
  const unsigned char* at(int x, int y) const {
    return &rgb[(static_cast<std::size_t>(y) * width + x) * 3];
  }
};

/// The PNG as RGB; empty (width 0) when it cannot be read.
inline Image read_png(const std::filesystem::path& file) {
  Image image;
  int channels = 0;
  unsigned char* data = stbi_load(file.string().c_str(), &image.width, &image.height, &channels, 3);
  if (data == nullptr) return image;
  image.rgb.assign(data, data + static_cast<std::size_t>(image.width) * image.height * 3);
  stbi_image_free(data);
  return image;
}

inline double luminance(const unsigned char* p) {
  return 0.299 * p[0] + 0.587 * p[1] + 0.114 * p[2];
}

}  // namespace viewer_test
