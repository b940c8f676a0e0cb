#include "image_colours.hpp"

#include <algorithm>
#include <cmath>
#include <cstring>
#include <limits>

namespace s2sim::viewer {
namespace {

std::uint8_t byte(float v) {
  return static_cast<std::uint8_t>(std::lround(std::clamp(v, 0.0f, 1.0f) * 255));
}

}  // namespace

ImageView image_view(PixelFormat format) {
  switch (format) {
    case PixelFormat::rgb8:
      return ImageView::colour;
    case PixelFormat::float32:
      return ImageView::distance;
    case PixelFormat::uint16:
      return ImageView::ids;
    case PixelFormat::xyz_float32:
      break;
  }
  return ImageView::points;
}

float distance_at(const Image& image, int x, int y) {
  float v;
  std::memcpy(&v, image.row(y) + static_cast<std::ptrdiff_t>(x) * 4, sizeof v);
  return v;
}

std::uint16_t id_at(const Image& image, int x, int y) {
  std::uint16_t v;
  std::memcpy(&v, image.row(y) + static_cast<std::ptrdiff_t>(x) * 2, sizeof v);
  return v;
}

std::array<std::uint8_t, 3> distance_colour(float t) {
  // Google's Turbo colour map (a polynomial fit) from red (near) to blue (far), its dark ends
  // left out so that no distance looks like the black of no hit.
  const float s = 0.9f - 0.8f * std::clamp(t, 0.0f, 1.0f);
  const float r =
      0.13572138f +
      s * (4.61539260f +
           s * (-42.66032258f + s * (132.13108234f + s * (-152.94239396f + s * 59.28637943f))));
  const float g =
      0.09140261f +
      s * (2.19418839f +
           s * (4.84296658f + s * (-14.18503333f + s * (4.27729857f + s * 2.82956604f))));
  const float b =
      0.10667330f +
      s * (12.64194608f +
           s * (-60.58204836f + s * (110.36276771f + s * (-89.90310912f + s * 27.34824973f))));
  return {byte(r), byte(g), byte(b)};
}

float distance_fraction(float d, float near_m, float far_m) {
  constexpr float kLeast_m = 0.01f;
  const float lo = std::max(near_m, kLeast_m), hi = std::max(far_m, lo * 1.0001f);
  return std::clamp(std::log(std::max(d, kLeast_m) / lo) / std::log(hi / lo), 0.0f, 1.0f);
}

float distance_at_fraction(float t, float near_m, float far_m) {
  constexpr float kLeast_m = 0.01f;
  const float lo = std::max(near_m, kLeast_m), hi = std::max(far_m, lo * 1.0001f);
  return lo * std::pow(hi / lo, t);
}

std::array<std::uint8_t, 3> id_colour(std::uint16_t id) {
  if (id == kNoBodyId) return {0, 0, 0};
  if (id == 0) return {110, 110, 110};
  // Hues a golden angle apart, so neighbouring ids differ; saturation and value alternate.
  const float h = std::fmod(static_cast<float>(id) * 0.6180340f, 1.0f) * 6;
  const float s = id % 2 ? 0.75f : 0.55f, v = id % 3 ? 0.95f : 0.75f;
  const int sector = static_cast<int>(h) % 6;
  const float f = h - std::floor(h);
  const float p = v * (1 - s), q = v * (1 - s * f), u = v * (1 - s * (1 - f));
  const float rgb[6][3] = {{v, u, p}, {q, v, p}, {p, v, u}, {p, q, v}, {u, p, v}, {v, p, q}};
  return {byte(rgb[sector][0]), byte(rgb[sector][1]), byte(rgb[sector][2])};
}

void to_rgb(const Image& image, ShownImage& out) {
  const int w = image.width_px, h = image.height_px;
  out.width_px = w;
  out.height_px = h;
  out.rgb.resize(static_cast<std::size_t>(w) * h * 3);
  out.any_hit = false;
  std::uint8_t* to = out.rgb.data();
  switch (image_view(image.format)) {
    case ImageView::colour:
      for (int y = 0; y < h; ++y, to += static_cast<std::ptrdiff_t>(w) * 3)
        std::memcpy(to, image.row(y), static_cast<std::size_t>(w) * 3);
      return;
    case ImageView::ids:
      for (int y = 0; y < h; ++y)
        for (int x = 0; x < w; ++x, to += 3) {
          const auto c = id_colour(id_at(image, x, y));
          std::memcpy(to, c.data(), 3);
        }
      return;
    case ImageView::distance: {
      float lo = std::numeric_limits<float>::infinity(), hi = -lo;
      for (int y = 0; y < h; ++y)
        for (int x = 0; x < w; ++x) {
          const float d = distance_at(image, x, y);
          if (std::isfinite(d)) lo = std::min(lo, d), hi = std::max(hi, d);
        }
      out.any_hit = lo <= hi;
      out.near_m = out.any_hit ? lo : 0;
      out.far_m = out.any_hit ? hi : 0;
      for (int y = 0; y < h; ++y)
        for (int x = 0; x < w; ++x, to += 3) {
          const float d = distance_at(image, x, y);
          if (!std::isfinite(d)) {
            to[0] = to[1] = to[2] = 0;
            continue;
          }
          const auto c = distance_colour(distance_fraction(d, lo, hi));
          std::memcpy(to, c.data(), 3);
        }
      return;
    }
    case ImageView::points:
      std::fill(out.rgb.begin(), out.rgb.end(), std::uint8_t{0});
      return;
  }
}

}  // namespace s2sim::viewer
