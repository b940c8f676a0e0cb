#include "image_texture.hpp"

#include "gl.hpp"

#include <utility>

namespace s2sim::viewer {

ImageTexture::~ImageTexture() {
  if (id_ != 0) glDeleteTextures(1, &id_);
}

ImageTexture& ImageTexture::operator=(ImageTexture&& o) noexcept {
  if (this != &o) {
    if (id_ != 0) glDeleteTextures(1, &id_);
    id_ = std::exchange(o.id_, 0u);
    width_px_ = o.width_px_;
    height_px_ = o.height_px_;
  }
  return *this;
}

void ImageTexture::upload(const std::uint8_t* rgb, int width_px, int height_px) {
  GLint bound = 0;
  glGetIntegerv(GL_TEXTURE_BINDING_2D, &bound);
  if (id_ == 0) glGenTextures(1, &id_);
  glBindTexture(GL_TEXTURE_2D, id_);
  glPixelStorei(GL_UNPACK_ALIGNMENT, 1);
  glPixelStorei(GL_UNPACK_ROW_LENGTH, 0);
  if (width_px != width_px_ || height_px != height_px_) {
    glTexParameteri(GL_TEXTURE_2D, GL_TEXTURE_MIN_FILTER, GL_NEAREST);
    glTexParameteri(GL_TEXTURE_2D, GL_TEXTURE_MAG_FILTER, GL_NEAREST);
    glTexParameteri(GL_TEXTURE_2D, GL_TEXTURE_WRAP_S, GL_CLAMP_TO_EDGE);
    glTexParameteri(GL_TEXTURE_2D, GL_TEXTURE_WRAP_T, GL_CLAMP_TO_EDGE);
    glTexImage2D(GL_TEXTURE_2D, 0, GL_RGB8, width_px, height_px, 0, GL_RGB, GL_UNSIGNED_BYTE, rgb);
    width_px_ = width_px;
    height_px_ = height_px;
  } else {
    glTexSubImage2D(GL_TEXTURE_2D, 0, 0, 0, width_px, height_px, GL_RGB, GL_UNSIGNED_BYTE, rgb);
  }
  glPixelStorei(GL_UNPACK_ALIGNMENT, 4);
  glBindTexture(GL_TEXTURE_2D, static_cast<GLuint>(bound));
}

}  // namespace s2sim::viewer
