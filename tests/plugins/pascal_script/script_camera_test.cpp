// SimTwo's camera image routines (plugins/pascal_script/host_camera.cpp): a script
// (fixtures/camera_pixel.pas) reads GetCameraPixel and CamBitmap.Canvas.Pixels at SimTwo's
// 640 x 480 coordinates on a robot with two <camera> shells; the pixels are the last shell's,
// scaled to its size, as the gradient renderer drew them.
#include <s2sim/kernel/simulation.hpp>

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <string>
#include <vector>
#include "common/gradient_renderer.hpp"
#include "common/temp_dir.hpp"

namespace fs = std::filesystem;
using s2sim::ScriptMode;
using s2sim::Simulation;
using s2sim::SimulationOptions;
using s2sim::test::GradientColour;
using ::testing::HasSubstr;

namespace {

#define SKIP_WITHOUT_FPC \
  if (std::system("fpc -iV > /dev/null 2>&1") != 0) GTEST_SKIP() << "no fpc"

constexpr int kWidth = 160, kHeight = 120;  // the last shell's

fs::path write_scene(const std::string& shells) {
  const fs::path dir = s2sim::test::process_temp_dir() / "script-camera";
  fs::remove_all(dir);
  fs::create_directories(dir);
  std::ofstream(dir / "scene.xml")
      << "<?xml version=\"1.0\" ?>\n<scene><robot><ID name='rig'/><body file='rig.xml'/>"
         "</robot></scene>\n";
  std::ofstream(dir / "rig.xml") << R"(<?xml version="1.0" ?>
<robot>
  <solids>
    <cuboid><ID value='base'/><mass value='1'/><size x='0.2' y='0.2' z='0.1'/>
      <pos x='0' y='0' z='0.05'/></cuboid>
  </solids>
  <shells>)" + shells + R"(</shells>
</robot>
)";
  return dir;
}

const std::string kTwoCameras =
    "<camera><ID value='first'/><size x='0.02' y='0.02' z='0.02'/><pos x='0' y='0' z='0.2'/>"
    "<frame decimation='1' width='32' height='24'/></camera>"
    "<camera><ID value='last'/><size x='0.02' y='0.02' z='0.02'/><pos x='0' y='0' z='0.2'/>"
    "<frame decimation='1' width='160' height='120'/></camera>";

std::vector<std::string> lines(const Simulation& sim, const std::string& tag) {
  std::vector<std::string> out;
  for (const auto& line : sim.annotations().lines)
    if (line.text.rfind(tag + " ", 0) == 0) out.push_back(line.text.substr(tag.size() + 1));
  return out;
}

std::unique_ptr<Simulation> run(const std::string& shells) {
  ::setenv("S2SIM_PASCAL_CACHE", S2SIM_PASCAL_TEST_CACHE, 1);
  SimulationOptions o;
  o.plugin_path = {fs::path(S2SIM_PLUGIN_DIR)};
  o.script_mode = ScriptMode::always;
  o.script_file = fs::path(S2SIM_PASCAL_FIXTURES) / "camera_pixel.pas";
  auto sim = Simulation::load(write_scene(shells), o);
  s2sim::test::render_gradients(*sim);
  sim->run_until(0.2);
  return sim;
}

TEST(ScriptCamera, PixelsAreTheLastShellsImageScaledFromSimTwosSize) {
  SKIP_WITHOUT_FPC;
  auto sim = run(kTwoCameras);
  ASSERT_EQ(sim->signal("controllers/script/error"), 0);
  const std::vector<std::string> said = lines(*sim, "CAM");
  ASSERT_EQ(said.size(), 4u);
  for (const std::string& line : said) {
    SCOPED_TRACE(line);
    std::istringstream in(line);
    int X, Y, r, g, b, a;
    long colour;
    in >> X >> Y >> r >> g >> b >> a >> colour;
    const int x = X * kWidth / 640, y = Y * kHeight / 480;
    EXPECT_EQ(r, GradientColour::red(x, kWidth));
    EXPECT_EQ(g, GradientColour::green(y, kHeight));
    EXPECT_EQ(b, GradientColour::kBlue);
    EXPECT_EQ(a, 255);
    EXPECT_EQ(colour, r | (g << 8) | (b << 16));  // TColor: red in the low byte
  }
  // Row 0 is the top: (0, 0) dark, (639, 479) the bottom right's full red and green.
  EXPECT_THAT(said[0], HasSubstr("0 0 0 0 60 255"));
  EXPECT_THAT(said[1], HasSubstr("639 479 255 255 60 255"));
  EXPECT_EQ(lines(*sim, "CAMSIZE"), std::vector<std::string>{"640 480"});
  const std::vector<std::string> errors = lines(*sim, "CAMERR");
  ASSERT_EQ(errors.size(), 3u);
  EXPECT_THAT(errors[0], HasSubstr("640"));
  EXPECT_THAT(errors[1], HasSubstr("-1"));
  EXPECT_THAT(errors[2], HasSubstr("belongs to SimTwo's own rendering"));
}

TEST(ScriptCamera, WithoutACameraShellTheImageIsBlack) {
  SKIP_WITHOUT_FPC;
  auto sim = run("");
  ASSERT_EQ(sim->signal("controllers/script/error"), 0);
  const std::vector<std::string> said = lines(*sim, "CAM");
  ASSERT_EQ(said.size(), 4u);
  EXPECT_EQ(said[2], "320 240 0 0 0 0 0");
}

}  // namespace
