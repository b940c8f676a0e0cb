#pragma once
/// \file
/// How the camera window shows an image (windows/camera_window.cpp): its pixels turned into
/// RGB8 for a texture. Colour as it is; a depth or a range (float32, metres) in false colour
/// from the nearest to the farthest distance it holds (a logarithmic scale), black where nothing
/// was hit (+infinity, NaN); a body-id image (uint16) with a colour per id, grey for the world,
/// black for the sky. No OpenGL here: the conversion is tested on its own.

#include <s2sim/image.hpp>

#include <array>
#include <cstdint>
#include <vector>

namespace s2sim::viewer {

/// What the window makes of an image.
enum class ImageView { colour, distance, ids, points };

/// The view of `format`: rgb8 colour, float32 distance, uint16 ids, xyz_float32 points.
ImageView image_view(PixelFormat format);

/// An image as RGB8, top row first, rows packed (width * 3 bytes).
struct ShownImage {
  int width_px = 0, height_px = 0;
  std::vector<std::uint8_t> rgb;
  /// A distance image: the nearest and farthest finite distance (the legend's ends), and
  /// whether any pixel holds one.
  float near_m = 0, far_m = 0;
  bool any_hit = false;
};

/// Converts `image` (colour, distance or ids; not points) into `out`, reusing its buffer.
void to_rgb(const Image& image, ShownImage& out);

/// The false colour of a distance at `t` from near (0) to far (1): warm near, cool far.
std::array<std::uint8_t, 3> distance_colour(float t);
/// Where distance `d` lies from `near_m` (0) to `far_m` (1) on a logarithmic scale (a camera
/// sees the floor from a few decimetres to tens of metres: a linear scale would leave
/// everything near in one colour); distances below 1 cm count as 1 cm.
float distance_fraction(float d, float near_m, float far_m);
/// The distance at fraction `t` of that scale (the legend's labels).
float distance_at_fraction(float t, float near_m, float far_m);
/// The colour of body id `id`: distinct hues for bodies, grey for the world (0), black for
/// the sky (kNoBodyId).
std::array<std::uint8_t, 3> id_colour(std::uint16_t id);

/// The value at pixel (x, y) of a distance image (metres) or an ids image (the id).
float distance_at(const Image& image, int x, int y);
std::uint16_t id_at(const Image& image, int x, int y);

}  // namespace s2sim::viewer
