// The world view's look, on screenshots of the real s2sim-view under Xvfb: smooth
// edges with multisampling, a gradient sky, shadows that fall on bodies (shadow map), and a
// SimTwo project's floor settings and texture. Each check compares two frames that differ in
// one setting only, so it fails when that setting does nothing.

#include "viewer_harness.hpp"

#include <algorithm>
#include <cmath>

namespace s2sim::viewer_test {
namespace {

/// A scene of static boxes only: a red slab on the floor and, when `with_blue_above`, a small
/// blue box floating above it, offset so that its shadow falls on the slab's top. `settings`
/// is written as the folder's SimTwo.ini (the project's check boxes), `params` as params.cfg.
fs::path boxes_scene(const fs::path& dir, bool with_blue_above, const std::string& settings,
                     const std::string& params = "") {
  fs::create_directories(dir);
  std::ofstream(dir / "scene.xml") << "<?xml version='1.0' ?>\n<scene>\n"
                                      "  <obstacles file='obstacles.xml'/>\n</scene>\n";
  std::ofstream obstacles(dir / "obstacles.xml");
  obstacles << "<?xml version='1.0' ?>\n<obstacles>\n"
               "  <cuboid><imovable/><size x='1' y='1' z='0.4'/><pos x='0' y='0' z='0.2'/>"
               "<color_rgb r='255' g='0' b='0'/></cuboid>\n";
  if (with_blue_above)
    obstacles << "  <cuboid><imovable/><size x='0.25' y='0.25' z='0.05'/>"
                 "<pos x='0.3' y='0.2' z='1.2'/><color_rgb r='0' g='0' b='255'/></cuboid>\n";
  obstacles << "</obstacles>\n";
  if (!settings.empty()) std::ofstream(dir / "SimTwo.ini") << "[Config]\n" << settings;
  if (!params.empty()) std::ofstream(dir / "params.cfg") << params;
  return dir;
}

bool strongly_red(const unsigned char* p) {
  return p[0] > 40 && p[1] * 3 < p[0] && p[2] * 3 < p[0];
}

/// Pixels that lie between their left and right neighbours on a sharp colour step (each
/// channel within the step's range, far from both ends): what multisampling leaves on edges.
int intermediate_edge_pixels(const Image& image) {
  int count = 0;
  for (int y = 0; y < image.height; ++y)
    for (int x = 1; x + 1 < image.width; ++x) {
      const unsigned char *a = image.at(x - 1, y), *p = image.at(x, y), *b = image.at(x + 1, y);
      int step = 0, to_a = 0, to_b = 0;
      bool between = true;
      for (int c = 0; c < 3; ++c) {
        step += std::abs(a[c] - b[c]);
        to_a += std::abs(p[c] - a[c]);
        to_b += std::abs(p[c] - b[c]);
        between = between && p[c] >= std::min(a[c], b[c]) - 2 && p[c] <= std::max(a[c], b[c]) + 2;
      }
      if (step > 120 && between && to_a > step / 6 && to_b > step / 6) ++count;
    }
  return count;
}

using ViewerLook = ViewerRun;

TEST_F(ViewerLook, MultisamplingLeavesIntermediateColoursOnEdgesAndCanBeTurnedOff) {
  // No grid, sky, shadows or overlay (ImGui's lines are anti-aliased either way): the only
  // edges are the slab's silhouette against a plain floor and between its faces.
  const fs::path scene = boxes_scene(dir_ / "scene", false,
                                     "CBGrid_Checked=0\nCBShadows_Checked=0\nCBSkyDome_Checked=0\n",
                                     "Floor.Diffuse.Color\t0.1\t0.1\t0.1\n");
  const std::vector<std::string> camera = {
      "--do", "camera 20 35 3", "--do", "overlay axes off", "--do", "overlay scale-bar off"};
  auto with = [&](std::vector<std::string> extra) {
    extra.insert(extra.end(), camera.begin(), camera.end());
    return extra;
  };
  const Image plain = screenshot(scene.string(), "plain", with({"--msaa", "0"}));
  const Image smooth = screenshot(scene.string(), "smooth", with({}));  // the default: 4x
  ASSERT_EQ(plain.width, 1280);
  ASSERT_EQ(smooth.width, 1280);
  const int plain_count = intermediate_edge_pixels(plain);
  const int smooth_count = intermediate_edge_pixels(smooth);
  EXPECT_GT(smooth_count, 150) << "no blended pixels on the slab's edges with --msaa 4";
  EXPECT_GT(smooth_count, 5 * std::max(plain_count, 1))
      << "plain " << plain_count << ", multisampled " << smooth_count;
}

TEST_F(ViewerLook, SkyIsAGradientUnlessTheProjectTurnsItOff) {
  // Looking almost level: the upper half of the view is sky.
  const std::vector<std::string> level = {"--do", "camera 0 3 3"};
  const fs::path with_sky = boxes_scene(dir_ / "sky", false, "");
  const fs::path without_sky = boxes_scene(dir_ / "flat", false, "CBSkyDome_Checked=0\n");
  const Image sky = screenshot(with_sky.string(), "sky", level);
  const Image flat = screenshot(without_sky.string(), "flat", level);
  ASSERT_EQ(sky.width, 1280);
  ASSERT_EQ(flat.width, 1280);
  auto row_mean = [](const Image& image, int y, int c) {
    double sum = 0;
    for (int x = 0; x < image.width; ++x)
      sum += image.at(x, y)[c];
    return sum / image.width;
  };
  // Deeper blue overhead than near the horizon (a few rows above the view's centre).
  const int top = 2, near_horizon = sky.height / 2 - 40;
  EXPECT_GT(row_mean(sky, near_horizon, 0) - row_mean(sky, top, 0), 25)
      << "top row red " << row_mean(sky, top, 0) << ", near the horizon "
      << row_mean(sky, near_horizon, 0);
  // A project without SimTwo's sky dome keeps the flat clear colour.
  for (int c = 0; c < 3; ++c)
    EXPECT_NEAR(row_mean(flat, top, c), row_mean(flat, near_horizon, c), 2) << "channel " << c;
}

TEST_F(ViewerLook, ShadowsFallOnBodiesAsWellAsOnTheFloor) {
  // Seen from straight above, the red slab's top is evenly lit without shadows; with them,
  // the blue box's shadow darkens part of it.
  const fs::path scene = boxes_scene(dir_ / "scene", true, "");
  const std::vector<std::string> above = {"--do", "camera 0 89 3"};
  std::vector<std::string> no_shadows = above;
  no_shadows.push_back("--no-shadows");
  const Image shadowed = screenshot(scene.string(), "shadowed", above);
  const Image unshadowed = screenshot(scene.string(), "unshadowed", no_shadows);
  ASSERT_EQ(shadowed.width, 1280);
  ASSERT_EQ(unshadowed.width, 1280);
  auto dark_red_pixels = [](const Image& image, int& red_pixels) {
    std::vector<int> reds;
    for (int y = 0; y < image.height; ++y)
      for (int x = 0; x < image.width; ++x)
        if (strongly_red(image.at(x, y))) reds.push_back(image.at(x, y)[0]);
    red_pixels = static_cast<int>(reds.size());
    if (reds.empty()) return 0;
    std::sort(reds.begin(), reds.end());
    const int bright = reds[reds.size() * 9 / 10];
    return static_cast<int>(
        std::count_if(reds.begin(), reds.end(), [&](int r) { return r < 0.6 * bright; }));
  };
  int red_shadowed = 0, red_unshadowed = 0;
  const int dark_shadowed = dark_red_pixels(shadowed, red_shadowed);
  const int dark_unshadowed = dark_red_pixels(unshadowed, red_unshadowed);
  ASSERT_GT(red_unshadowed, 20000) << "the slab is not in view";
  EXPECT_GT(dark_shadowed, 1000) << "no shadow on the slab (" << red_shadowed << " red pixels)";
  EXPECT_LT(dark_unshadowed, 100) << "the slab is unevenly lit without shadows";
}

/// The median brightness step between horizontally adjacent pixels of the bottom rows: near 0
/// on a plain floor, several levels on a textured one.
double floor_detail(const Image& image) {
  std::vector<double> steps;
  for (int y = image.height - 60; y < image.height; y += 2)
    for (int x = 0; x + 1 < image.width; x += 2)
      steps.push_back(std::abs(luminance(image.at(x, y)) - luminance(image.at(x + 1, y))));
  std::nth_element(steps.begin(), steps.begin() + steps.size() / 2, steps.end());
  return steps[steps.size() / 2];
}

int green_floor_pixels(const Image& image) {
  int count = 0;
  for (int y = image.height - 60; y < image.height; ++y)
    for (int x = 0; x < image.width; ++x) {
      const unsigned char* p = image.at(x, y);
      if (p[1] > 40 && p[1] > 2 * p[0] && p[1] > 2 * p[2]) ++count;
    }
  return count;
}

TEST_F(ViewerLook, SimTwoProjectShowsItsGroundTextureAndFloorColour) {
  const fs::path project = kSharedScenes / "Manipulator6DoF";
  if (!fs::exists(project / "ground.jpg")) GTEST_SKIP() << project << " is not there";
  // The same project without its ground image: the floor takes params.cfg's green.
  const fs::path plain = dir_ / "plain";
  fs::copy(project, plain, fs::copy_options::recursive);
  fs::remove(plain / "ground.jpg");
  const Image textured = screenshot(project.string(), "textured", {"--paused"});
  const Image coloured = screenshot(plain.string(), "coloured", {"--paused"});
  ASSERT_EQ(textured.width, 1280);
  ASSERT_EQ(coloured.width, 1280);
  EXPECT_GT(green_floor_pixels(coloured), 1280 * 60 / 2) << "params.cfg's green floor is missing";
  EXPECT_LT(green_floor_pixels(textured), 1280 * 60 / 20) << "the texture does not cover the floor";
  EXPECT_GT(floor_detail(textured), 2.5) << "the floor shows no texture detail";
  EXPECT_LT(floor_detail(coloured), 1.5);
}

TEST_F(ViewerLook, UnreadableFloorTextureIsALocatedWarningAndTheFloorKeepsItsColour) {
  const fs::path scene = boxes_scene(dir_ / "scene", false, "",
                                     "Floor.Diffuse.Color\t0\t0.451\t0\n"
                                     "Floor.Texture\tno_such_ground.jpg\t2\n");
  const Image image = screenshot(scene.string(), "floor", {});
  ASSERT_EQ(image.width, 1280);
  const std::string err = read_file(dir_ / "stderr.txt");
  EXPECT_NE(err.find("params.cfg:2: Floor.Texture"), std::string::npos) << err;
  EXPECT_NE(err.find("no_such_ground.jpg"), std::string::npos) << err;
  EXPECT_GT(green_floor_pixels(image), 1280 * 60 / 2) << "the floor lost its colour";
}

}  // namespace
}  // namespace s2sim::viewer_test
