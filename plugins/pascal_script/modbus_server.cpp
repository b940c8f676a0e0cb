#include "modbus_server.hpp"

#include <arpa/inet.h>
#include <netinet/in.h>
#include <sys/socket.h>
#include <unistd.h>
#include <cerrno>
#include <cstring>

namespace s2sim::pascal {
namespace {

int word_at(const std::string& s, std::size_t at) {
  return (static_cast<unsigned char>(s[at]) << 8) | static_cast<unsigned char>(s[at + 1]);
}
void put_word(std::string& s, int v) {
  s += static_cast<char>((v >> 8) & 0xFF);
  s += static_cast<char>(v & 0xFF);
}
std::string exception(int function, int code) {
  return {static_cast<char>(function | 0x80), static_cast<char>(code)};
}

}  // namespace

ModbusServer::ModbusServer() : coils_(kSize, 0), inputs_(kSize, 0), registers_(kSize, 0) {}

ModbusServer::~ModbusServer() {
  for (const Client& c : clients_)
    ::close(c.fd);
  if (listen_fd_ >= 0) ::close(listen_fd_);
}

bool ModbusServer::open(int port, std::string& error) {
  listen_fd_ = ::socket(AF_INET, SOCK_STREAM | SOCK_NONBLOCK | SOCK_CLOEXEC, 0);
  if (listen_fd_ < 0) {
    error = std::strerror(errno);
    return false;
  }
  const int yes = 1;
  ::setsockopt(listen_fd_, SOL_SOCKET, SO_REUSEADDR, &yes, sizeof yes);
  sockaddr_in addr{};
  addr.sin_family = AF_INET;
  addr.sin_addr.s_addr = htonl(INADDR_ANY);
  addr.sin_port = htons(static_cast<std::uint16_t>(port));
  if (::bind(listen_fd_, reinterpret_cast<sockaddr*>(&addr), sizeof addr) != 0 ||
      ::listen(listen_fd_, 8) != 0) {
    error = std::strerror(errno);
    ::close(listen_fd_);
    listen_fd_ = -1;
    return false;
  }
  return true;
}

void ModbusServer::serve() {
  if (listen_fd_ < 0) return;
  for (;;) {
    const int fd = ::accept4(listen_fd_, nullptr, nullptr, SOCK_NONBLOCK | SOCK_CLOEXEC);
    if (fd < 0) break;
    clients_.push_back({fd, {}});
  }
  for (std::size_t k = 0; k < clients_.size();) {
    Client& c = clients_[k];
    bool closed = false;
    char buf[4096];
    for (;;) {
      const ssize_t n = ::recv(c.fd, buf, sizeof buf, 0);
      if (n > 0) {
        c.pending.append(buf, static_cast<std::size_t>(n));
        continue;
      }
      closed = n == 0 || (errno != EAGAIN && errno != EWOULDBLOCK);
      break;
    }
    // MBAP header: transaction (2), protocol 0 (2), length of what follows (2), unit (1).
    while (c.pending.size() >= 8) {
      const std::size_t length = static_cast<std::size_t>(word_at(c.pending, 4));
      if (word_at(c.pending, 2) != 0 || length < 2 || length > 254) {  // not Modbus/TCP
        closed = true;
        break;
      }
      if (c.pending.size() < 6 + length) break;
      const std::string pdu = c.pending.substr(7, length - 1);
      const std::string reply = respond(pdu);
      std::string frame = c.pending.substr(0, 4);
      put_word(frame, static_cast<int>(reply.size() + 1));
      frame += c.pending[6];  // the unit, echoed
      frame += reply;
      c.pending.erase(0, 6 + length);
      if (::send(c.fd, frame.data(), frame.size(), MSG_NOSIGNAL) !=
          static_cast<ssize_t>(frame.size()))
        closed = true;
    }
    if (closed) {
      ::close(c.fd);
      clients_.erase(clients_.begin() + static_cast<std::ptrdiff_t>(k));
    } else {
      ++k;
    }
  }
}

std::string ModbusServer::respond(const std::string& pdu) {
  const int function = static_cast<unsigned char>(pdu[0]);
  auto need = [&](std::size_t bytes) { return pdu.size() >= bytes; };
  switch (function) {
    case 1:    // read coils
    case 2: {  // read discrete inputs
      if (!need(5)) return exception(function, 3);
      const int start = word_at(pdu, 1), count = word_at(pdu, 3);
      if (count < 1 || count > 2000) return exception(function, 3);
      if (start + count > kSize) return exception(function, 2);
      const auto& bits = function == 1 ? coils_ : inputs_;
      std::string r{static_cast<char>(function), static_cast<char>((count + 7) / 8)};
      for (int i = 0; i < count; i += 8) {
        int byte = 0;
        for (int b = 0; b < 8 && i + b < count; ++b)
          if (bits[static_cast<std::size_t>(start + i + b)]) byte |= 1 << b;
        r += static_cast<char>(byte);
      }
      return r;
    }
    case 3: {  // read holding registers
      if (!need(5)) return exception(function, 3);
      const int start = word_at(pdu, 1), count = word_at(pdu, 3);
      if (count < 1 || count > 125) return exception(function, 3);
      if (start + count > kSize) return exception(function, 2);
      std::string r{static_cast<char>(function), static_cast<char>(2 * count)};
      for (int i = 0; i < count; ++i)
        put_word(r, registers_[static_cast<std::size_t>(start + i)]);
      return r;
    }
    case 5: {  // write single coil: FF00 on, 0000 off
      if (!need(5)) return exception(function, 3);
      const int value = word_at(pdu, 3);
      if (value != 0xFF00 && value != 0) return exception(function, 3);
      coils_[static_cast<std::size_t>(word_at(pdu, 1))] = value != 0;
      return pdu.substr(0, 5);
    }
    case 6:  // write single register
      if (!need(5)) return exception(function, 3);
      registers_[static_cast<std::size_t>(word_at(pdu, 1))] =
          static_cast<std::uint16_t>(word_at(pdu, 3));
      return pdu.substr(0, 5);
    case 15: {  // write multiple coils
      if (!need(6)) return exception(function, 3);
      const int start = word_at(pdu, 1), count = word_at(pdu, 3);
      const int bytes = static_cast<unsigned char>(pdu[5]);
      if (count < 1 || count > 1968 || bytes != (count + 7) / 8 ||
          !need(6 + static_cast<std::size_t>(bytes)))
        return exception(function, 3);
      if (start + count > kSize) return exception(function, 2);
      for (int i = 0; i < count; ++i)
        coils_[static_cast<std::size_t>(start + i)] =
            (static_cast<unsigned char>(pdu[6 + static_cast<std::size_t>(i / 8)]) >> (i % 8)) & 1;
      return pdu.substr(0, 5);
    }
    case 16: {  // write multiple registers
      if (!need(6)) return exception(function, 3);
      const int start = word_at(pdu, 1), count = word_at(pdu, 3);
      const int bytes = static_cast<unsigned char>(pdu[5]);
      if (count < 1 || count > 123 || bytes != 2 * count ||
          !need(6 + static_cast<std::size_t>(bytes)))
        return exception(function, 3);
      if (start + count > kSize) return exception(function, 2);
      for (int i = 0; i < count; ++i)
        registers_[static_cast<std::size_t>(start + i)] =
            static_cast<std::uint16_t>(word_at(pdu, 6 + 2 * static_cast<std::size_t>(i)));
      return pdu.substr(0, 5);
    }
    default:
      return exception(function, 1);
  }
}

}  // namespace s2sim::pascal
