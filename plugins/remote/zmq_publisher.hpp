#pragma once
/// \file
/// The camera stream's ZeroMQ PUB socket (libzmq), bound at configure, sending without ever
/// waiting. Built without libzmq, making one throws saying so.

#include <s2sim/error.hpp>

#include <cstddef>
#include <cstdint>
#include <string>

namespace s2sim::links {

class ZmqPublisher {
 public:
  /// Binds a PUB socket to `endpoint` (`tcp://127.0.0.1:9899`, `tcp://127.0.0.1:*` for a port
  /// the system picks, `ipc:///path`), keeping at most `high_water_mark` messages for a slow
  /// subscriber (ZeroMQ drops the newer ones past it). Throws s2sim::Error located at `where`.
  ZmqPublisher(const std::string& endpoint, int high_water_mark, const Location& where);
  ZmqPublisher(const ZmqPublisher&) = delete;
  ZmqPublisher& operator=(const ZmqPublisher&) = delete;
  ~ZmqPublisher();

  /// The endpoint bound (the port filled in), and its TCP port (0 for another transport).
  const std::string& endpoint() const { return bound_; }
  int port() const { return port_; }
  /// One message of `size` bytes; false when ZeroMQ refused it (it does not wait).
  bool send(const std::uint8_t* data, std::size_t size);

 private:
  void* context_ = nullptr;
  void* socket_ = nullptr;
  std::string bound_;
  int port_ = 0;
};

}  // namespace s2sim::links
