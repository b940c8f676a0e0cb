// What components publish for the people watching (SDK 0.9, kernel/src/sim/annotations.cpp):
// log lines with time and source, HUD texts, trails and XY series, bounded, forgotten by a
// reset, and no part of the simulation's state.
#include <s2sim/kernel/simulation.hpp>

#include "common/edited_copy.hpp"

#include <gtest/gtest.h>

#include <filesystem>

namespace s2sim {
namespace {

namespace fs = std::filesystem;

const fs::path kFixture = fs::path(S2SIM_SOURCE_DIR) / "tests/kernel/sim/fixtures/components";

std::unique_ptr<Simulation> load_with_annotator(const std::string& attributes) {
  SimulationOptions o;
  o.plugin_path = {fs::path(S2SIM_TEST_PLUGIN_DIR) / "scene", fs::path(S2SIM_PLUGIN_DIR)};
  const fs::path scene =
      test::edited_copy(kFixture, "scene.xml", "</scene>",
                        "<plugin kind='test_annotator' id='notes' " + attributes + "/></scene>");
  return Simulation::load(scene, o);
}

TEST(Annotations, LinesHudTrailsAndSeriesArePublishedWithTheirSource) {
  auto sim = load_with_annotator("period_ms='10'");
  sim->run_until(0.1);
  const Annotations& a = sim->annotations();
  ASSERT_EQ(a.lines.size(), 10u);
  EXPECT_EQ(a.lines.front().text, "update 1");
  EXPECT_EQ(a.lines.front().source, "controllers/notes");
  EXPECT_EQ(a.lines.front().sequence, 0u);
  EXPECT_DOUBLE_EQ(a.lines.back().time_s, 0.09);
  EXPECT_EQ(a.lines_from(8).size(), 2u);
  EXPECT_EQ(a.hud_text(), "updates 10");
  ASSERT_EQ(a.trails.size(), 1u);
  EXPECT_EQ(a.trails[0].id, 0);
  EXPECT_EQ(a.trails[0].points_m.size(), 10u);
  EXPECT_DOUBLE_EQ(a.trails[0].points_m.back().x, 0.09);
  ASSERT_EQ(a.series.size(), 1u);
  EXPECT_EQ(a.series[0].id, 1);
  EXPECT_DOUBLE_EQ(a.series[0].points.back().second, 0.18);
}

TEST(Annotations, ClearTrailEmptiesItAndEveryListIsBounded) {
  auto sim = load_with_annotator("period_ms='1' clear_every='7'");
  sim->run_until(12.0);  // 12 000 updates
  const Annotations& a = sim->annotations();
  EXPECT_EQ(a.lines.size(), Annotations::kMaxLines);
  EXPECT_EQ(a.lines.back().text, "update 12000");
  EXPECT_EQ(a.next_sequence, 12000u);
  EXPECT_EQ(a.trails.at(0).points_m.size(), 12000u % 7 + 1) << "cleared every 7th update";
  EXPECT_EQ(a.series.at(0).points.size(), Annotations::kMaxPoints);
}

// 1 000 lines of 1 MB each were all kept (1.1 GB): a line keeps at most kMaxTextBytes now,
// and says how much was cut.
TEST(Annotations, AVeryLongLineOrHudTextIsCutAndSaysSo) {
  auto sim = load_with_annotator("period_ms='1' line_bytes='1000000'");
  sim->run_until(1.2);  // 1 200 lines of a megabyte
  const Annotations& a = sim->annotations();
  ASSERT_EQ(a.lines.size(), Annotations::kMaxLines);
  std::size_t kept = 0;
  for (const auto& line : a.lines) {
    EXPECT_LE(line.text.size(), Annotations::kMaxTextBytes + 32);
    kept += line.text.size();
  }
  EXPECT_LT(kept, 5'000'000u);
  EXPECT_EQ(a.lines.back().text.rfind("update 1200xxx", 0), 0u);
  EXPECT_NE(a.lines.back().text.find(" bytes cut]"), std::string::npos);
  EXPECT_LE(a.hud_text().size(), Annotations::kMaxTextBytes + 32);
}

TEST(Annotations, ResetForgetsThemAndSnapshotsDoNotHoldThem) {
  auto sim = load_with_annotator("period_ms='10'");
  const Simulation::Snapshot start = sim->save();
  sim->run_until(0.5);
  const std::size_t layout_size = start.values.size();
  EXPECT_EQ(sim->save().values.size(), layout_size);
  sim->reset();
  EXPECT_TRUE(sim->annotations().lines.empty());
  EXPECT_TRUE(sim->annotations().trails.empty());
  EXPECT_EQ(sim->annotations().hud_text(), "");
  sim->run_until(0.05);
  EXPECT_EQ(sim->annotations().lines.front().sequence, 0u) << "numbered from 0 again";
}

}  // namespace
}  // namespace s2sim
