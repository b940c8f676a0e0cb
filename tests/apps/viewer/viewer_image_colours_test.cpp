// The Cameras window's conversion of images to colours (image_colours.hpp), without a window.
#include <image_colours.hpp>

#include <gtest/gtest.h>

#include <cmath>
#include <cstring>
#include <limits>
#include <set>
#include <vector>

namespace s2sim::viewer {
namespace {

/// An image over `bytes`, rows padded to `stride` bytes.
Image image_over(std::vector<std::uint8_t>& bytes, int w, int h, int stride, PixelFormat f) {
  bytes.assign(static_cast<std::size_t>(stride) * h, 0xEE);
  Image image;
  image.width_px = w;
  image.height_px = h;
  image.stride_bytes = stride;
  image.format = f;
  image.data = bytes.data();
  return image;
}

TEST(ImageColours, ColourRowsArePackedWithoutTheirPadding) {
  std::vector<std::uint8_t> bytes;
  const Image image = image_over(bytes, 2, 2, 8, PixelFormat::rgb8);
  for (int y = 0; y < 2; ++y)
    for (int i = 0; i < 6; ++i)
      image.row(y)[i] = static_cast<std::uint8_t>(10 * y + i);
  ShownImage shown;
  to_rgb(image, shown);
  ASSERT_EQ(shown.rgb.size(), 12u);
  EXPECT_EQ(shown.rgb[5], 5);
  EXPECT_EQ(shown.rgb[6], 10);  // the second row, its padding left out
  EXPECT_EQ(shown.rgb[11], 15);
}

TEST(ImageColours, DistancesRunFromWarmNearToBlueFarAndNoHitIsBlack) {
  std::vector<std::uint8_t> bytes;
  const Image image = image_over(bytes, 4, 1, 16, PixelFormat::float32);
  const float d[4] = {0.5f, 2, 8, std::numeric_limits<float>::infinity()};
  std::memcpy(image.row(0), d, sizeof d);
  ShownImage shown;
  to_rgb(image, shown);
  EXPECT_TRUE(shown.any_hit);
  EXPECT_FLOAT_EQ(shown.near_m, 0.5f);
  EXPECT_FLOAT_EQ(shown.far_m, 8);
  const std::uint8_t* near = &shown.rgb[0];
  const std::uint8_t* far = &shown.rgb[6];
  EXPECT_GT(near[0], near[2] + 100);  // red
  EXPECT_GT(far[2], far[0] + 100);    // blue
  for (int k = 9; k < 12; ++k)
    EXPECT_EQ(shown.rgb[k], 0);
  // No distance looks black: both ends of the scale are bright enough.
  for (float t : {0.0f, 0.5f, 1.0f}) {
    const auto c = distance_colour(t);
    EXPECT_GT(c[0] + c[1] + c[2], 150) << t;
  }
  // The scale is logarithmic: 2 m lies halfway between 0.5 m and 8 m.
  EXPECT_NEAR(distance_fraction(2, 0.5f, 8), 0.5f, 1e-6);
  EXPECT_NEAR(distance_at_fraction(0.5f, 0.5f, 8), 2, 1e-5);
}

TEST(ImageColours, NothingHitGivesABlackImageAndNoLegend) {
  std::vector<std::uint8_t> bytes;
  const Image image = image_over(bytes, 2, 1, 8, PixelFormat::float32);
  const float d[2] = {std::numeric_limits<float>::infinity(), std::nanf("")};
  std::memcpy(image.row(0), d, sizeof d);
  ShownImage shown;
  to_rgb(image, shown);
  EXPECT_FALSE(shown.any_hit);
  for (std::uint8_t v : shown.rgb)
    EXPECT_EQ(v, 0);
}

TEST(ImageColours, EachBodyIdHasItsOwnColourTheWorldGreyTheSkyBlack) {
  std::set<std::array<std::uint8_t, 3>> colours;
  for (std::uint16_t id = 1; id <= 40; ++id)
    colours.insert(id_colour(id));
  EXPECT_EQ(colours.size(), 40u);
  const auto world = id_colour(0);
  EXPECT_EQ(world[0], world[1]);
  EXPECT_EQ(world[1], world[2]);
  EXPECT_GT(world[0], 50);
  EXPECT_EQ(id_colour(kNoBodyId), (std::array<std::uint8_t, 3>{0, 0, 0}));
  std::vector<std::uint8_t> bytes;
  const Image image = image_over(bytes, 2, 1, 4, PixelFormat::uint16);
  const std::uint16_t ids[2] = {7, kNoBodyId};
  std::memcpy(image.row(0), ids, sizeof ids);
  ShownImage shown;
  to_rgb(image, shown);
  EXPECT_EQ(id_at(image, 0, 0), 7);
  EXPECT_EQ(shown.rgb[0], id_colour(7)[0]);
  EXPECT_EQ(shown.rgb[3] + shown.rgb[4] + shown.rgb[5], 0);
}

}  // namespace
}  // namespace s2sim::viewer
