#include "io_ports.hpp"

#include <arpa/inet.h>
#include <fcntl.h>
#include <netinet/in.h>
#include <sys/socket.h>
#include <termios.h>
#include <unistd.h>
#include <cerrno>
#include <cstring>

namespace s2sim::pascal {

UdpPort::~UdpPort() {
  if (fd_ >= 0) ::close(fd_);
  if (other_fd_ >= 0) ::close(other_fd_);
}

bool UdpPort::open(const std::string& address, int port, std::string& error) {
  if (opened_) return bound_port_ != 0;
  opened_ = true;
  sockaddr_in addr{};
  addr.sin_family = AF_INET;
  addr.sin_port = htons(static_cast<std::uint16_t>(port));
  if (::inet_pton(AF_INET, address.c_str(), &addr.sin_addr) != 1) {
    error = "'" + address + "' is not an IPv4 address";
    return false;
  }
  fd_ = ::socket(AF_INET, SOCK_DGRAM | SOCK_NONBLOCK | SOCK_CLOEXEC, 0);
  if (fd_ < 0) {
    error = std::strerror(errno);
    return false;
  }
  if (port < 1 || port > 65535 ||
      ::bind(fd_, reinterpret_cast<sockaddr*>(&addr), sizeof addr) != 0) {
    error = port < 1 || port > 65535 ? "no such port" : std::strerror(errno);
    return false;
  }
  bound_port_ = port;
  bound_to_loopback_ = (ntohl(addr.sin_addr.s_addr) >> 24) == 127;
  return true;
}

void UdpPort::send(const std::string& ip, int port, const std::string& data) {
  if (fd_ < 0) return;
  sockaddr_in to{};
  to.sin_family = AF_INET;
  to.sin_port = htons(static_cast<std::uint16_t>(port));
  if (::inet_pton(AF_INET, ip.c_str(), &to.sin_addr) != 1) return;
  int fd = fd_;
  // A socket bound to loopback cannot reach another machine: those go from a port of their own.
  if (bound_to_loopback_ && (ntohl(to.sin_addr.s_addr) >> 24) != 127) {
    if (other_fd_ < 0) other_fd_ = ::socket(AF_INET, SOCK_DGRAM | SOCK_NONBLOCK | SOCK_CLOEXEC, 0);
    fd = other_fd_;
  }
  if (fd < 0) return;
  (void)::sendto(fd, data.data(), data.size(), 0, reinterpret_cast<sockaddr*>(&to), sizeof to);
}

namespace {
constexpr std::size_t kMaxPackets = 4096;
constexpr std::size_t kMaxStreamBytes = std::size_t{16} << 20;
}  // namespace

void UdpPort::poll() {
  if (fd_ < 0 || bound_port_ == 0) return;
  char buf[65536];
  for (;;) {
    const ssize_t n = ::recv(fd_, buf, sizeof buf, 0);
    if (n < 0) break;
    packets_.emplace_back(buf, static_cast<std::size_t>(n));
    if (packets_.size() > kMaxPackets) packets_.pop_front();  // a script that never reads
    stream_.append(buf, static_cast<std::size_t>(n));
    if (stream_.size() > kMaxStreamBytes) stream_.erase(0, stream_.size() - kMaxStreamBytes);
  }
}

std::string UdpPort::receive() {
  poll();
  std::string all;
  all.swap(stream_);
  return all;
}

std::string UdpPort::receive_packet() {
  poll();
  if (packets_.empty()) return {};
  std::string p = std::move(packets_.front());
  packets_.pop_front();
  return p;
}

int UdpPort::packet_count() {
  poll();
  return static_cast<int>(packets_.size());
}

SerialPort::~SerialPort() {
  if (fd_ >= 0) ::close(fd_);
}

bool SerialPort::open(const std::string& device, std::string& error) {
  fd_ = ::open(device.c_str(), O_RDWR | O_NOCTTY | O_NONBLOCK | O_CLOEXEC);
  if (fd_ < 0) {
    error = std::strerror(errno);
    return false;
  }
  termios t{};
  if (::tcgetattr(fd_, &t) == 0) {
    ::cfmakeraw(&t);
    ::tcsetattr(fd_, TCSANOW, &t);
  }
  return true;
}

void SerialPort::write(const std::string& data) {
  if (fd_ < 0) return;
  std::size_t done = 0;
  while (done < data.size()) {
    const ssize_t n = ::write(fd_, data.data() + done, data.size() - done);
    if (n <= 0) break;
    done += static_cast<std::size_t>(n);
  }
}

std::string SerialPort::read() {
  std::string all;
  if (fd_ < 0) return all;
  char buf[4096];
  for (;;) {
    const ssize_t n = ::read(fd_, buf, sizeof buf);
    if (n <= 0) break;
    all.append(buf, static_cast<std::size_t>(n));
  }
  return all;
}

}  // namespace s2sim::pascal
