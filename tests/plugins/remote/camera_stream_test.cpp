// The `camera_stream` controller (plugins/remote/camera_stream.cpp, docs/remote.md "Camera
// streaming") against a receiver here: a UDP socket on a port the system picks, the datagrams
// reassembled by their SimTwo header, the JPEG decoded with libjpeg and compared with the
// camera's rgb image; and its located errors.
#include <s2sim/kernel/simulation.hpp>

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <map>
#include <string>
#include <vector>
#include "common/gradient_renderer.hpp"
#include "common/temp_dir.hpp"

#include <arpa/inet.h>
#include <jpeglib.h>
#include <sys/socket.h>
#include <unistd.h>

namespace s2sim {
namespace {

namespace fs = std::filesystem;
using ::testing::HasSubstr;

constexpr const char* kRgb = "robots/rig/sensors/eye/rgb";

/// A UDP socket bound to 127.0.0.1 on a port the system picks, read without waiting.
class Receiver {
 public:
  Receiver() {
    fd_ = ::socket(AF_INET, SOCK_DGRAM, 0);
    const int buffer = 8 << 20;  // every datagram of the run waits here until read
    ::setsockopt(fd_, SOL_SOCKET, SO_RCVBUF, &buffer, sizeof buffer);
    sockaddr_in a{};
    a.sin_family = AF_INET;
    a.sin_addr.s_addr = htonl(INADDR_LOOPBACK);
    ::bind(fd_, reinterpret_cast<sockaddr*>(&a), sizeof a);
    socklen_t len = sizeof a;
    ::getsockname(fd_, reinterpret_cast<sockaddr*>(&a), &len);
    port_ = ntohs(a.sin_port);
  }
  Receiver(const Receiver&) = delete;
  Receiver& operator=(const Receiver&) = delete;
  ~Receiver() { ::close(fd_); }
  int port() const { return port_; }
  std::vector<std::vector<std::uint8_t>> drain() {
    std::vector<std::vector<std::uint8_t>> out;
    std::vector<std::uint8_t> buf(65536);
    for (;;) {
      const ssize_t n = ::recv(fd_, buf.data(), buf.size(), MSG_DONTWAIT);
      if (n < 0) break;
      out.emplace_back(buf.begin(), buf.begin() + n);
    }
    return out;
  }

 private:
  int fd_ = -1;
  int port_ = 0;
};

std::int32_t get_i32(const std::uint8_t* p) {
  std::uint32_t v = 0;
  for (int i = 0; i < 4; ++i)
    v |= static_cast<std::uint32_t>(p[i]) << (8 * i);
  return static_cast<std::int32_t>(v);
}

/// The images of the datagrams, by image number; an image missing a chunk is left out.
struct Received {
  std::map<std::int32_t, std::vector<std::uint8_t>> images;
  int bad_headers = 0;
  std::size_t largest_datagram = 0;
};

Received reassemble(const std::vector<std::vector<std::uint8_t>>& datagrams) {
  struct Partial {
    std::int32_t size = 0, packets = 0;
    std::vector<std::uint8_t> bytes;
    std::vector<bool> have;
  };
  Received r;
  std::map<std::int32_t, Partial> partial;
  for (const auto& d : datagrams) {
    r.largest_datagram = std::max(r.largest_datagram, d.size());
    if (d.size() < 20 || get_i32(d.data()) != 0x5241) {
      ++r.bad_headers;
      continue;
    }
    const std::int32_t number = get_i32(d.data() + 4), size = get_i32(d.data() + 8),
                       packets = get_i32(d.data() + 12), index = get_i32(d.data() + 16);
    Partial& p = partial[number];
    if (p.bytes.empty()) {
      p.size = size, p.packets = packets;
      p.bytes.assign(static_cast<std::size_t>(size), 0);
      p.have.assign(static_cast<std::size_t>(packets), false);
    }
    const std::size_t at = static_cast<std::size_t>(index) * 512, n = d.size() - 20;
    if (index < 0 || index >= p.packets || at + n > p.bytes.size()) {
      ++r.bad_headers;
      continue;
    }
    std::memcpy(p.bytes.data() + at, d.data() + 20, n);
    p.have[static_cast<std::size_t>(index)] = true;
  }
  for (auto& [number, p] : partial)
    if (std::find(p.have.begin(), p.have.end(), false) == p.have.end())
      r.images[number] = std::move(p.bytes);
  return r;
}

struct Decoded {
  int width = 0, height = 0, components = 0;
  std::vector<std::uint8_t> rgb;
};

Decoded decode(const std::vector<std::uint8_t>& jpeg) {
  jpeg_decompress_struct cinfo{};
  jpeg_error_mgr err{};
  cinfo.err = jpeg_std_error(&err);
  jpeg_create_decompress(&cinfo);
  jpeg_mem_src(&cinfo, jpeg.data(), static_cast<unsigned long>(jpeg.size()));
  Decoded d;
  if (jpeg_read_header(&cinfo, TRUE) == JPEG_HEADER_OK) {
    cinfo.out_color_space = JCS_RGB;
    jpeg_start_decompress(&cinfo);
    d.width = static_cast<int>(cinfo.output_width);
    d.height = static_cast<int>(cinfo.output_height);
    d.components = cinfo.output_components;
    d.rgb.resize(static_cast<std::size_t>(d.width) * d.height * 3);
    while (cinfo.output_scanline < cinfo.output_height) {
      JSAMPROW row = d.rgb.data() + static_cast<std::size_t>(cinfo.output_scanline) * d.width * 3;
      jpeg_read_scanlines(&cinfo, &row, 1);
    }
    jpeg_finish_decompress(&cinfo);
  }
  jpeg_destroy_decompress(&cinfo);
  return d;
}

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
      <frame decimation='4' width='160' height='120'/></camera>
  </shells>
  <sensors>
    <camera><ID value='deep'/><frame width='16' height='12'/><outputs rgb='0' depth='1'/></camera>
  </sensors>
</robot>
)";
  return dir;
}

SimulationOptions options() {
  SimulationOptions o;
  o.plugin_path = {fs::path(S2SIM_PLUGIN_DIR)};
  return o;
}

std::string stream_element(int port, const std::string& extra = "") {
  return "<plugin kind='camera_stream' id='stream' image='" + std::string(kRgb) + "' port='" +
         std::to_string(port) + "' quality='90' announce='0' " + extra + "/>";
}

TEST(CameraStream, EveryFrameArrivesInSimTwosChunksAndDecodesToTheCamerasImage) {
  Receiver rx;
  auto sim = Simulation::load(write_scene("stream", stream_element(rx.port())), options());
  test::render_gradients(*sim);
  sim->run_until(0.5);
  const Received got = reassemble(rx.drain());
  const double frames = sim->signal("controllers/stream/frames");
  const double camera_frames = sim->signal("robots/rig/sensors/eye/frames");
  EXPECT_GT(frames, 5);
  EXPECT_EQ(frames, camera_frames);  // each camera frame once: the camera's period is longer
  EXPECT_EQ(sim->signal("controllers/stream/dropped"), 0);
  EXPECT_EQ(sim->signal("controllers/stream/skipped_frames"), 0);
  EXPECT_EQ(got.bad_headers, 0);
  EXPECT_LE(got.largest_datagram, 20u + 512u);
  ASSERT_EQ(static_cast<double>(got.images.size()), frames);
  // Numbered from 1, one more each frame (SimTwo's RemoteImage.Number).
  std::int32_t expected = 1;
  for (const auto& [number, bytes] : got.images)
    EXPECT_EQ(number, expected++);
  EXPECT_EQ(sim->signal("controllers/stream/image_number"), frames);
  EXPECT_EQ(sim->signal("controllers/stream/bytes"),
            static_cast<double>(got.images.rbegin()->second.size()));
  EXPECT_GT(sim->signal("controllers/stream/datagrams"), frames);  // several chunks a frame

  const Image& rgb = sim->image(kRgb);
  const Decoded d = decode(got.images.rbegin()->second);
  ASSERT_EQ(d.width, rgb.width_px);
  ASSERT_EQ(d.height, rgb.height_px);
  ASSERT_EQ(d.components, 3);
  double diff = 0;
  for (int y = 0; y < d.height; ++y)
    for (int x = 0; x < 3 * d.width; ++x)
      diff +=
          std::abs(int{d.rgb[static_cast<std::size_t>(y * d.width * 3 + x)]} - int{rgb.row(y)[x]});
  const double mean = diff / (3.0 * d.width * d.height);
  std::printf("mean absolute difference of the decoded JPEG: %.3f levels\n", mean);
  EXPECT_LT(mean, 3.0);
  // Top row first, as the image: the top left is dark, the bottom right red and green.
  EXPECT_LT(d.rgb[0] + d.rgb[1], 20);
  const std::size_t last = d.rgb.size() - 3;
  EXPECT_GT(d.rgb[last], 235);
  EXPECT_GT(d.rgb[last + 1], 235);
}

TEST(CameraStream, AnUnchangedImageIsNotSentAgain) {
  Receiver rx;
  // Every physics step: the camera draws every 40 ms, the stream sends only those.
  auto sim = Simulation::load(
      write_scene("every-step", stream_element(rx.port(), "period_s='0.001'")), options());
  test::render_gradients(*sim);
  sim->run_until(0.2);
  const Received got = reassemble(rx.drain());
  EXPECT_EQ(static_cast<double>(got.images.size()), sim->signal("robots/rig/sensors/eye/frames"));
  EXPECT_EQ(sim->signal("controllers/stream/frames"), sim->signal("robots/rig/sensors/eye/frames"));
}

std::string load_error(const std::string& name, const std::string& stream) {
  try {
    Simulation::load(write_scene(name, stream), options())->run_until(0.01);
  } catch (const Error& e) {
    return e.what();
  }
  return "";
}

TEST(CameraStream, ParametersAreCheckedWithTheirPlace) {
  const std::string base = "<plugin kind='camera_stream' id='stream' announce='0' ";
  const std::string image = "image='" + std::string(kRgb) + "' ";
  struct Case {
    std::string element, attribute, says;
  };
  const Case cases[] = {
      {base + image + "quality='0'/>", "quality", "quality"},
      {base + image + "quality='101'/>", "quality", "101"},
      {base + image + "chunk_bytes='513'/>", "chunk_bytes", "513"},
      {base + image + "port='0'/>", "port", "port"},
      {base + image + "host='localhost'/>", "host", "numeric IPv4"},
      {base + image + "host='192.0.2.1'/>", "host", "allow_remote"},
      {base + "image='robots/rig/sensors/eye/rbg'/>", "", "rbg"},
      {base + "image='robots/rig/sensors/deep/depth'/>", "image", "not rgb8"},
      {base + image + "qualty='50'/>", "qualty", "qualty"},
  };
  int k = 0;
  for (const Case& c : cases) {
    const std::string what = load_error("bad-" + std::to_string(k++), c.element);
    SCOPED_TRACE(c.element);
    EXPECT_THAT(what, HasSubstr("scene.xml"));
    EXPECT_THAT(what, HasSubstr(c.attribute));
    EXPECT_THAT(what, HasSubstr(c.says));
  }
}

}  // namespace
}  // namespace s2sim
