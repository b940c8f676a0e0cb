#pragma once
/// \file
/// An OpenGL texture of an RGB8 image for ImGui::Image, made and filled on the window's
/// thread (its context); freed with it.

#include <cstdint>

namespace s2sim::viewer {

class ImageTexture {
 public:
  ImageTexture() = default;
  ~ImageTexture();
  ImageTexture(ImageTexture&& o) noexcept : id_(o.id_) { o.id_ = 0; }
  ImageTexture& operator=(ImageTexture&& o) noexcept;
  ImageTexture(const ImageTexture&) = delete;
  ImageTexture& operator=(const ImageTexture&) = delete;

  /// Replaces the texture's pixels: `rgb` rows packed, top row first (drawn as they are:
  /// ImGui's texture coordinates start at the top), each screen pixel the nearest image pixel.
  void upload(const std::uint8_t* rgb, int width_px, int height_px);
  /// The OpenGL name, 0 before the first upload.
  unsigned id() const { return id_; }

 private:
  unsigned id_ = 0;
  int width_px_ = 0, height_px_ = 0;
};

}  // namespace s2sim::viewer
