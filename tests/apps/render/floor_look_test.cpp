// A scene folder's floor and sky settings (apps/render/floor_look.cpp): SimTwo's params.cfg
// rows and check boxes, the project's ground image, and located warnings for bad rows.

#include "floor_look.hpp"

#include <gtest/gtest.h>
#include <unistd.h>

#include <filesystem>
#include <fstream>
#include "common/temp_dir.hpp"

namespace s2sim::render {
namespace {

namespace fs = std::filesystem;

class FloorLookTest : public ::testing::Test {
 protected:
  void SetUp() override {
    dir_ = s2sim::test::process_temp_dir() /
           ("s2sim_floor_look_" + std::to_string(::getpid()) + "_" +
            ::testing::UnitTest::GetInstance()->current_test_info()->name());
    fs::remove_all(dir_);
    fs::create_directories(dir_);
  }
  void TearDown() override { fs::remove_all(dir_); }
  void write(const std::string& name, const std::string& text) {
    std::ofstream(dir_ / name, std::ios::binary) << text;
  }
  fs::path dir_;
};

TEST_F(FloorLookTest, AFolderWithoutSettingsKeepsTheDefaults) {
  std::vector<std::string> warnings;
  const FloorLook look = read_floor_look(dir_, warnings);
  EXPECT_FALSE(look.color);
  EXPECT_FALSE(look.grid);
  EXPECT_FALSE(look.shadows);
  EXPECT_FALSE(look.sky);
  EXPECT_TRUE(look.texture_file.empty());
  EXPECT_TRUE(warnings.empty());
}

TEST_F(FloorLookTest, ReadsSimTwosFloorColourCheckBoxesAndGroundImage) {
  // As SimTwo writes them: CRLF lines, tab-separated params.cfg with empty rows.
  write("params.cfg",
        "Camera.Position\t0.36\t-1.24\t0.94\r\nFloor.Diffuse.Color\t0\t0.451\t0\r\n\t\t\t\r\n");
  write("SimTwo.ini", "[Config]\r\nCBGrid_Checked=1\r\nCBShadows_Checked=0\r\n");
  // config_Params.ini wins over SimTwo.ini where it has the key.
  write("config_Params.ini", "[Config]\r\nCBGrid_Checked=0\r\nCBSkyDome_Checked=1\r\n");
  write("ground.jpg", "not read here");
  std::vector<std::string> warnings;
  const FloorLook look = read_floor_look(dir_, warnings);
  ASSERT_TRUE(look.color);
  EXPECT_FLOAT_EQ((*look.color)[0], 0);
  EXPECT_FLOAT_EQ((*look.color)[1], 0.451f);
  EXPECT_FLOAT_EQ((*look.color)[2], 0);
  EXPECT_EQ(look.grid, std::optional<bool>(false));
  EXPECT_EQ(look.shadows, std::optional<bool>(false));
  EXPECT_EQ(look.sky, std::optional<bool>(true));
  EXPECT_EQ(look.texture_file, dir_ / "ground.jpg");
  EXPECT_FLOAT_EQ(look.texture_tile_m, 1);
  EXPECT_TRUE(warnings.empty());
}

TEST_F(FloorLookTest, FloorTextureRowNamesTheImageAndItsTileOverTheGroundImage) {
  write("ground.jpg", "x");
  write("params.cfg", "Floor.Texture\ttiles/floor.png\t2.5\n");
  std::vector<std::string> warnings;
  const FloorLook look = read_floor_look(dir_, warnings);
  EXPECT_EQ(look.texture_file, dir_ / "tiles/floor.png");
  EXPECT_FLOAT_EQ(look.texture_tile_m, 2.5f);
  EXPECT_EQ(look.texture_source, (dir_ / "params.cfg").string() + ":1: Floor.Texture");
}

TEST_F(FloorLookTest, BadRowsAreWarningsNamingFileLineAndValue) {
  write("params.cfg", "Floor.Diffuse.Color\t0\tgreen\t0\nFloor.Texture\tfloor.png\t-1\n");
  std::vector<std::string> warnings;
  const FloorLook look = read_floor_look(dir_, warnings);
  EXPECT_FALSE(look.color);
  EXPECT_TRUE(look.texture_file.empty());
  ASSERT_EQ(warnings.size(), 2u);
  const std::string params = (dir_ / "params.cfg").string();
  EXPECT_NE(warnings[0].find(params + ":1: Floor.Diffuse.Color"), std::string::npos) << warnings[0];
  EXPECT_NE(warnings[0].find("green"), std::string::npos) << warnings[0];
  EXPECT_NE(warnings[1].find(params + ":2: Floor.Texture"), std::string::npos) << warnings[1];
  EXPECT_NE(warnings[1].find("-1"), std::string::npos) << warnings[1];
}

}  // namespace
}  // namespace s2sim::render
