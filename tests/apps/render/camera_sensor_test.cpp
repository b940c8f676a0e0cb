// The `camera` sensor drawn by the headless renderer, end to end: a unit cube of known colour
// 1 m in front of a 90° camera on a robot, through the scene, the sensor plugin, the kernel's
// render_camera and the images a controller or Python reads; and s2sim-run --save-images.
#include "headless_camera_renderer.hpp"

#include <s2sim/image.hpp>
#include <s2sim/kernel/simulation.hpp>

#include <gtest/gtest.h>

#include <cmath>
#include <cstdlib>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <string>
#include <vector>
#include "common/temp_dir.hpp"
#include "no_display.hpp"

namespace s2sim {
namespace {

namespace fs = std::filesystem;

// The camera, on a post at (0.8, 0, 0.05), sits at (1, y, z) looking along +X: the cube's near
// face (x = 2, y in ±0.5, z in 0..1) is 1 m in front of it. The offsets put the face's edges
// at fractions of a pixel.
constexpr double kY_m = 0.1234, kZ_m = 0.4321;
constexpr int kW = 200, kH = 150;

fs::path write_scene(const std::string& name, const std::string& camera_extra = "") {
  const fs::path dir = test::process_temp_dir() / name;
  fs::remove_all(dir);
  fs::create_directories(dir);
  std::ofstream(dir / "scene.xml") << R"(<?xml version="1.0" ?>
<scene>
  <robot><ID name='rig'/><body file='rig.xml'/></robot>
  <things file='things.xml'/>
</scene>
)";
  std::ofstream(dir / "rig.xml") << R"(<?xml version="1.0" ?>
<robot>
  <solids>
    <cuboid><ID value='post'/><mass value='1'/><size x='0.1' y='0.1' z='0.1'/>
      <pos x='0.8' y='0' z='0.05'/></cuboid>
  </solids>
  <sensors>
    <camera><ID value='eye'/><pos x='0.2' y=')" +
                                        std::to_string(kY_m) + "' z='" +
                                        std::to_string(kZ_m - 0.05) + R"('/>
      <frame width='200' height='150'/><fov vertical='90'/><clip near='0.05' far='50'/>
      <outputs rgb='1' depth='1' segmentation='1'/>)" +
                                        camera_extra + R"(
    </camera>
  </sensors>
</robot>
)";
  std::ofstream(dir / "things.xml") << R"(<?xml version="1.0" ?>
<things>
  <cuboid><ID value='cube'/><mass value='1'/><size x='1' y='1' z='1'/>
    <pos x='2.5' y='0' z='0.5'/><color_rgb r='230' g='40' b='40'/></cuboid>
</things>
)";
  return dir;
}

std::unique_ptr<Simulation> load(const fs::path& scene, std::uint64_t seed = 1) {
  SimulationOptions o;
  o.seed = seed;
  o.plugin_path = {fs::path(S2SIM_PLUGIN_DIR)};
  auto sim = Simulation::load(scene, o);
  sim->set_camera_renderer(render::headless_camera_renderer_factory());
  return sim;
}

const std::string kEye = "robots/rig/sensors/eye/";

std::uint16_t id_at(const Image& ids, int x, int y) {
  std::uint16_t v;
  std::memcpy(&v, ids.row(y) + 2 * x, 2);
  return v;
}
float depth_at(const Image& depth, int x, int y) {
  float v;
  std::memcpy(&v, depth.row(y) + 4 * x, 4);
  return v;
}

int body_index(const Simulation& sim, const std::string& path) {
  for (int b = 0; b < sim.body_count(); ++b)
    if (sim.body_path(b) == path) return b;
  return -1;
}

TEST(CameraSensor, SeesAUnitCubeWhereThePinholeModelPutsIt) {
  auto sim = load(write_scene("camera_sensor_cube"));
  sim->step(1);  // the frame of tick 0
  const Image& rgb = sim->image(kEye + "rgb");
  const Image& depth = sim->image(kEye + "depth");
  const Image& ids = sim->image(kEye + "segmentation");
  ASSERT_EQ(rgb.frame, 1u);
  const int cube = body_index(*sim, "things/cube");
  ASSERT_GT(cube, 0);
  // The pinhole model: f = (H/2)/tan(45°) pixels; the camera's +X (world +Y) is the image's
  // left, its +Y (world +Z) up.
  const double f = kH / 2.0;
  const double left = kW / 2.0 - f * (0.5 - kY_m), right = kW / 2.0 + f * (0.5 + kY_m);
  const double top = kH / 2.0 - f * (1 - kZ_m), bottom = kH / 2.0 + f * kZ_m;
  // The colour: the cube's red (lit, so darker or brighter, never another hue).
  auto red = [&](int x, int y) {
    const std::uint8_t* p = rgb.row(y) + 3 * x;
    return p[0] > 2 * p[1] + 40 && p[0] > 2 * p[2] + 40;
  };
  int first_col = kW, last_col = -1, first_row = kH, last_row = -1;
  for (int y = 0; y < kH; ++y)
    for (int x = 0; x < kW; ++x)
      if (red(x, y)) {
        first_col = std::min(first_col, x), last_col = std::max(last_col, x);
        first_row = std::min(first_row, y), last_row = std::max(last_row, y);
      }
  // A covered pixel's centre lies inside: the edges are within half a pixel of the first and
  // one past the last covered pixel.
  std::printf("edges: left %.3f (%d), right %.3f (%d), top %.3f (%d), bottom %.3f (%d)\n", left,
              first_col, right, last_col + 1, top, first_row, bottom, last_row + 1);
  EXPECT_LE(std::abs(first_col - left), 0.5);
  EXPECT_LE(std::abs(last_col + 1 - right), 0.5);
  EXPECT_LE(std::abs(first_row - top), 0.5);
  EXPECT_LE(std::abs(last_row + 1 - bottom), 0.5);
  // Every red pixel is the cube's in the segmentation, and the cube's are red.
  for (int y = 0; y < kH; ++y)
    for (int x = 0; x < kW; ++x)
      ASSERT_EQ(red(x, y), id_at(ids, x, y) == cube) << x << ", " << y;
  const int cx = static_cast<int>(0.5 * (left + right)),
            cy = static_cast<int>(0.5 * (top + bottom));
  EXPECT_EQ(id_at(ids, cx, cy), cube);
  EXPECT_NEAR(depth_at(depth, cx, cy), 1.0, 1e-3);
  EXPECT_EQ(id_at(ids, kW / 2, 0), kNoBodyId);  // the sky above the cube
  EXPECT_TRUE(std::isinf(depth_at(depth, kW / 2, 0)));
  EXPECT_EQ(id_at(ids, 0, kH - 1), 0);  // the floor, bottom left
  std::printf("depth at the face's centre: %.6f m\n", depth_at(depth, cx, cy));
}

std::vector<std::uint8_t> bytes(const Image& image) {
  return {image.data, image.data + image.size_bytes()};
}

TEST(CameraSensor, TheSameSeedGivesByteIdenticalNoisyImages) {
  const std::string noise = "<noise stdev='4'/><depth_noise stdev='0.002'/>";
  auto a = load(write_scene("camera_sensor_seed_a", noise), 5);
  auto b = load(write_scene("camera_sensor_seed_b", noise), 5);
  auto c = load(write_scene("camera_sensor_seed_c", noise), 6);
  const auto ticks = static_cast<std::int64_t>(std::llround(0.1 / a->tick_s()));
  for (auto* sim : {a.get(), b.get(), c.get()})
    sim->step(ticks);
  EXPECT_EQ(a->image(kEye + "rgb").frame, 3u);  // at 0, 40 and 80 ms
  for (const char* name : {"rgb", "depth", "segmentation"})
    EXPECT_EQ(bytes(a->image(kEye + name)), bytes(b->image(kEye + name))) << name;
  EXPECT_NE(bytes(a->image(kEye + "rgb")), bytes(c->image(kEye + "rgb")));
  EXPECT_NE(bytes(a->image(kEye + "depth")), bytes(c->image(kEye + "depth")));
}

}  // namespace
}  // namespace s2sim
