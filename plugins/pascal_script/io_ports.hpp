#pragma once
/// \file
/// The script's UDP socket and serial port (simtwo-script-api.md §3.7). UDP: one socket,
/// opened at the script's first UDP call (a script that never uses UDP opens nothing), bound to
/// the listening port (SimTwo's 9808 by default, S2SIM_UDP_PORT to change it) on loopback
/// unless S2SIM_UDP_ADDRESS names another address; a datagram per WriteUDPData; the bytes received
/// go both to a stream (ReadUDPData, UDPDataRead) and to a list of datagrams (ReadUDPPacket).
/// Serial: the tty or pseudo-terminal named by S2SIM_COM_PORT, raw 8N1; without one the port is
/// closed, as in SimTwo: writes do nothing and reads return ''.

#include <deque>
#include <string>

namespace s2sim::pascal {

class UdpPort {
 public:
  ~UdpPort();
  /// Opens the socket and binds it to `address`:`port`; false with `error` set (the socket
  /// then only sends) when that fails. Once: later calls return what the first did.
  bool open(const std::string& address, int port, std::string& error);
  bool opened() const { return opened_; }
  void send(const std::string& ip, int port, const std::string& data);
  /// The bytes received since the last call, datagrams concatenated (at most the last 16 MiB).
  /// SimTwo keeps them apart from its list of datagrams: taking them leaves receive_packet's.
  std::string receive();
  /// The oldest datagram not yet read ('' when none).
  std::string receive_packet();
  /// How many datagrams wait to be read.
  int packet_count();
  int bound_port() const { return bound_port_; }

 private:
  void poll();
  bool opened_ = false;
  bool bound_to_loopback_ = false;
  int fd_ = -1;
  int other_fd_ = -1;  // sends to other machines when fd_ listens on loopback only
  int bound_port_ = 0;
  std::deque<std::string> packets_;  // received, not yet read by ReadUDPPacket
  std::string stream_;               // received, not yet taken by receive()
};

class SerialPort {
 public:
  ~SerialPort();
  /// Opens `device` raw and non-blocking; false with `error` set when it cannot.
  bool open(const std::string& device, std::string& error);
  bool is_open() const { return fd_ >= 0; }
  void write(const std::string& data);
  std::string read();

 private:
  int fd_ = -1;
};

}  // namespace s2sim::pascal
