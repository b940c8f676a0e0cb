#pragma once
/// \file
/// The links' UDP socket (the remote link's, the camera stream's): bound at configure (loopback
/// unless allowed otherwise), non-blocking, closed with the component.

#include <s2sim/error.hpp>

#include <cstddef>
#include <cstdint>
#include <string>

#include <netinet/in.h>

namespace s2sim::links {

class UdpSocket {
 public:
  UdpSocket() = default;
  UdpSocket(const UdpSocket&) = delete;
  UdpSocket& operator=(const UdpSocket&) = delete;
  ~UdpSocket();

  /// Binds `address`:`port` (port 0: one the system picks). A non-loopback address is refused
  /// unless `allow_non_local`. Throws s2sim::Error located at `where`.
  void bind(const std::string& address, int port, bool allow_non_local, const Location& where);
  /// The port actually bound.
  int port() const { return port_; }

  /// Waits up to `timeout_s` (0: not at all) for a datagram. Returns its full size (which may
  /// exceed `capacity`: the copy is then cut), or -1 when none came.
  long receive(unsigned char* buffer, std::size_t capacity, double timeout_s, sockaddr_in* from);
  /// Best effort, never waiting: a full buffer or an unreachable client is not the
  /// simulation's problem. Returns whether the system took the whole datagram.
  bool send(const unsigned char* data, std::size_t size, const sockaddr_in& to);
  /// Asks for a send buffer of `bytes` (the system caps it at net.core.wmem_max).
  void set_send_buffer(int bytes);

 private:
  int fd_ = -1;
  int port_ = 0;
};

}  // namespace s2sim::links
