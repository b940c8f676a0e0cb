// A canvas seen by the headless renderer (apps/render/scene_drawables.cpp): scenes/canvas's
// script draws a red rectangle on the board's canvas; a camera straight above the board, its
// view just covering the board's top, sees it where the canvas has it (pixel x along the
// board's +X, y along -Y), and sees the canvas white again once a reset cleared it (the
// texture follows the image's frame counter).
#include "headless_camera_renderer.hpp"

#include <s2sim/image.hpp>
#include <s2sim/kernel/simulation.hpp>

#include "common/canvas_scene.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <cstdlib>
#include <vector>

namespace s2sim {
namespace {

class NoDisplay : public ::testing::Environment {
 public:
  void SetUp() override {
    ::unsetenv("DISPLAY");
    ::unsetenv("WAYLAND_DISPLAY");
  }
};
[[maybe_unused]] ::testing::Environment* const kNoDisplay =
    ::testing::AddGlobalTestEnvironment(new NoDisplay);

constexpr int kW = 200, kH = 150;  // the canvas's size: one image pixel per canvas pixel

/// An rgb8 image of the shot's size over `pixels`.
Image rgb_image(std::vector<std::uint8_t>& pixels) {
  pixels.assign(static_cast<std::size_t>(kW * kH * 3), 0);
  Image image;
  image.width_px = kW;
  image.height_px = kH;
  image.stride_bytes = 3 * kW;
  image.format = PixelFormat::rgb8;
  image.data = pixels.data();
  return image;
}

/// The camera 0.5 m above the board's top, looking down with +Y up: its +X (the image's left)
/// is world -X, so the image shows the canvas unmirrored. Its view covers the board's 0.3 m.
CameraShot above(const Simulation& sim, int board) {
  const Pose& b = sim.body_pose(board);
  CameraShot shot;
  shot.pose.position = b.position + Vec3{0, 0, 0.01 + 0.5};
  shot.pose.rotation = Mat3{{{-1, 0, 0}, {0, 1, 0}, {0, 0, -1}}};
  shot.vertical_fov_rad = 2 * std::atan(0.15 / 0.5);
  shot.near_m = 0.05;
  shot.far_m = 10;
  shot.width_px = kW;
  shot.height_px = kH;
  return shot;
}

bool reddish(const std::array<int, 3>& c) {
  return c[0] > 2 * c[1] + 40 && c[0] > 2 * c[2] + 40;
}
bool whitish(const std::array<int, 3>& c) {
  return c[0] > 150 && std::abs(c[0] - c[1]) < 20 && std::abs(c[0] - c[2]) < 20;
}

TEST(CanvasTexture, TheCameraSeesTheScriptsRectangleOnTheBoardsTopFace) {
  if (std::system("fpc -iV > /dev/null 2>&1") != 0) GTEST_SKIP() << "no fpc";
  auto sim = test::load_canvas_scene("canvas-texture");
  int board = -1;
  for (int b = 0; b < sim->body_count(); ++b)
    if (sim->body_path(b) == "robots/board/solids/board") board = b;
  ASSERT_GT(board, 0);
  sim->run_until(0.1);
  ASSERT_EQ(sim->image(test::kBoardCanvas).frame, 1u);
  auto renderer = render::headless_camera_renderer_factory()(*sim);
  std::vector<std::uint8_t> pixels;
  Image rgb = rgb_image(pixels);
  auto shoot = [&] {
    renderer->render(above(*sim, board), sim->body_poses().data(), sim->body_count(), &rgb, nullptr,
                     nullptr);
  };
  shoot();
  // The rectangle's inside, canvas x 21..78, y 21..58 (a pixel's margin for the projection);
  // the canvas's white elsewhere; the board's own blue nowhere on its top.
  int red = 0;
  for (int y = 23; y <= 56; ++y)
    for (int x = 23; x <= 76; ++x)
      red += reddish(test::rgb_at(rgb, x, y)) ? 1 : 0;
  std::printf("rectangle: %d of %d pixels red; (50, 40) = %d %d %d; (150, 135) = %d %d %d\n", red,
              34 * 54, test::rgb_at(rgb, 50, 40)[0], test::rgb_at(rgb, 50, 40)[1],
              test::rgb_at(rgb, 50, 40)[2], test::rgb_at(rgb, 150, 135)[0],
              test::rgb_at(rgb, 150, 135)[1], test::rgb_at(rgb, 150, 135)[2]);
  EXPECT_EQ(red, 34 * 54);
  EXPECT_TRUE(whitish(test::rgb_at(rgb, 150, 135)));
  EXPECT_TRUE(whitish(test::rgb_at(rgb, 100, 80)));
  EXPECT_FALSE(reddish(test::rgb_at(rgb, 120, 40)));  // right of the rectangle (+X)
  EXPECT_FALSE(reddish(test::rgb_at(rgb, 50, 100)));  // below it (-Y)
  // A reset leaves the canvas white (frame 0): the next shot uploads it again.
  sim->reset();
  shoot();
  EXPECT_TRUE(whitish(test::rgb_at(rgb, 50, 40)));
  sim->run_until(0.1);
  shoot();
  EXPECT_TRUE(reddish(test::rgb_at(rgb, 50, 40)));
}

}  // namespace
}  // namespace s2sim
