#pragma once
/// \file
/// A JPEG encoder for one image size (libjpeg-turbo, through libjpeg's API): the compressor
/// and the output buffer are made once, so encoding a frame writes into memory already there.
/// libjpeg keeps its own per-frame work memory (its image pools); nothing here allocates.

#include <s2sim/image.hpp>

#include <cstddef>
#include <cstdint>
#include <memory>
#include <vector>

namespace s2sim::links {

class JpegEncoder {
 public:
  /// For rgb8 images of `width_px` × `height_px`, at `quality` (1..100, libjpeg's scale).
  JpegEncoder(int width_px, int height_px, int quality);
  JpegEncoder(const JpegEncoder&) = delete;
  JpegEncoder& operator=(const JpegEncoder&) = delete;
  ~JpegEncoder();

  /// Encodes `image` (rgb8, of the size given, top row first). Returns the JPEG's size in
  /// bytes, readable at data(), or 0 when libjpeg failed (its message: error()).
  std::size_t encode(const Image& image);
  const std::uint8_t* data() const { return buffer_.data(); }
  /// The largest JPEG the encoder can hold (never exceeded: see jpeg_encoder.cpp).
  std::size_t capacity() const { return buffer_.size(); }
  const char* error() const;

  struct State;  // libjpeg's structures (jpeg_encoder.cpp)

 private:
  std::unique_ptr<State> s_;
  std::vector<std::uint8_t> buffer_;
};

}  // namespace s2sim::links
