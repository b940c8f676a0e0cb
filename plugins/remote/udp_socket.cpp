#include "udp_socket.hpp"

#include <cerrno>
#include <cmath>
#include <cstring>

#include <arpa/inet.h>
#include <fcntl.h>
#include <poll.h>
#include <sys/socket.h>
#include <unistd.h>

namespace s2sim::links {

UdpSocket::~UdpSocket() {
  if (fd_ >= 0) ::close(fd_);
}

void UdpSocket::bind(const std::string& address, int port, bool allow_non_local,
                     const Location& where) {
  sockaddr_in local{};
  local.sin_family = AF_INET;
  if (port < 0 || port > 65535)
    throw Error(ErrorKind::scene, where,
                "port must be from 0 to 65535, got " + std::to_string(port));
  local.sin_port = htons(static_cast<std::uint16_t>(port));
  if (::inet_pton(AF_INET, address.c_str(), &local.sin_addr) != 1)
    throw Error(ErrorKind::scene, where,
                "address must be a numeric IPv4 address such as 127.0.0.1, got '" + address + "'");
  const bool loopback = (ntohl(local.sin_addr.s_addr) >> 24) == 127;
  if (!loopback && !allow_non_local)
    throw Error(ErrorKind::scene, where,
                "address '" + address +
                    "' is not a loopback address: anyone on that network could drive the robot; "
                    "set allow_remote='1' to serve it anyway");
  fd_ = ::socket(AF_INET, SOCK_DGRAM, 0);
  if (fd_ < 0)
    throw Error(ErrorKind::plugin, where,
                std::string("cannot open a UDP socket: ") + std::strerror(errno));
  ::fcntl(fd_, F_SETFL, ::fcntl(fd_, F_GETFL) | O_NONBLOCK);
  // Datagrams wait here between two control periods: room for a burst (best effort, the
  // system caps it at net.core.rmem_max; what overflows is dropped and counted by the system).
  const int receive_buffer_bytes = 4 << 20;
  ::setsockopt(fd_, SOL_SOCKET, SO_RCVBUF, &receive_buffer_bytes, sizeof receive_buffer_bytes);
  if (::bind(fd_, reinterpret_cast<const sockaddr*>(&local), sizeof local) != 0)
    throw Error(
        ErrorKind::plugin, where,
        "cannot bind UDP " + address + ":" + std::to_string(port) + ": " + std::strerror(errno));
  socklen_t len = sizeof local;
  ::getsockname(fd_, reinterpret_cast<sockaddr*>(&local), &len);
  port_ = ntohs(local.sin_port);
}

long UdpSocket::receive(unsigned char* buffer, std::size_t capacity, double timeout_s,
                        sockaddr_in* from) {
  if (timeout_s > 0) {
    pollfd p{fd_, POLLIN, 0};
    const int ms = static_cast<int>(std::ceil(timeout_s * 1000.0));
    if (::poll(&p, 1, ms) <= 0) return -1;
  }
  socklen_t len = sizeof *from;
  // MSG_TRUNC: the datagram's real size, so that an oversized one is seen as such.
  const ssize_t got =
      ::recvfrom(fd_, buffer, capacity, MSG_TRUNC, reinterpret_cast<sockaddr*>(from), &len);
  return got < 0 ? -1 : static_cast<long>(got);
}

bool UdpSocket::send(const unsigned char* data, std::size_t size, const sockaddr_in& to) {
  const ssize_t sent =
      ::sendto(fd_, data, size, MSG_DONTWAIT, reinterpret_cast<const sockaddr*>(&to), sizeof to);
  return sent == static_cast<ssize_t>(size);
}

void UdpSocket::set_send_buffer(int bytes) {
  ::setsockopt(fd_, SOL_SOCKET, SO_SNDBUF, &bytes, sizeof bytes);
}

}  // namespace s2sim::links
