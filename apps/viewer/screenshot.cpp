#include "screenshot.hpp"

#include "gl.hpp"

#include <stb/stb_image_write.h>

#include <vector>

namespace s2sim::viewer {

std::string save_screenshot(const std::string& file, int width_px, int height_px) {
  std::vector<unsigned char> pixels(static_cast<std::size_t>(width_px) * height_px * 3);
  glPixelStorei(GL_PACK_ALIGNMENT, 1);
  glReadBuffer(GL_BACK);
  glReadPixels(0, 0, width_px, height_px, GL_RGB, GL_UNSIGNED_BYTE, pixels.data());
  // OpenGL's rows go bottom-up, PNG's top-down.
  stbi_flip_vertically_on_write(1);
  if (stbi_write_png(file.c_str(), width_px, height_px, 3, pixels.data(), width_px * 3) == 0)
    return "cannot write the screenshot '" + file + "'";
  return {};
}

}  // namespace s2sim::viewer
