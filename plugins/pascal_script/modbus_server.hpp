#pragma once
/// \file
/// The script's Modbus/TCP server (SimTwo's Modbus page, simtwo-script-api.md §4): a listening
/// TCP port (S2SIM_MODBUS_PORT), served at each script tick, holding 65536 coils, 65536 discrete
/// inputs and 65536 holding registers. The script sets inputs and reads coils (setModbusInput,
/// getModbusCoil...); clients read inputs (2), read and write coils (1, 5, 15) and holding
/// registers (3, 6, 16). Other function codes get exception 1, addresses past the end
/// exception 2, counts beyond the protocol's exception 3.

#include <array>
#include <cstdint>
#include <string>
#include <vector>

namespace s2sim::pascal {

class ModbusServer {
 public:
  static constexpr int kSize = 65536;
  ModbusServer();
  ~ModbusServer();
  ModbusServer(const ModbusServer&) = delete;
  ModbusServer& operator=(const ModbusServer&) = delete;
  /// Listens on `port` on all interfaces; false (with `error`) when it cannot.
  bool open(int port, std::string& error);
  bool is_open() const { return listen_fd_ >= 0; }
  /// Accepts waiting clients, answers every complete request they sent; never blocks.
  void serve();

  bool coil(int address) const { return coils_[index(address)] != 0; }
  void set_coil(int address, bool on) { coils_[index(address)] = on ? 1 : 0; }
  bool input(int address) const { return inputs_[index(address)] != 0; }
  void set_input(int address, bool on) { inputs_[index(address)] = on ? 1 : 0; }

  /// The response to one request's PDU (function code and data), without the MBAP header.
  std::string respond(const std::string& pdu);

 private:
  static std::size_t index(int address) { return static_cast<std::size_t>(address & (kSize - 1)); }
  struct Client {
    int fd = -1;
    std::string pending;  // bytes received, not yet a whole frame
  };
  int listen_fd_ = -1;
  std::vector<Client> clients_;
  std::vector<std::uint8_t> coils_, inputs_;
  std::vector<std::uint16_t> registers_;
};

}  // namespace s2sim::pascal
