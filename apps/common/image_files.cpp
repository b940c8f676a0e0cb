#include "image_files.hpp"

#include <png.h>

#include <cerrno>
#include <cmath>
#include <cstdio>
#include <cstring>
#include <vector>

namespace s2sim::apps {

bool png_holds(PixelFormat format) {
  return format == PixelFormat::rgb8 || format == PixelFormat::uint16 ||
         format == PixelFormat::float32;
}

namespace {

/// One row as PNG wants it: 8-bit RGB as it is, 16-bit grey big-endian.
void png_row(const Image& image, int y, std::vector<std::uint8_t>& out) {
  const std::uint8_t* row = image.row(y);
  const int w = image.width_px;
  if (image.format == PixelFormat::rgb8) {
    out.assign(row, row + 3 * w);
    return;
  }
  out.resize(2 * static_cast<std::size_t>(w));
  for (int x = 0; x < w; ++x) {
    std::uint16_t v = 0;
    if (image.format == PixelFormat::uint16) {
      std::memcpy(&v, row + 2 * x, 2);
    } else {
      float m;
      std::memcpy(&m, row + 4 * x, 4);
      const double mm = std::isfinite(m) ? std::round(1000.0 * m) : 0.0;
      v = static_cast<std::uint16_t>(mm <= 0 ? 0 : mm >= 65535 ? 65535 : mm);
    }
    out[2 * x] = static_cast<std::uint8_t>(v >> 8);
    out[2 * x + 1] = static_cast<std::uint8_t>(v & 0xFF);
  }
}

/// "cannot write '<file>': <why>" (appended piecewise: GCC 12 warns wrongly on `"..." + s`).
std::string cannot_write(const std::filesystem::path& file, const char* why) {
  std::string text = "cannot write '";
  text += file.string();
  text += "': ";
  text += why;
  return text;
}

}  // namespace

std::string write_png(const std::filesystem::path& file, const Image& image) {
  if (!png_holds(image.format)) return cannot_write(file, "a point cloud is not a PNG");
  std::FILE* f = std::fopen(file.c_str(), "wb");
  if (!f) return cannot_write(file, std::strerror(errno));
  png_structp png = png_create_write_struct(PNG_LIBPNG_VER_STRING, nullptr, nullptr, nullptr);
  png_infop info = png ? png_create_info_struct(png) : nullptr;
  if (!png || !info) {
    png_destroy_write_struct(&png, nullptr);
    std::fclose(f);
    return cannot_write(file, "libpng could not start");
  }
  std::vector<std::uint8_t> row;
  // libpng reports errors by longjmp: nothing with a destructor is made after this point.
  if (setjmp(png_jmpbuf(png))) {
    png_destroy_write_struct(&png, &info);
    std::fclose(f);
    return cannot_write(file, "libpng failed");
  }
  png_init_io(png, f);
  const bool colour = image.format == PixelFormat::rgb8;
  png_set_IHDR(png, info, static_cast<png_uint_32>(image.width_px),
               static_cast<png_uint_32>(image.height_px), colour ? 8 : 16,
               colour ? PNG_COLOR_TYPE_RGB : PNG_COLOR_TYPE_GRAY, PNG_INTERLACE_NONE,
               PNG_COMPRESSION_TYPE_DEFAULT, PNG_FILTER_TYPE_DEFAULT);
  png_set_compression_level(png, 1);  // fast: a camera writes many frames
  png_write_info(png, info);
  row.reserve(static_cast<std::size_t>(image.width_px) * 3);
  for (int y = 0; y < image.height_px; ++y) {
    png_row(image, y, row);
    png_write_row(png, row.data());
  }
  png_write_end(png, nullptr);
  png_destroy_write_struct(&png, &info);
  const bool failed = std::ferror(f) != 0;
  if (std::fclose(f) != 0 || failed) return cannot_write(file, std::strerror(errno));
  return "";
}

}  // namespace s2sim::apps
