// SimTwo's spray-painting routines (plugins/pascal_script/host_paint.cpp) from a script
// (fixtures/spray_paint.pas) on the plate of tests/common/spray_scene.hpp, painted by two guns:
// the statistics the script reads are the ones computed here from the guns' signals (a
// triangle's paint the sum of theirs), by SimTwo's definitions.
#include <s2sim/kernel/simulation.hpp>

#include <gmock/gmock.h>
#include "common/spray_scene.hpp"
#include "common/temp_dir.hpp"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <map>
#include <string>
#include <vector>

namespace fs = std::filesystem;
using s2sim::ScriptMode;
using s2sim::Simulation;
using s2sim::SimulationOptions;
using ::testing::HasSubstr;

namespace {

#define SKIP_WITHOUT_FPC \
  if (std::system("fpc -iV > /dev/null 2>&1") != 0) GTEST_SKIP() << "no fpc"

/// The script's `PAINT <name> <value>` lines.
std::map<std::string, double> said(const Simulation& sim) {
  std::map<std::string, double> out;
  for (const auto& line : sim.annotations().lines) {
    if (line.text.rfind("PAINT ", 0) != 0) continue;
    const auto space = line.text.find(' ', 6);
    out[line.text.substr(6, space - 6)] = std::stod(line.text.substr(space + 1));
  }
  return out;
}

std::vector<std::string> errors(const Simulation& sim) {
  std::vector<std::string> out;
  for (const auto& line : sim.annotations().lines)
    if (line.text.rfind("PAINTERROR ", 0) == 0) out.push_back(line.text);
  return out;
}

TEST(ScriptPaint, TheScriptsStatisticsAreTheGunsPaintBySimTwosDefinitions) {
  SKIP_WITHOUT_FPC;
  ::setenv("S2SIM_PASCAL_CACHE", S2SIM_PASCAL_TEST_CACHE, 1);
  s2sim::test::SprayScene scene;
  scene.cells = 40;  // 3 200 triangles
  scene.on = false;  // the script turns it on
  SimulationOptions o;
  o.plugin_path = {fs::path(S2SIM_PLUGIN_DIR)};
  o.script_mode = ScriptMode::always;
  o.script_file = fs::path(S2SIM_PASCAL_FIXTURES) / "spray_paint.pas";
  const fs::path dir =
      s2sim::test::write_spray_scene(s2sim::test::process_temp_dir() / "script-paint", scene);
  {  // a second gun, 5 cm aside, on from the start, twice the flow
    std::ifstream in(dir / "sensors.xml");
    std::string text((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
    text.replace(text.find("</sensors>"), std::string("</sensors>").size(),
                 "  <spraygun>\n    <ID value='gun2'/>\n    <pos x='0.05' y='0' z='0.31'/>\n"
                 "    <rot_deg y='90'/>\n    <paint_rate value='2e-6'/>\n"
                 "    <paint_max_angle value='0.3'/>\n    <paint_default_on value='1'/>\n"
                 "  </spraygun>\n</sensors>\n");
    std::ofstream(dir / "sensors.xml") << text;
  }
  auto sim = Simulation::load(dir, o);
  sim->run_until(0.6);  // the statistics at 519 ms, the gun off since
  ASSERT_EQ(sim->signal("controllers/script/error"), 0);
  EXPECT_EQ(sim->input(sim->input_index("sensors/gun/on")), 0);
  EXPECT_EQ(sim->input(sim->input_index("sensors/gun2/on")), 0);
  std::vector<double> t;  // a triangle's paint: the sum of the guns'
  for (int k = 0; k < 2 * scene.cells * scene.cells; ++k)
    t.push_back(sim->signal("sensors/gun/paint/0/" + std::to_string(k)) +
                sim->signal("sensors/gun2/paint/0/" + std::to_string(k)));
  const double n = static_cast<double>(t.size());
  double sum = 0, pos_sum = 0, max = 0, min = 10000, pos_min = 10000;
  int painted = 0;
  for (double v : t) {
    sum += v;
    max = std::max(max, v);
    min = std::min(min, v);
    if (v > 0) {
      ++painted;
      pos_sum += v;
      pos_min = std::min(pos_min, v);
    }
  }
  const double avg = sum / n, pos_avg = pos_sum / painted;
  double sd = 0, pos_sd = 0;
  for (double v : t) {
    sd += (v - avg) * (v - avg);
    if (v > 0) pos_sd += (v - pos_avg) * (v - pos_avg);
  }
  sd = std::sqrt(sd / n);
  pos_sd = std::sqrt(pos_sd / painted);
  const auto got = said(*sim);
  ASSERT_EQ(got.count("avg"), 1u);
  EXPECT_GT(painted, 0);
  EXPECT_DOUBLE_EQ(got.at("avg"), avg);
  EXPECT_DOUBLE_EQ(got.at("sd"), sd);
  EXPECT_DOUBLE_EQ(got.at("posavg"), pos_avg);
  EXPECT_DOUBLE_EQ(got.at("possd"), pos_sd);
  EXPECT_DOUBLE_EQ(got.at("posmin"), pos_min);
  EXPECT_DOUBLE_EQ(got.at("min"), 0);
  EXPECT_DOUBLE_EQ(got.at("max"), max);
  EXPECT_DOUBLE_EQ(got.at("coverage"), painted / n);
  EXPECT_DOUBLE_EQ(got.at("mindist"), sim->signal("sensors/gun/min_dist"));
  // Ten bins from 0 to the greatest: every triangle counted once, the unpainted in the first.
  EXPECT_EQ(got.at("bins"), 10);
  EXPECT_EQ(got.at("binsum"), n);
  EXPECT_GE(got.at("bin0"), n - painted);
  EXPECT_GE(got.at("bin9"), 1);
  EXPECT_DOUBLE_EQ(got.at("bin9limit"), max);
  // The mesh in the plate's frame: 3 200 triangles on 0.16 m², flat, facing up.
  EXPECT_EQ(got.at("triangles"), n);
  EXPECT_NEAR(got.at("area"), scene.side_m * scene.side_m, 1e-6);  // assimp reads floats
  EXPECT_EQ(got.at("neighbours0"), 6);  // sharing a vertex with the corner's first triangle
  EXPECT_DOUBLE_EQ(got.at("normalz"), 1);
  EXPECT_NEAR(got.at("minx"), -0.2, 1e-6);
  EXPECT_NEAR(got.at("maxy"), 0.2, 1e-6);
  const auto e = errors(*sim);
  ASSERT_EQ(e.size(), 2u);
  EXPECT_THAT(e[0], HasSubstr("3 colours for the 3200 triangles"));
  EXPECT_THAT(e[1], HasSubstr("List index (2) out of bounds"));
  // ResetPaintTargetPaint: clear at once for the script, and in the gun's state after it.
  sim->run_until(0.9);
  const auto later = said(*sim);
  EXPECT_EQ(later.at("avg_at_reset"), 0);
  EXPECT_EQ(later.at("posmin_at_reset"), 10000) << "SimTwo's start value: nothing painted";
  EXPECT_EQ(later.at("max_after_reset"), 0);
  for (const char* gun : {"gun", "gun2"}) {
    EXPECT_EQ(sim->signal(std::string("sensors/") + gun + "/volume"), 0) << gun;
    EXPECT_EQ(sim->signal(std::string("sensors/") + gun + "/paint/0/resets"), 1) << gun;
  }
}

}  // namespace
