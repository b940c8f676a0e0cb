#pragma once
// Loopback UDP for the script tests: an address, and a client socket on a free port.

#include <arpa/inet.h>
#include <netinet/in.h>
#include <sys/socket.h>

#include <cstdint>

namespace s2sim::test {

/// The loopback address at `port`.
inline sockaddr_in loopback(int port) {
  sockaddr_in a{};
  a.sin_family = AF_INET;
  a.sin_addr.s_addr = htonl(INADDR_LOOPBACK);
  a.sin_port = htons(static_cast<std::uint16_t>(port));
  return a;
}

/// A non-blocking UDP socket on an ephemeral loopback port (`port`); -1 when none could be
/// bound.
inline int loopback_socket(int& port) {
  const int fd = ::socket(AF_INET, SOCK_DGRAM | SOCK_NONBLOCK, 0);
  sockaddr_in me = loopback(0);
  socklen_t len = sizeof me;
  if (fd < 0 || ::bind(fd, reinterpret_cast<sockaddr*>(&me), sizeof me) != 0 ||
      ::getsockname(fd, reinterpret_cast<sockaddr*>(&me), &len) != 0)
    return -1;
  port = ntohs(me.sin_port);
  return fd;
}

}  // namespace s2sim::test
