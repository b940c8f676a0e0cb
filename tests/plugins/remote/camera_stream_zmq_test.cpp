// The `camera_stream` controller's ZeroMQ transport (plugins/remote/camera_stream.cpp,
// docs/remote.md "Camera streaming"): a SUB socket here gets raw frames, 32-bit BGRA with the
// bottom row first, each the camera's rgb image; the endpoint's checks.
#include <s2sim/kernel/simulation.hpp>

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <chrono>
#include <cstdint>
#include <filesystem>
#include <fstream>
#include <string>
#include <thread>
#include <vector>
#include "common/gradient_renderer.hpp"
#include "common/temp_dir.hpp"

#include <zmq.h>

namespace s2sim {
namespace {

namespace fs = std::filesystem;
using ::testing::HasSubstr;

constexpr const char* kRgb = "robots/rig/sensors/eye/rgb";

fs::path write_scene(const std::string& name, const std::string& stream) {
  const fs::path dir = test::process_temp_dir() / name;
  fs::remove_all(dir);
  fs::create_directories(dir);
  std::ofstream(dir / "scene.xml")
      << "<?xml version=\"1.0\" ?>\n<scene><robot><ID name='rig'/><body file='rig.xml'/>"
         "</robot>\n"
      << stream << "\n</scene>\n";
  std::ofstream(dir / "rig.xml") << R"(<?xml version="1.0" ?>
<robot>
  <solids>
    <cuboid><ID value='base'/><mass value='1'/><size x='0.2' y='0.2' z='0.1'/>
      <pos x='0' y='0' z='0.05'/></cuboid>
  </solids>
  <shells>
    <camera><ID value='eye'/><size x='0.02' y='0.02' z='0.02'/><pos x='0' y='0' z='0.2'/>
      <frame decimation='4' width='64' height='48'/></camera>
  </shells>
</robot>
)";
  return dir;
}

SimulationOptions options() {
  SimulationOptions o;
  o.plugin_path = {fs::path(S2SIM_PLUGIN_DIR)};
  return o;
}

TEST(CameraStreamZmq, SubscribersGetRawBgraFramesBottomRowFirst) {
  auto sim = Simulation::load(
      write_scene(
          "zmq", "<plugin kind='camera_stream' id='stream' image='" + std::string(kRgb) +
                     "' transport='both' port='9' zmq_endpoint='tcp://127.0.0.1:*' zmq_queue='100' "
                     "announce='0'/>"),
      options());
  test::render_gradients(*sim);
  const int port = static_cast<int>(sim->signal("controllers/stream/zmq_port"));
  ASSERT_GT(port, 0);
  void* context = zmq_ctx_new();
  void* sub = zmq_socket(context, ZMQ_SUB);
  const int hwm = 1000;  // keep every frame of the run here (and zmq_queue there)
  zmq_setsockopt(sub, ZMQ_RCVHWM, &hwm, sizeof hwm);
  zmq_setsockopt(sub, ZMQ_SUBSCRIBE, "", 0);
  ASSERT_EQ(zmq_connect(sub, ("tcp://127.0.0.1:" + std::to_string(port)).c_str()), 0);
  // A subscription reaches the publisher some time after connecting; frames sent before it
  // are not for this subscriber. One frame at a time, each waited for.
  std::this_thread::sleep_for(std::chrono::milliseconds(300));
  const Image& rgb = sim->image(kRgb);
  std::vector<std::uint8_t> frame(static_cast<std::size_t>(rgb.width_px) * rgb.height_px * 4 + 1);
  int got = 0;
  for (int k = 1; k <= 5; ++k) {
    sim->run_until(0.04 * k + 0.001);  // one more camera frame
    int size = -1;
    for (int tries = 0; tries < 200 && size < 0; ++tries) {
      size = zmq_recv(sub, frame.data(), frame.size(), ZMQ_DONTWAIT);
      if (size < 0) std::this_thread::sleep_for(std::chrono::milliseconds(5));
    }
    ASSERT_EQ(size, rgb.width_px * rgb.height_px * 4) << "frame " << k;
    ++got;
    for (int y = 0; y < rgb.height_px; ++y)
      for (int x = 0; x < rgb.width_px; ++x) {
        const std::uint8_t* in = rgb.row(rgb.height_px - 1 - y) + 3 * x;
        const std::uint8_t* out =
            frame.data() + (static_cast<std::size_t>(y) * rgb.width_px + x) * 4;
        ASSERT_EQ(out[0], in[2]);
        ASSERT_EQ(out[1], in[1]);
        ASSERT_EQ(out[2], in[0]);
        ASSERT_EQ(out[3], 255);
      }
  }
  EXPECT_EQ(got, 5);
  EXPECT_GE(sim->signal("controllers/stream/zmq_frames"), 5);
  EXPECT_EQ(sim->signal("controllers/stream/zmq_dropped"), 0);
  EXPECT_GE(sim->signal("controllers/stream/frames"), 5);  // the UDP stream too (to port 9)
  // The first pixel is the bottom left: no red, full green.
  EXPECT_EQ(frame[2], 0);
  EXPECT_EQ(frame[1], 255);
  zmq_close(sub);
  zmq_ctx_term(context);
}

std::string load_error(const std::string& name, const std::string& stream) {
  try {
    Simulation::load(write_scene(name, stream), options());
  } catch (const Error& e) {
    return e.what();
  }
  return "";
}

TEST(CameraStreamZmq, EndpointsAreCheckedWithTheirPlace) {
  const std::string base =
      "<plugin kind='camera_stream' id='stream' announce='0' image='" + std::string(kRgb) + "' ";
  EXPECT_THAT(load_error("z1", base + "transport='zmq' zmq_endpoint='tcp://*:0'/>"),
              HasSubstr("@zmq_endpoint: 'tcp://*:0' is not on this machine"));
  EXPECT_THAT(load_error("z2", base + "transport='zmq' zmq_endpoint='tcp://127.0.0.1:x'/>"),
              HasSubstr("@zmq_endpoint: cannot bind ZeroMQ"));
  EXPECT_THAT(load_error("z3", base + "zmq_endpoint='tcp://127.0.0.1:*'/>"),
              HasSubstr("@zmq_endpoint: zmq_endpoint is for the ZeroMQ stream"));
  EXPECT_THAT(load_error("z4", base + "transport='zmq' quality='50'/>"),
              HasSubstr("@quality: quality is for the UDP stream"));
  EXPECT_THAT(load_error("z5", base + "transport='tcp'/>"), HasSubstr("@transport"));
  EXPECT_THAT(load_error("z6", base + "transport='zmq' zmq_queue='0'/>"),
              HasSubstr("@zmq_queue: must be an integer from 1 to 1000"));
}

}  // namespace
}  // namespace s2sim
