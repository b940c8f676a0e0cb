// SimTwo's canvases from a script (plugins/pascal_script/host_canvas.cpp): scenes/canvas's
// control.pas draws a rectangle, text, a line, an ellipse and a pixel on the board's canvas and
// fills the sign's; the kernel's canvas images hold them with Delphi's pixel conventions.
#include <s2sim/kernel/simulation.hpp>

#include "common/canvas_scene.hpp"

#include <gtest/gtest.h>

#include <array>
#include <cstdlib>
#include <string>
#include <vector>

namespace {

using s2sim::Image;
using s2sim::test::rgb_at;
using Rgb = std::array<int, 3>;

#define SKIP_WITHOUT_FPC \
  if (std::system("fpc -iV > /dev/null 2>&1") != 0) GTEST_SKIP() << "no fpc"

constexpr Rgb kRed{255, 0, 0}, kBlue{0, 0, 255}, kWhite{255, 255, 255}, kLime{0, 255, 0};
constexpr Rgb kYellow{255, 255, 0}, kNavy{0, 0, 128};

std::string line_starting(const s2sim::Simulation& sim, const std::string& start) {
  for (const auto& line : sim.annotations().lines)
    if (line.text.rfind(start, 0) == 0) return line.text;
  return "";
}

bool dark(const Rgb& c) {
  return c[0] + c[1] + c[2] < 300;
}

TEST(ScriptCanvas, TheRectangleTheTextAndThePixelAreInTheCanvasImage) {
  SKIP_WITHOUT_FPC;
  auto sim = s2sim::test::load_canvas_scene("script-canvas");
  const Image& board = sim->image(s2sim::test::kBoardCanvas);
  ASSERT_EQ(board.width_px, 200);
  ASSERT_EQ(board.height_px, 150);
  ASSERT_EQ(board.format, s2sim::PixelFormat::rgb8);
  EXPECT_EQ(board.frame, 0u);
  EXPECT_EQ(rgb_at(board, 50, 40), kWhite);  // white before the script draws
  sim->run_until(0.1);
  ASSERT_EQ(sim->signal("controllers/script/error"), 0);
  EXPECT_EQ(board.frame, 1u);
  // Rectangle(20, 20, 80, 60): a 1-pixel blue outline on x 20 and 79, y 20 and 59, red inside;
  // the right and bottom edges excluded.
  for (int y = 21; y <= 58; ++y)
    for (int x = 21; x <= 78; ++x)
      ASSERT_EQ(rgb_at(board, x, y), kRed) << x << ", " << y;
  for (int y = 20; y <= 59; ++y) {
    EXPECT_EQ(rgb_at(board, 20, y), kBlue) << y;
    EXPECT_EQ(rgb_at(board, 79, y), kBlue) << y;
    EXPECT_EQ(rgb_at(board, 80, y), kWhite) << y;
    EXPECT_EQ(rgb_at(board, 19, y), kWhite) << y;
  }
  for (int x = 20; x <= 79; ++x) {
    EXPECT_EQ(rgb_at(board, x, 20), kBlue) << x;
    EXPECT_EQ(rgb_at(board, x, 59), kBlue) << x;
    EXPECT_EQ(rgb_at(board, x, 60), kWhite) << x;
  }
  EXPECT_EQ(rgb_at(board, 5, 5), kLime);  // Pixels[5, 5] := clLime
  // TextOut(100, 20, 'S2Sim'): black glyphs on the yellow of the text's cell, nothing dark
  // around it. The script printed the cell's size (TextWidth, TextHeight).
  const std::string text = line_starting(*sim, "TEXT ");
  ASSERT_FALSE(text.empty());
  int width = 0, height = 0;
  ASSERT_EQ(std::sscanf(text.c_str(), "TEXT %d %d", &width, &height), 2);
  EXPECT_GT(width, 30);
  EXPECT_LT(width, 90);
  EXPECT_GT(height, 15);
  EXPECT_LT(height, 30);
  int glyphs = 0, yellow = 0, outside = 0;
  for (int y = 10; y < 20 + height + 10; ++y)
    for (int x = 90; x < 100 + width + 10; ++x) {
      const bool in_cell = x >= 100 && x < 100 + width && y >= 20 && y < 20 + height;
      const Rgb c = rgb_at(board, x, y);
      if (in_cell && dark(c)) ++glyphs;
      if (in_cell && c == kYellow) ++yellow;
      if (!in_cell && dark(c)) ++outside;
    }
  std::printf("text cell %d x %d: %d dark pixels, %d yellow, %d dark outside\n", width, height,
              glyphs, yellow, outside);
  EXPECT_GT(glyphs, 60);
  EXPECT_GT(yellow, width * height / 2);
  EXPECT_EQ(outside, 0);
  // The green line (3 pixels wide along y = 120) and the ellipse's black outline.
  EXPECT_EQ(rgb_at(board, 100, 120), (Rgb{0, 128, 0}));
  EXPECT_EQ(rgb_at(board, 100, 117), kWhite);
  EXPECT_EQ(rgb_at(board, 140, 90), kWhite);  // inside the clear-brushed ellipse
  int outline = 0;
  for (int x = 118; x < 125; ++x)
    outline += dark(rgb_at(board, x, 90)) ? 1 : 0;
  EXPECT_GE(outline, 1);
  // Pixels read back: clRed ($0000FF), clLime, white, -1 outside.
  EXPECT_EQ(line_starting(*sim, "PIXEL "), "PIXEL 255 65280 16777215 -1");
  // The sign: navy with a white ellipse.
  const Image& sign = sim->image(s2sim::test::kSignCanvas);
  ASSERT_EQ(sign.width_px, 150);
  ASSERT_EQ(sign.height_px, 100);
  EXPECT_EQ(rgb_at(sign, 3, 3), kNavy);
  EXPECT_EQ(rgb_at(sign, 75, 15), kWhite);
}

TEST(ScriptCanvas, AnUnchangedCanvasMakesNoFrameAndAResetMakesItWhiteAgain) {
  SKIP_WITHOUT_FPC;
  auto sim = s2sim::test::load_canvas_scene("script-canvas-reset");
  const Image& board = sim->image(s2sim::test::kBoardCanvas);
  sim->run_until(0.1);
  ASSERT_EQ(board.frame, 1u);
  const std::vector<std::uint8_t> drawn(board.data, board.data + board.size_bytes());
  sim->run_until(0.5);  // the script draws once: no more frames
  EXPECT_EQ(board.frame, 1u);
  sim->reset();
  EXPECT_EQ(board.frame, 0u);
  for (int y = 0; y < board.height_px; y += 7)
    for (int x = 0; x < board.width_px; x += 7)
      ASSERT_EQ(rgb_at(board, x, y), kWhite) << x << ", " << y;
  sim->run_until(0.1);  // the script runs afresh and draws the same
  EXPECT_EQ(board.frame, 1u);
  EXPECT_EQ(std::vector<std::uint8_t>(board.data, board.data + board.size_bytes()), drawn);
}

}  // namespace
