// Where the runner and the viewer look for their SCENE (apps/common/scene_search.hpp): a path
// first, then a bare name in S2SIM_SCENE_PATH and the install's (here: the source tree's)
// scenes; a scene found nowhere is an error listing every place looked.
#include "common/temp_dir.hpp"

#include <s2sim/error.hpp>
#include <scene_search.hpp>

#include <gtest/gtest.h>

#include <cstdlib>
#include <filesystem>
#include <fstream>

namespace s2sim::apps {
namespace {

namespace fs = std::filesystem;

TEST(SceneSearch, APathFirstThenTheSearchPathThenTheScenesFolder) {
  const fs::path dir = test::process_temp_dir() / "scene_search";
  fs::create_directories(dir / "mine" / "default");
  std::ofstream(dir / "mine" / "default" / "scene.xml") << "<scene/>\n";
  ::unsetenv("S2SIM_SCENE_PATH");
  // This test runs from build/bin, as the runner does: after S2SIM_SCENE_PATH comes the
  // source tree's scenes/ (an installed runner's: its prefix's share/s2sim/scenes).
  const fs::path cwd = fs::current_path();
  fs::current_path(dir);
  EXPECT_EQ(find_scene("mine/default"), fs::path("mine/default"));  // a path, as given
  const std::string path = (dir / "nowhere").string() + ":" + (dir / "mine").string();
  ::setenv("S2SIM_SCENE_PATH", path.c_str(), 1);
  EXPECT_EQ(find_scene("default"), dir / "mine" / "default");
  EXPECT_EQ(scene_search_path().back(), fs::path(S2SIM_SOURCE_DIR) / "scenes");
  EXPECT_EQ(find_scene("nxt"), fs::path(S2SIM_SOURCE_DIR) / "scenes" / "nxt");
  try {
    find_scene("defualt");
    ADD_FAILURE() << "a misspelt name was found";
  } catch (const Error& e) {
    const std::string m = e.what();
    EXPECT_EQ(e.kind(), ErrorKind::scene);
    EXPECT_NE(m.find("scene 'defualt' not found; looked at, in order:"), std::string::npos) << m;
    EXPECT_NE(m.find((dir / "defualt").string()), std::string::npos) << m;
    EXPECT_NE(m.find((dir / "mine" / "defualt").string()), std::string::npos) << m;
    EXPECT_NE(m.find("scenes in " + (dir / "mine").string() + ": default"), std::string::npos) << m;
  }
  // A name with a '/' is a path only.
  try {
    find_scene("mine/defualt");
    ADD_FAILURE() << "found";
  } catch (const Error& e) {
    EXPECT_NE(std::string(e.what()).find("is only a path"), std::string::npos) << e.what();
  }
  ::unsetenv("S2SIM_SCENE_PATH");
  fs::current_path(cwd);
}

}  // namespace
}  // namespace s2sim::apps
