// s2sim-run --save-images and --video: a robot's camera (colour, depth, body ids) written as
// PNG files and an MP4 that decode to the camera's size and frame count.
#include "runner_harness.hpp"

#ifdef S2SIM_TEST_VIDEO
#include "common/decoded_video.hpp"
#endif

namespace {

using namespace s2sim::runner_test;

/// A robot on the floor with a 64 × 48 camera drawing colour, depth and ids every 40 ms.
void write_camera_scene(const fs::path& dir, const std::string& second_camera = "") {
  write_file(dir / "scene.xml",
             "<?xml version='1.0'?><scene><robot><ID name='rig'/><body file='rig.xml'/>"
             "</robot></scene>");
  write_file(dir / "rig.xml", R"(<?xml version='1.0'?>
<robot>
  <solids><cuboid><ID value='base'/><mass value='1'/><size x='0.2' y='0.2' z='0.1'/>
    <pos x='0' y='0' z='0.05'/></cuboid></solids>
  <sensors>
    <camera><ID value='eye'/><pos x='0.1' y='0' z='0.1'/><rot_deg x='0' y='20' z='0'/>
      <frame width='64' height='48'/><outputs depth='1' segmentation='1'/></camera>
    )" + second_camera + R"(
  </sensors>
</robot>)");
}

/// A PNG's width, height, bit depth and colour type from its IHDR chunk.
struct PngHeader {
  int width = 0, height = 0, bit_depth = 0, colour_type = -1;
};
PngHeader png_header(const fs::path& file) {
  const std::string bytes = read_file(file);
  PngHeader h;
  if (bytes.size() < 26 || bytes.compare(1, 3, "PNG") != 0) return h;
  auto be32 = [&](std::size_t at) {
    return (static_cast<unsigned char>(bytes[at]) << 24) |
           (static_cast<unsigned char>(bytes[at + 1]) << 16) |
           (static_cast<unsigned char>(bytes[at + 2]) << 8) |
           static_cast<unsigned char>(bytes[at + 3]);
  };
  h.width = static_cast<int>(be32(16));
  h.height = static_cast<int>(be32(20));
  h.bit_depth = static_cast<unsigned char>(bytes[24]);
  h.colour_type = static_cast<unsigned char>(bytes[25]);
  return h;
}

std::vector<fs::path> files_in(const fs::path& dir) {
  std::vector<fs::path> files;
  if (fs::is_directory(dir))
    for (const auto& e : fs::directory_iterator(dir))
      files.push_back(e.path());
  std::sort(files.begin(), files.end());
  return files;
}

TEST_F(Runner, SaveImagesWritesEveryCameraFrameAsAPng) {
  write_camera_scene(dir_ / "cam");
  const Result r = run({"cam", "--duration", "0.2", "--save-images", "frames", "--quiet"});
  ASSERT_EQ(r.status, 0) << r.err;
  // Frames at 0, 40, 80, 120 and 160 ms.
  const fs::path base = dir_ / "frames/robots/rig/sensors/eye";
  for (const char* image : {"rgb", "depth", "segmentation"}) {
    const std::vector<fs::path> files = files_in(base / image);
    ASSERT_EQ(files.size(), 5u) << image;
    EXPECT_EQ(files.front().filename(), "000001.png");
    const PngHeader h = png_header(files.back());
    EXPECT_EQ(h.width, 64) << image;
    EXPECT_EQ(h.height, 48) << image;
    EXPECT_EQ(h.bit_depth, std::string(image) == "rgb" ? 8 : 16) << image;
    EXPECT_EQ(h.colour_type, std::string(image) == "rgb" ? 2 : 0) << image;  // RGB, grey
  }
  // Another folder it cannot make: exit 6, naming it.
  write_file(dir_ / "blocked", "a file where the folder would be");
  const Result blocked = run({"cam", "--duration", "0.05", "--save-images", "blocked", "--quiet"});
  EXPECT_EQ(blocked.status, 6) << blocked.err;
  EXPECT_THAT(blocked.err, HasSubstr("--save-images: cannot make"));
}

#ifdef S2SIM_TEST_VIDEO
TEST_F(Runner, VideoWritesACamerasFramesAtItsRate) {
  write_camera_scene(dir_ / "cam");
  const Result r = run({"cam", "--duration", "1", "--video", "eye.mp4", "--quiet"});
  ASSERT_EQ(r.status, 0) << r.err;
  const s2sim::test::Decoded d = s2sim::test::decode(dir_ / "eye.mp4");
  EXPECT_EQ(d.width, 64);
  EXPECT_EQ(d.height, 48);
  EXPECT_EQ(d.frames, 25) << d.codec;  // 1 s at the camera's 40 ms
}
#endif

TEST_F(Runner, VideoNeedsOneCameraImageNamedWhenThereAreSeveral) {
  write_camera_scene(dir_ / "two",
                     "<camera><ID value='back'/><rot_deg x='0' y='0' z='180'/>"
                     "<frame width='32' height='24'/></camera>");
  Result r = run({"two", "--duration", "0.1", "--video", "v.mp4", "--quiet"});
  EXPECT_EQ(r.status, 4) << r.err;
  EXPECT_THAT(r.err, HasSubstr("several camera images; name one with --video-image"));
  EXPECT_THAT(r.err, HasSubstr("robots/rig/sensors/back/rgb"));
  r = run({"two", "--duration", "0.1", "--video", "v.mp4", "--video-image",
           "robots/rig/sensors/eye/depth", "--quiet"});
  EXPECT_EQ(r.status, 4) << r.err;
  EXPECT_THAT(r.err, HasSubstr("not a colour image"));
  r = run({"two", "--duration", "0.1", "--video-image", "robots/rig/sensors/eye/rgb"});
  EXPECT_EQ(r.status, 4) << r.err;
  EXPECT_THAT(r.err, HasSubstr("--video-image chooses the camera image of --video"));
}

}  // namespace
