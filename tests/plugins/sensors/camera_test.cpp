// The `camera` sensor (docs/models/sensors.md, "Cameras") against a renderer that records what
// it is asked to draw: the images it declares, the shot (pose, field of view, clip planes), its
// period, its noise and its errors. What the headless renderer draws is tested in
// tests/apps/render.
#include <s2sim/kernel/simulation.hpp>

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <cmath>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <memory>
#include <string>
#include <vector>
#include "common/recording_renderer.hpp"
#include "common/temp_dir.hpp"

namespace s2sim {
namespace {

namespace fs = std::filesystem;
using ::testing::HasSubstr;

constexpr const char* kFront = "robots/rig/sensors/front/";
constexpr const char* kEye = "robots/rig/sensors/eye/";

std::string rig(const std::string& front_camera) {
  return R"(<?xml version="1.0" ?>
<robot>
  <solids>
    <cuboid><ID value='base'/><mass value='1'/><size x='0.2' y='0.2' z='0.1'/>
      <pos x='0' y='0' z='0.05'/></cuboid>
  </solids>
  <shells>
    <camera><ID value='eye'/><size x='0.02' y='0.02' z='0.02'/><pos x='0' y='0' z='0.2'/>
      <rot_deg x='90' y='0' z='0'/><focal length='50'/>
      <frame decimation='2' width='32' height='24'/></camera>
  </shells>
  <sensors>
    )" + front_camera +
         R"(
  </sensors>
</robot>
)";
}

constexpr const char* kFrontCamera =
    "<camera><ID value='front'/><pos x='0.1' y='0' z='0.1'/><rot_deg x='0' y='0' z='30'/>"
    "<frame width='64' height='48'/><fov horizontal='90'/><clip near='0.05' far='20'/>"
    "<outputs depth='1' segmentation='1'/><period value='0.02'/></camera>";

fs::path write_scene(const std::string& name, const std::string& front_camera) {
  const fs::path dir = test::process_temp_dir() / name;
  fs::remove_all(dir);
  fs::create_directories(dir);
  std::ofstream(dir / "scene.xml")
      << "<?xml version=\"1.0\" ?>\n<scene><robot><ID name='rig'/><body file='rig.xml'/>"
         "</robot></scene>\n";
  std::ofstream(dir / "rig.xml") << rig(front_camera);
  return dir;
}

SimulationOptions options(std::uint64_t seed = 1) {
  SimulationOptions o;
  o.seed = seed;
  o.plugin_path = {fs::path(S2SIM_PLUGIN_DIR)};
  return o;
}

std::unique_ptr<Simulation> load(const std::string& name, const std::string& front,
                                 std::vector<CameraShot>& shots, std::uint64_t seed = 1) {
  auto sim = Simulation::load(write_scene(name, front), options(seed));
  test::record_shots(*sim, shots);
  return sim;
}

Vec3 column(const Mat3& r, int c) {
  return {r.m[0][c], r.m[1][c], r.m[2][c]};
}

std::string error_of(const std::string& name, const std::string& front) {
  try {
    std::vector<CameraShot> shots;
    auto sim = load(name, front, shots);
    sim->step(1);
  } catch (const Error& e) {
    return e.what();
  }
  return "";
}

TEST(Camera, DeclaresTheImagesItsOutputsAskForWithTheirSizesAndFormats) {
  std::vector<CameraShot> shots;
  auto sim = load("camera_images", kFrontCamera, shots);
  EXPECT_THAT(
      sim->image_names(),
      ::testing::ElementsAre(std::string(kEye) + "rgb", std::string(kFront) + "rgb",
                             std::string(kFront) + "depth", std::string(kFront) + "segmentation"));
  const Image& depth = sim->image(std::string(kFront) + "depth");
  EXPECT_EQ(depth.width_px, 64);
  EXPECT_EQ(depth.height_px, 48);
  EXPECT_EQ(depth.format, PixelFormat::float32);
  EXPECT_EQ(depth.stride_bytes, 64 * 4);
  EXPECT_EQ(sim->image(std::string(kFront) + "segmentation").format, PixelFormat::uint16);
  const Image& eye = sim->image(std::string(kEye) + "rgb");
  EXPECT_EQ(eye.width_px, 32);
  EXPECT_EQ(eye.stride_bytes, 32 * 3);
  EXPECT_EQ(eye.frame, 0u);  // nothing drawn before the first step
  EXPECT_THROW(sim->image("robots/rig/sensors/front/rbg"), Error);
}

TEST(Camera, LooksAlongTheSensorsXOrTheShellsZWithTheFieldOfViewAsked) {
  std::vector<CameraShot> shots;
  auto sim = load("camera_shot", kFrontCamera, shots);
  const Pose base = sim->body_pose(1);  // the shot of tick 0 sees the pose at its start
  sim->step(1);
  ASSERT_EQ(shots.size(), 2u);  // the shell's camera, then the sensor's, in scene order
  const CameraShot& eye = shots[0];
  const CameraShot& front = shots[1];
  // The sensor, yawed 30°: it looks along (cos 30°, sin 30°, 0) with +Z up.
  const double c = std::cos(kPi / 6), s = std::sin(kPi / 6);
  const Vec3 forward = column(front.pose.rotation, 2), up = column(front.pose.rotation, 1);
  EXPECT_NEAR(forward.x, c, 1e-12);
  EXPECT_NEAR(forward.y, s, 1e-12);
  EXPECT_NEAR(forward.z, 0, 1e-12);
  EXPECT_NEAR(up.z, 1, 1e-12);
  EXPECT_NEAR(front.pose.position.x, base.position.x + 0.1, 1e-9);
  EXPECT_NEAR(front.pose.position.z, base.position.z + 0.1, 1e-9);
  // 90° across 64 pixels: the vertical field across 48.
  EXPECT_NEAR(front.vertical_fov_rad, 2 * std::atan(48.0 / 64), 1e-12);
  EXPECT_EQ(front.width_px, 64);
  EXPECT_EQ(front.height_px, 48);
  EXPECT_DOUBLE_EQ(front.near_m, 0.05);
  EXPECT_DOUBLE_EQ(front.far_m, 20);
  // The shell, turned 90° about X: its +Z, which it looks along, is the world's -Y, and its
  // +Y, up, the world's +Z. Focal length 50 (GLScene) across the longer side of SimTwo's
  // 640-pixel image: tan(fov/2) = 25.4·640/(4·96·50).
  const Vec3 eye_forward = column(eye.pose.rotation, 2), eye_up = column(eye.pose.rotation, 1);
  EXPECT_NEAR(eye_forward.y, -1, 1e-9);
  EXPECT_NEAR(eye_up.z, 1, 1e-9);
  const double half_longer = 25.4 * 640 / (4 * 96 * 50.0);
  EXPECT_NEAR(eye.vertical_fov_rad, 2 * std::atan(half_longer * 24 / 32), 1e-12);
}

TEST(Camera, DrawsAFrameAtEachPeriodIntoTheImagesTheControllersRead) {
  std::vector<CameraShot> shots;
  auto sim = load("camera_period", kFrontCamera, shots);
  const auto ticks = static_cast<std::int64_t>(std::llround(0.1 / sim->tick_s()));
  sim->step(ticks);
  // Both at 20 ms (the shell's decimation 2 in frames of 10 ms): ticks 0, 20, ..., 80.
  EXPECT_EQ(shots.size(), 10u);
  const Image& rgb = sim->image(std::string(kFront) + "rgb");
  EXPECT_EQ(rgb.frame, 5u);
  EXPECT_NEAR(rgb.time_s, 0.08, 1e-12);
  EXPECT_EQ(rgb.data[0], 100);
  EXPECT_EQ(reinterpret_cast<const float*>(sim->image(std::string(kFront) + "depth").data)[5],
            2.0f);
  EXPECT_DOUBLE_EQ(sim->signal(std::string(kFront) + "frames"), 5);
  sim->reset();  // images are outputs: zero again, no frame
  EXPECT_EQ(rgb.frame, 0u);
  EXPECT_EQ(rgb.data[0], 0);
}

TEST(Camera, WithoutARendererTheFirstFrameStopsTheRunNamingTheCamera) {
  auto sim = Simulation::load(write_scene("camera_no_renderer", kFrontCamera), options());
  try {
    sim->step(1);
    FAIL() << "expected an error";
  } catch (const Error& e) {
    EXPECT_EQ(e.kind(), ErrorKind::runtime);
    EXPECT_THAT(e.what(), HasSubstr("eye"));
    EXPECT_THAT(e.what(), HasSubstr("no renderer"));
  }
}

TEST(Camera, ARendererThatCannotStartIsSaidAtEveryFrame) {
  auto sim = Simulation::load(write_scene("camera_bad_renderer", kFrontCamera), options());
  sim->set_camera_renderer([](const Simulation&) -> std::unique_ptr<CameraRenderer> {
    throw Error(ErrorKind::runtime, "EGL: no display");
  });
  for (int i = 0; i < 2; ++i) {
    try {
      sim->step(1);
      FAIL() << "expected an error";
    } catch (const Error& e) {
      EXPECT_THAT(e.what(), HasSubstr("could not start: EGL: no display"));
    }
  }
}

std::vector<std::uint8_t> pixels(const Image& image) {
  return {image.data, image.data + image.size_bytes()};
}

TEST(Camera, PixelAndDepthNoiseFollowTheSeed) {
  const std::string noisy =
      "<camera><ID value='front'/><frame width='64' height='48'/><noise stdev='5'/>"
      "<depth_noise stdev='0.01'/><outputs depth='1'/></camera>";
  std::vector<CameraShot> shots;
  auto a = load("camera_noise_a", noisy, shots, 3);
  auto b = load("camera_noise_b", noisy, shots, 3);
  auto c = load("camera_noise_c", noisy, shots, 4);
  for (auto* sim : {a.get(), b.get(), c.get()})
    sim->step(1);
  const std::string rgb = std::string(kFront) + "rgb", depth = std::string(kFront) + "depth";
  EXPECT_EQ(pixels(a->image(rgb)), pixels(b->image(rgb)));
  EXPECT_EQ(pixels(a->image(depth)), pixels(b->image(depth)));
  EXPECT_NE(pixels(a->image(rgb)), pixels(c->image(rgb)));
  const std::vector<std::uint8_t> px = pixels(a->image(rgb));
  double sum = 0, sum2 = 0;
  for (std::uint8_t v : px) {
    sum += v;
    sum2 += (v - 100.0) * (v - 100.0);
  }
  const double n = static_cast<double>(px.size());
  EXPECT_NEAR(sum / n, 100, 0.2);  // 9 216 draws: the mean's stdev is 0.05
  EXPECT_NEAR(std::sqrt(sum2 / n), std::sqrt(25 + 1.0 / 12), 0.2);  // rounding adds 1/12
  const auto* d = reinterpret_cast<const float*>(a->image(depth).data);
  double dsum2 = 0;
  for (int i = 0; i < 64 * 48; ++i)
    dsum2 += (d[i] - 2.0) * (d[i] - 2.0);
  EXPECT_NEAR(std::sqrt(dsum2 / (64 * 48)), 0.01, 0.0005);
}

TEST(Camera, RefusesSettingsItCannotHonourNamingTheElement) {
  EXPECT_THAT(error_of("camera_bad_fov", "<camera><ID value='front'/><fov vertical='0'/></camera>"),
              HasSubstr("fov"));
  EXPECT_THAT(error_of("camera_two_fovs",
                       "<camera><ID value='front'/><fov vertical='60'/><focal length='20'/>"
                       "</camera>"),
              HasSubstr("not several"));
  EXPECT_THAT(
      error_of("camera_clip", "<camera><ID value='front'/><clip near='2' far='1'/></camera>"),
      HasSubstr("beyond near"));
  EXPECT_THAT(error_of("camera_outputs", "<camera><ID value='front'/><outputs rgb='0'/></camera>"),
              HasSubstr("at least one"));
  EXPECT_THAT(error_of("camera_width", "<camera><ID value='front'/><frame width='0'/></camera>"),
              HasSubstr("width"));
  EXPECT_THAT(error_of("camera_huge",
                       "<camera><ID value='front'/><frame width='16000' height='16000'/></camera>"),
              HasSubstr("pixels"));
}

}  // namespace
}  // namespace s2sim
