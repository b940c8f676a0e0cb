#include "jpeg_encoder.hpp"

#include <csetjmp>
#include <cstdio>
#include <cstring>
#include <stdexcept>
#include <string>

#include <jpeglib.h>

namespace s2sim::links {

/// The compressor, its error handler (libjpeg's default one calls exit(): this one jumps back
/// to encode() with the message kept) and a destination that is the encoder's buffer.
struct JpegEncoder::State {
  jpeg_compress_struct cinfo{};
  jpeg_error_mgr errors{};
  jpeg_destination_mgr destination{};
  std::jmp_buf failed{};
  char message[JMSG_LENGTH_MAX] = {};
  bool overflow = false;
  std::uint8_t* begin = nullptr;
  std::size_t size = 0;
};

namespace {

JpegEncoder::State& state_of(j_common_ptr cinfo) {
  return *static_cast<JpegEncoder::State*>(cinfo->client_data);
}

[[noreturn]] void on_error(j_common_ptr cinfo) {
  JpegEncoder::State& s = state_of(cinfo);
  (*cinfo->err->format_message)(cinfo, s.message);
  std::longjmp(s.failed, 1);
}
void on_message(j_common_ptr) {}  // warnings: not printed

void on_init_destination(j_compress_ptr cinfo) {
  JpegEncoder::State& s = state_of(reinterpret_cast<j_common_ptr>(cinfo));
  s.destination.next_output_byte = s.begin;
  s.destination.free_in_buffer = s.size;
  s.overflow = false;
}
// The buffer holds the largest JPEG libjpeg-turbo makes of the size (tjBufSize's bound), so
// this is not reached; if it were, the frame is refused rather than cut.
boolean on_buffer_full(j_compress_ptr cinfo) {
  JpegEncoder::State& s = state_of(reinterpret_cast<j_common_ptr>(cinfo));
  s.overflow = true;
  s.destination.next_output_byte = s.begin;
  s.destination.free_in_buffer = s.size;
  return TRUE;
}
void on_term_destination(j_compress_ptr) {}

}  // namespace

JpegEncoder::JpegEncoder(int width_px, int height_px, int quality) : s_(std::make_unique<State>()) {
  // 4:2:0 on 16 × 16 blocks; at worst 6 bytes a pixel, plus the headers (libjpeg-turbo's
  // tjBufSize for 4:4:4, which bounds the others).
  const auto padded = [](int v) { return static_cast<std::size_t>((v + 15) / 16 * 16); };
  buffer_.assign(padded(width_px) * padded(height_px) * 6 + 2048, 0);
  State& s = *s_;
  s.begin = buffer_.data();
  s.size = buffer_.size();
  s.cinfo.err = jpeg_std_error(&s.errors);
  s.errors.error_exit = on_error;
  s.errors.output_message = on_message;
  s.cinfo.client_data = &s;
  if (setjmp(s.failed) != 0) {
    const std::string why = s.message;
    jpeg_destroy_compress(&s.cinfo);
    throw std::runtime_error("libjpeg: " + why);
  }
  jpeg_create_compress(&s.cinfo);
  s.destination.init_destination = on_init_destination;
  s.destination.empty_output_buffer = on_buffer_full;
  s.destination.term_destination = on_term_destination;
  s.cinfo.dest = &s.destination;
  s.cinfo.image_width = static_cast<JDIMENSION>(width_px);
  s.cinfo.image_height = static_cast<JDIMENSION>(height_px);
  s.cinfo.input_components = 3;
  s.cinfo.in_color_space = JCS_RGB;
  jpeg_set_defaults(&s.cinfo);
  jpeg_set_quality(&s.cinfo, quality, TRUE);
}

JpegEncoder::~JpegEncoder() {
  jpeg_destroy_compress(&s_->cinfo);
}

const char* JpegEncoder::error() const {
  return s_->message;
}

std::size_t JpegEncoder::encode(const Image& image) {
  State& s = *s_;
  j_compress_ptr cinfo = &s.cinfo;
  if (setjmp(s.failed) != 0) {
    jpeg_abort_compress(cinfo);
    return 0;
  }
  s.message[0] = '\0';
  jpeg_start_compress(cinfo, TRUE);
  while (cinfo->next_scanline < cinfo->image_height) {
    JSAMPROW row = image.row(static_cast<int>(cinfo->next_scanline));
    jpeg_write_scanlines(cinfo, &row, 1);
  }
  jpeg_finish_compress(cinfo);
  if (s.overflow) {
    std::snprintf(s.message, sizeof s.message, "the JPEG is larger than its %zu-byte buffer",
                  s.size);
    return 0;
  }
  return s.size - s.destination.free_in_buffer;
}

}  // namespace s2sim::links
