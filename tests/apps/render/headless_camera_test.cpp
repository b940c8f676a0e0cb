// The cameras' headless renderer (apps/render/headless_camera_renderer.cpp): EGL with no
// display, a unit cube 1 m in front of a pinhole camera whose image edges, depth and body ids
// are checked against the analytic projection, repeatable images, another thread, and a
// clear error when EGL has no driver.
#include "headless_camera_renderer.hpp"

#include <s2sim/error.hpp>
#include <s2sim/image.hpp>
#include <s2sim/kernel/simulation.hpp>

#include <gtest/gtest.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <limits>
#include <thread>
#include <vector>
#include "common/temp_dir.hpp"
#include "no_display.hpp"

namespace s2sim::render {
namespace {

namespace fs = std::filesystem;

// The camera looks along the world's +X from (1, y, z), so the cube's near face (x = 2) is 1 m
// in front of it; it stands inside the cube's slab in y and z, so no other face shows. The
// offsets put the face's edges at fractions of a pixel.
constexpr double kCameraY_m = 0.1234, kCameraZ_m = 0.4321;
constexpr int kWidth_px = 200, kHeight_px = 150;
constexpr double kFov_rad = 90 * 3.14159265358979323846 / 180;

fs::path write_cube_scene() {
  const fs::path dir = test::process_temp_dir() / "render_cube";
  fs::create_directories(dir);
  std::ofstream(dir / "scene.xml") << R"(<?xml version="1.0" ?>
<scene>
  <things file='things.xml'/>
</scene>
)";
  std::ofstream(dir / "things.xml") << R"(<?xml version="1.0" ?>
<things>
  <cuboid>
    <ID value='cube'/>
    <mass value='1'/>
    <size x='1' y='1' z='1'/>
    <pos x='2.5' y='0' z='0.5'/>
    <color_rgb r='230' g='40' b='40'/>
  </cuboid>
</things>
)";
  return dir;
}

std::unique_ptr<Simulation> load(const fs::path& scene) {
  SimulationOptions o;
  o.plugin_path = {fs::path(S2SIM_PLUGIN_DIR)};
  return Simulation::load(scene, o);
}

/// A camera at `eye` looking at `target`, world +Z up (camera +Z forward, +Y up, +X left).
Pose looking(const Vec3& eye, const Vec3& target) {
  const Vec3 z = (target - eye) / norm(target - eye);
  const Vec3 x = cross(Vec3{0, 0, 1}, z) / norm(cross(Vec3{0, 0, 1}, z));
  const Vec3 y = cross(z, x);
  Pose p;
  p.position = eye;
  const Vec3 axes[3] = {x, y, z};
  for (int c = 0; c < 3; ++c) {
    p.rotation.m[0][c] = axes[c].x;
    p.rotation.m[1][c] = axes[c].y;
    p.rotation.m[2][c] = axes[c].z;
  }
  return p;
}

CameraShot cube_shot() {
  CameraShot shot;
  shot.pose = looking({1, kCameraY_m, kCameraZ_m}, {2, kCameraY_m, kCameraZ_m});
  shot.vertical_fov_rad = kFov_rad;
  shot.near_m = 0.05;
  shot.far_m = 50;
  shot.width_px = kWidth_px;
  shot.height_px = kHeight_px;
  return shot;
}

/// An image with its own pixels, as the kernel hands them (rows padded to 8 bytes, so that
/// the stride is not the row's width).
struct OwnedImage {
  OwnedImage(int width_px, int height_px, PixelFormat format) {
    image.width_px = width_px;
    image.height_px = height_px;
    image.format = format;
    image.stride_bytes = (width_px * bytes_per_pixel(format) + 7) / 8 * 8 + 8;
    bytes.assign(static_cast<std::size_t>(image.stride_bytes) * height_px, 0xAB);
    image.data = bytes.data();
  }
  std::vector<std::uint8_t> bytes;
  Image image;

  const std::uint8_t* rgb(int x, int y) const { return image.row(y) + 3 * x; }
  float depth(int x, int y) const {
    float d;
    std::memcpy(&d, image.row(y) + 4 * x, sizeof d);
    return d;
  }
  std::uint16_t id(int x, int y) const {
    std::uint16_t v;
    std::memcpy(&v, image.row(y) + 2 * x, sizeof v);
    return v;
  }
};

struct ShotImages {
  explicit ShotImages(const CameraShot& shot)
      : rgb(shot.width_px, shot.height_px, PixelFormat::rgb8),
        depth(shot.width_px, shot.height_px, PixelFormat::float32),
        ids(shot.width_px, shot.height_px, PixelFormat::uint16) {}
  OwnedImage rgb, depth, ids;
};

void render(CameraRenderer& renderer, const Simulation& sim, const CameraShot& shot,
            ShotImages& images) {
  const std::vector<Pose>& poses = sim.body_poses();
  renderer.render(shot, poses.data(), static_cast<int>(poses.size()), &images.rgb.image,
                  &images.depth.image, &images.ids.image);
}

bool cube_coloured(const std::uint8_t* p) {
  return p[0] > 40 && p[0] > 2 * std::max(p[1], p[2]);
}

class CubeCamera : public ::testing::Test {
 protected:
  void SetUp() override {
    sim_ = load(write_cube_scene());
    ASSERT_EQ(sim_->scene().things.size(), 1u);
    cube_body_ = sim_->things()[0].body;
    renderer_ = make_headless_camera_renderer(*sim_);
  }
  std::unique_ptr<Simulation> sim_;
  std::unique_ptr<CameraRenderer> renderer_;
  int cube_body_ = -1;
};

TEST_F(CubeCamera, TheCubeCoversItsPinholeProjectionToHalfAPixel) {
  const CameraShot shot = cube_shot();
  ShotImages images(shot);
  render(*renderer_, *sim_, shot, images);

  // The face's corners in the camera frame: x = world y - camera y (camera +X is world +Y),
  // y = world z - camera z, z = 1 m. Image column u = W/2 - f x / z (+X is the image's left),
  // row v = H/2 - f y / z, pixel (i, j) covering [i, i + 1] x [j, j + 1].
  const double f_px = kHeight_px / 2.0 / std::tan(kFov_rad / 2);
  const double left = kWidth_px / 2.0 - f_px * (0.5 - kCameraY_m);
  const double right = kWidth_px / 2.0 - f_px * (-0.5 - kCameraY_m);
  const double top = kHeight_px / 2.0 - f_px * (1.0 - kCameraZ_m);
  const double bottom = kHeight_px / 2.0 - f_px * (0.0 - kCameraZ_m);

  int first_col = kWidth_px, last_col = -1, first_row = kHeight_px, last_row = -1;
  for (int y = 0; y < kHeight_px; ++y)
    for (int x = 0; x < kWidth_px; ++x)
      if (cube_coloured(images.rgb.rgb(x, y))) {
        first_col = std::min(first_col, x), last_col = std::max(last_col, x);
        first_row = std::min(first_row, y), last_row = std::max(last_row, y);
      }
  ASSERT_GE(last_col, 0) << "no cube-coloured pixel";
  // A pixel is covered when its centre is inside: the measured edges are the covered pixels'
  // centres, half a pixel further out.
  const double errors[4] = {first_col + 0.5 - 0.5 - left, last_col + 0.5 + 0.5 - right,
                            first_row + 0.5 - 0.5 - top, last_row + 0.5 + 0.5 - bottom};
  const char* names[4] = {"left", "right", "top", "bottom"};
  for (int k = 0; k < 4; ++k) {
    EXPECT_LE(std::abs(errors[k]), 0.5) << names[k] << " edge";
    RecordProperty(std::string(names[k]) + "_edge_error_px", std::to_string(errors[k]));
    std::printf("%s edge: predicted %.4f px, measured error %+.4f px\n", names[k],
                k == 0   ? left
                : k == 1 ? right
                : k == 2 ? top
                         : bottom,
                errors[k]);
  }
  // Every pixel whose centre is inside the face is the cube's colour (a solid rectangle).
  for (int y = first_row; y <= last_row; ++y)
    for (int x = first_col; x <= last_col; ++x)
      ASSERT_TRUE(cube_coloured(images.rgb.rgb(x, y))) << x << ", " << y;
  // The body ids cover the same pixels.
  for (int y = 0; y < kHeight_px; ++y)
    for (int x = 0; x < kWidth_px; ++x)
      ASSERT_EQ(images.ids.id(x, y) == cube_body_, cube_coloured(images.rgb.rgb(x, y)))
          << x << ", " << y;
}

TEST_F(CubeCamera, DepthIsAlongTheOpticalAxisAndIdsNameTheBodies) {
  const CameraShot shot = cube_shot();
  ShotImages images(shot);
  render(*renderer_, *sim_, shot, images);
  const double f_px = kHeight_px / 2.0 / std::tan(kFov_rad / 2);
  // The face's centre (world y = 0, z = 0.5).
  const int cx = static_cast<int>(kWidth_px / 2.0 - f_px * (0 - kCameraY_m));
  const int cy = static_cast<int>(kHeight_px / 2.0 - f_px * (0.5 - kCameraZ_m));
  const double face_error_m = images.depth.depth(cx, cy) - 1.0;
  std::printf("depth at the face's centre: %.7f m (error %+.2e m)\n", images.depth.depth(cx, cy),
              face_error_m);
  RecordProperty("face_depth_error_m", std::to_string(face_error_m));
  EXPECT_LT(std::abs(face_error_m), 1e-3);
  // Along the optical axis, not along the ray: the same 1 m near the face's corner.
  EXPECT_NEAR(images.depth.depth(cx + 30, cy - 30), 1.0, 1e-3);
  EXPECT_EQ(images.ids.id(cx, cy), cube_body_);

  // The floor in the bottom row: the ray through the pixel's centre meets z = 0 at
  // z_camera = height f / (v - H/2).
  const int floor_row = kHeight_px - 1;
  const double floor_m = kCameraZ_m * f_px / (floor_row + 0.5 - kHeight_px / 2.0);
  EXPECT_EQ(images.ids.id(cx, floor_row), 0) << "the floor is the world's";
  EXPECT_NEAR(images.depth.depth(cx, floor_row), floor_m, 1e-3);

  // The sky in the top row: nothing.
  EXPECT_EQ(images.ids.id(cx, 0), kNoBodyId);
  EXPECT_EQ(images.depth.depth(cx, 0), std::numeric_limits<float>::infinity());
  const std::uint8_t* sky = images.rgb.rgb(cx, 0);
  EXPECT_GT(sky[2], sky[0]) << "the sky is blue";
  // Only the pixels were written: the rows' padding keeps what was there.
  EXPECT_EQ(images.rgb.image.row(0)[3 * kWidth_px], 0xAB);
}

TEST_F(CubeCamera, RenderingTwiceGivesTheSameBytes) {
  const CameraShot shot = cube_shot();
  ShotImages first(shot), second(shot);
  render(*renderer_, *sim_, shot, first);
  render(*renderer_, *sim_, shot, second);
  EXPECT_EQ(first.rgb.bytes, second.rgb.bytes);
  EXPECT_EQ(first.depth.bytes, second.depth.bytes);
  EXPECT_EQ(first.ids.bytes, second.ids.bytes);
}

TEST_F(CubeCamera, BodiesAreDrawnAtThePosesPassedAndAnyImageMayBeLeftOut) {
  CameraShot shot = cube_shot();
  std::vector<Pose> poses = sim_->body_poses();
  poses[static_cast<std::size_t>(cube_body_)].position.y += 10;  // out of sight
  OwnedImage ids(shot.width_px, shot.height_px, PixelFormat::uint16);
  renderer_->render(shot, poses.data(), static_cast<int>(poses.size()), nullptr, nullptr,
                    &ids.image);
  for (int y = 0; y < shot.height_px; ++y)
    for (int x = 0; x < shot.width_px; ++x)
      ASSERT_NE(ids.id(x, y), cube_body_) << x << ", " << y;
  // Colour alone, at another size.
  shot.width_px = 64;
  shot.height_px = 48;
  OwnedImage rgb(shot.width_px, shot.height_px, PixelFormat::rgb8);
  renderer_->render(shot, sim_->body_poses().data(), static_cast<int>(sim_->body_count()),
                    &rgb.image, nullptr, nullptr);
  EXPECT_TRUE(cube_coloured(rgb.rgb(shot.width_px / 2, shot.height_px / 2)));
}

TEST_F(CubeCamera, ShotsMayComeFromAnotherThread) {
  const CameraShot shot = cube_shot();
  ShotImages here(shot), there(shot);
  render(*renderer_, *sim_, shot, here);
  std::thread other([&] { render(*renderer_, *sim_, shot, there); });
  other.join();
  EXPECT_EQ(here.rgb.bytes, there.rgb.bytes);
  EXPECT_EQ(here.depth.bytes, there.depth.bytes);
  EXPECT_EQ(here.ids.bytes, there.ids.bytes);
}

TEST(HeadlessCamera, TheFactoryDrawsTheDefaultScene) {
  auto sim = load(fs::path(S2SIM_SOURCE_DIR) / "scenes/default");
  std::unique_ptr<CameraRenderer> renderer = headless_camera_renderer_factory()(*sim);
  CameraShot shot;
  shot.pose = looking({3.5, -3.5, 2.0}, {0, 0, 0.3});
  shot.vertical_fov_rad = 0.8;
  for (const auto& [w, h] : {std::pair{320, 240}, std::pair{640, 480}}) {
    shot.width_px = w;
    shot.height_px = h;
    ShotImages images(shot);
    render(*renderer, *sim, shot, images);  // the first: shaders, shadow map, framebuffers
    constexpr int kShots = 10;
    const auto start = std::chrono::steady_clock::now();
    for (int i = 0; i < kShots; ++i)
      render(*renderer, *sim, shot, images);
    const double ms =
        std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - start)
            .count() /
        kShots;
    std::printf("scenes/default %dx%d colour + depth + ids: %.1f ms a shot\n", w, h, ms);
    RecordProperty("ms_per_shot_" + std::to_string(w) + "x" + std::to_string(h),
                   std::to_string(ms));
    int bodies = 0;
    for (int y = 0; y < h; ++y)
      for (int x = 0; x < w; ++x)
        bodies += images.ids.id(x, y) != 0 && images.ids.id(x, y) != kNoBodyId;
    EXPECT_GT(bodies, w * h / 400) << "the mechanisms are in view";
  }
}

// Registered a second time with GLVND pointed at no EGL driver (tests/apps/render/
// CMakeLists.txt); skipped in the ordinary run.
TEST(HeadlessCamera, WithoutAnEglDriverTheErrorSaysSo) {
  if (std::getenv("S2SIM_RENDER_EXPECT_NO_EGL") == nullptr)
    GTEST_SKIP() << "runs as HeadlessCamera.NoEglDriver, without an EGL driver";
  auto sim = load(write_cube_scene());
  try {
    make_headless_camera_renderer(*sim);
    FAIL() << "a renderer without an EGL driver";
  } catch (const Error& e) {
    EXPECT_EQ(e.kind(), ErrorKind::runtime);
    const std::string what = e.what();
    EXPECT_NE(what.find("EGL"), std::string::npos) << what;
    EXPECT_NE(what.find("0x300"), std::string::npos) << "an EGL error code: " << what;
    std::printf("%s\n", what.c_str());
  }
}

TEST(HeadlessCamera, AnUnknownPlatformIsNamed) {
  auto sim = load(write_cube_scene());
  ::setenv("S2SIM_EGL_PLATFORM", "wayland", 1);
  try {
    make_headless_camera_renderer(*sim);
    ADD_FAILURE() << "a renderer on an unknown platform";
  } catch (const Error& e) {
    EXPECT_EQ(e.kind(), ErrorKind::runtime);
    EXPECT_NE(std::string(e.what()).find("S2SIM_EGL_PLATFORM=wayland"), std::string::npos)
        << e.what();
  }
  ::unsetenv("S2SIM_EGL_PLATFORM");
}

}  // namespace
}  // namespace s2sim::render
