// The `camera_stream` controller (docs/remote.md, "Camera streaming"): SimTwo's camera
// streaming of a camera's rgb image, by one or both of its transports:
//   udp: JPEG-compressed and sent in chunks, each datagram five little-endian int32 (0x5241,
//        the image number, the JPEG's size, the number of datagrams, this one's index) and up
//        to `chunk_bytes` of the JPEG;
//   zmq: raw on a ZeroMQ PUB socket, one message a frame: 32-bit BGRA pixels, the bottom row
//        first (SimTwo's OpenGL snapshot order), alpha 255.
// An image is sent once, when its frame counter has moved since the last one sent.
//
// It only sends: nothing it does reaches the simulated world, and it declares no state. Its
// image number and last frame seen live in members (as the remote link's connection does): a
// restored snapshot or a reset does not roll the image numbers back, so a receiver always sees
// them increase. Its counters are published signals; the drops depend on the system's
// buffers, so they are no part of a run's determinism.
#include "jpeg_encoder.hpp"
#include "kinds.hpp"
#include "udp_socket.hpp"
#include "zmq_publisher.hpp"

#include <s2sim/sdk.hpp>

#include <arpa/inet.h>

#include <algorithm>
#include <cstdio>
#include <cstring>
#include <memory>
#include <stdexcept>
#include <string>
#include <vector>

namespace s2sim::links {

namespace {

constexpr std::int32_t kImageId = 0x5241;  // SimTwo's RemoteImage.id
constexpr int kHeaderBytes = 5 * 4;
constexpr int kMaxChunkBytes = 512;  // SimTwo's MTU: RemoteImage.data's size
constexpr int kSimTwoDestinationPort = 9898;
constexpr int kZmqHighWaterMark = 2;  // SimTwo's ZMQ_SNDHWM

/// Whether a ZeroMQ endpoint stays on this machine: ipc://, or tcp:// on a 127.x.x.x address.
bool local_endpoint(const std::string& e) {
  if (e.rfind("ipc://", 0) == 0) return true;
  if (e.rfind("tcp://", 0) != 0) return false;
  const std::string rest = e.substr(6);
  const std::size_t colon = rest.rfind(':');
  const std::string host = colon == std::string::npos ? rest : rest.substr(0, colon);
  in_addr a{};
  return ::inet_pton(AF_INET, host.c_str(), &a) == 1 && (ntohl(a.s_addr) >> 24) == 127;
}

void put_i32(std::uint8_t* out, std::uint32_t v) {
  for (int i = 0; i < 4; ++i)
    out[i] = static_cast<std::uint8_t>(v >> (8 * i));
}

class CameraStream final : public Component {
 public:
  void configure(ConfigureContext& ctx) override {
    const Params& p = ctx.params();
    ctx.refuse_unread_attributes();
    image_name_ = p.text("image");
    image_ = ctx.image(image_name_);
    const std::string transport = p.choice("transport", {"udp", "zmq", "both"}, "udp");
    udp_ = transport != "zmq";
    const bool zmq = transport != "udp";
    const bool allow_remote = p.boolean("allow_remote", false);
    for (const char* a : {"host", "port", "source_port", "quality", "chunk_bytes"})
      if (!udp_ && p.has(a))
        throw Error(ErrorKind::scene, p.where(a),
                    std::string(a) + " is for the UDP stream: give transport='udp' or 'both'");
    for (const char* a : {"zmq_endpoint", "zmq_queue"})
      if (!zmq && p.has(a))
        throw Error(ErrorKind::scene, p.where(a),
                    std::string(a) + " is for the ZeroMQ stream: give transport='zmq' or 'both'");
    if (udp_) configure_udp(p, allow_remote);
    if (zmq) {
      const std::string endpoint = p.text("zmq_endpoint", "tcp://127.0.0.1:9899");
      if (!local_endpoint(endpoint) && !allow_remote)
        throw Error(ErrorKind::scene, p.where("zmq_endpoint"),
                    "'" + endpoint +
                        "' is not on this machine (ipc://, or tcp:// on a 127.x.x.x address): "
                        "the camera's images would leave it unencrypted; set allow_remote='1' "
                        "to publish them anyway");
      const int queue = p.integer_in("zmq_queue", kZmqHighWaterMark, 1, 1000);
      zmq_ = std::make_unique<ZmqPublisher>(endpoint, queue, p.where("zmq_endpoint"));
    }
    if (p.has("period_s"))
      ctx.set_schedule(Stage::control, p.number("period_s", Range::positive()));

    port_ = ctx.declare_signal("port", "1");
    frames_ = ctx.declare_signal("frames", "1");
    skipped_ = ctx.declare_signal("skipped_frames", "1");
    datagrams_ = ctx.declare_signal("datagrams", "1");
    dropped_ = ctx.declare_signal("dropped", "1");
    bytes_ = ctx.declare_signal("bytes", "byte");
    number_ = ctx.declare_signal("image_number", "1");
    zmq_port_ = ctx.declare_signal("zmq_port", "1");
    zmq_frames_ = ctx.declare_signal("zmq_frames", "1");
    zmq_dropped_ = ctx.declare_signal("zmq_dropped", "1");
    where_ = p.where("image");
    announce_ = p.boolean("announce", true);
  }

  void configure_udp(const Params& p, bool allow_remote) {
    quality_ = p.integer_in("quality", 75, 1, 100);
    chunk_ = p.integer_in("chunk_bytes", kMaxChunkBytes, 1, kMaxChunkBytes);
    host_ = p.text("host", "127.0.0.1");
    dest_port_ = p.integer_in("port", kSimTwoDestinationPort, 1, 65535);
    const int source_port = p.integer_in("source_port", 0, 0, 65535);
    to_.sin_family = AF_INET;
    to_.sin_port = htons(static_cast<std::uint16_t>(dest_port_));
    if (::inet_pton(AF_INET, host_.c_str(), &to_.sin_addr) != 1)
      throw Error(ErrorKind::scene, p.where("host"),
                  "host must be a numeric IPv4 address such as 127.0.0.1, got '" + host_ + "'");
    const bool loopback = (ntohl(to_.sin_addr.s_addr) >> 24) == 127;
    if (!loopback && !allow_remote)
      throw Error(ErrorKind::scene, p.where("host"),
                  "host '" + host_ +
                      "' is not a loopback address: the camera's images would leave this "
                      "machine unencrypted; set allow_remote='1' to send them anyway");
    socket_.bind(loopback ? "127.0.0.1" : "0.0.0.0", source_port, !loopback,
                 p.where("source_port"));
    // A frame's datagrams leave in one burst: room for a few frames of them.
    socket_.set_send_buffer(4 << 20);
    datagram_.assign(static_cast<std::size_t>(kHeaderBytes + chunk_), 0);
  }

  // The image's size is known once every component is configured.
  void initialize(StepContext& ctx) override {
    const Image& img = ctx.image(image_);
    if (img.format != PixelFormat::rgb8)
      throw Error(ErrorKind::scene, where_,
                  "image '" + image_name_ + "' is not rgb8: only a camera's rgb image streams");
    if (width_ != img.width_px || height_ != img.height_px) {
      width_ = img.width_px;
      height_ = img.height_px;
      if (udp_) {
        try {
          encoder_ = std::make_unique<JpegEncoder>(width_, height_, quality_);
        } catch (const std::runtime_error& e) {
          throw Error(ErrorKind::plugin, where_, e.what());
        }
      }
      if (zmq_) bgra_.assign(static_cast<std::size_t>(width_) * height_ * 4, 255);
      if (announce_ && udp_)
        std::fprintf(stderr,
                     "s2sim camera_stream: %s (%dx%d) as JPEG (quality %d) to udp %s:%d from "
                     "port %d\n",
                     image_name_.c_str(), width_, height_, quality_, host_.c_str(), dest_port_,
                     socket_.port());
      if (announce_ && zmq_)
        std::fprintf(stderr, "s2sim camera_stream: %s (%dx%d) as BGRA, bottom row first, on %s\n",
                     image_name_.c_str(), width_, height_, zmq_->endpoint().c_str());
    }
    if (zmq_) ctx.publish(zmq_port_, zmq_->port());
    ctx.publish(port_, socket_.port());
    last_frame_ = img.frame;
  }

  void update(StepContext& ctx) override {
    const Image& img = ctx.image(image_);
    if (img.frame == 0 || img.frame == last_frame_) return;
    last_frame_ = img.frame;
    if (zmq_) publish_raw(ctx, img);
    if (udp_) send_jpeg(ctx, img);
  }

 private:
  void publish_raw(StepContext& ctx, const Image& img) {
    for (int y = 0; y < height_; ++y) {
      const std::uint8_t* in = img.row(height_ - 1 - y);
      std::uint8_t* out = bgra_.data() + static_cast<std::size_t>(y) * width_ * 4;
      for (int x = 0; x < width_; ++x, in += 3, out += 4) {
        out[0] = in[2];
        out[1] = in[1];
        out[2] = in[0];
      }
    }
    count(ctx, zmq_->send(bgra_.data(), bgra_.size()) ? zmq_frames_ : zmq_dropped_);
  }

  void send_jpeg(StepContext& ctx, const Image& img) {
    const std::size_t size = encoder_->encode(img);
    if (size == 0 || size > 0x7fffffff) {
      count(ctx, skipped_);
      return;
    }
    const std::uint8_t* jpeg = encoder_->data();
    const std::size_t chunk = static_cast<std::size_t>(chunk_);
    const std::size_t packets = (size + chunk - 1) / chunk;
    ++number_sent_;
    std::uint8_t* out = datagram_.data();
    put_i32(out, kImageId);
    put_i32(out + 4, number_sent_);
    put_i32(out + 8, static_cast<std::uint32_t>(size));
    put_i32(out + 12, static_cast<std::uint32_t>(packets));
    std::size_t sent = 0;
    for (std::size_t i = 0; i < packets; ++i) {
      const std::size_t n = std::min(chunk, size - i * chunk);
      put_i32(out + 16, static_cast<std::uint32_t>(i));
      std::memcpy(out + kHeaderBytes, jpeg + i * chunk, n);
      if (!socket_.send(out, kHeaderBytes + n, to_)) break;  // the rest would not go either
      ++sent;
    }
    ctx.publish(datagrams_, ctx.signal(datagrams_) + static_cast<double>(sent));
    if (sent < packets) {
      ctx.publish(dropped_, ctx.signal(dropped_) + static_cast<double>(packets - sent));
      count(ctx, skipped_);
    } else {
      count(ctx, frames_);
    }
    ctx.publish(bytes_, static_cast<double>(size));
    ctx.publish(number_, static_cast<double>(number_sent_));
  }

  static void count(StepContext& ctx, SignalHandle h) { ctx.publish(h, ctx.signal(h) + 1.0); }

  std::string image_name_, host_;
  ImageHandle image_;
  Location where_;
  int quality_ = 75, chunk_ = kMaxChunkBytes, dest_port_ = kSimTwoDestinationPort;
  bool announce_ = true, udp_ = true;
  UdpSocket socket_;
  std::unique_ptr<ZmqPublisher> zmq_;
  std::vector<std::uint8_t> bgra_;  // the ZeroMQ frame
  sockaddr_in to_{};
  std::unique_ptr<JpegEncoder> encoder_;
  int width_ = 0, height_ = 0;
  std::vector<std::uint8_t> datagram_;
  SignalHandle port_, frames_, skipped_, datagrams_, dropped_, bytes_, number_;
  SignalHandle zmq_port_, zmq_frames_, zmq_dropped_;

  // The stream (see the file comment).
  std::uint64_t last_frame_ = 0;
  std::uint32_t number_sent_ = 0;
};

}  // namespace

s2sim_kind_entry camera_stream_kind() {
  return S2SIM_KIND("camera_stream", Category::controller, CameraStream);
}

}  // namespace s2sim::links
