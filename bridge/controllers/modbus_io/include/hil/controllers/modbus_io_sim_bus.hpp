// SPDX-License-Identifier: MIT
#pragma once
// The simulated I/O terminal as a ModbusIoBus (scenario `bus: sim`): an in-process
// hil::mocks::IoTerminal inside a ModbusDriveServer, which optionally listens on TCP so that an
// independent peer (pymodbus, mbpoll, a PLC) can read and write the same coils and inputs while
// the run goes on. The link reads the terminal's tables directly under the server's device mutex
// (a short lock, no network), on the cycle's time, so a run on virtual time stays deterministic:
//  - a poll every `poll` of cycle time (the first at the first fetch) reads the read plan's
//    blocks; a block that is not in the terminal fails the poll with exception 02, as FC 1/2
//    would;
//  - put() writes the changed write blocks at once (as FC 5/15 acknowledged within the cycle);
//  - set_answering(false) models a terminal that stopped answering (power, cable): a poll
//    started then fails with `timeout` one `response_timeout` later, writes do not land, and
//    when it answers again every output block is written anew.
// Thread: fetch/put/set_answering on the cycle thread; the server's I/O thread serves peers.

#include <expected>
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include "hil/controllers/modbus_io_bus.hpp"
#include "hil/mocks/modbus_server.hpp"

namespace hil::controllers {

struct SimModbusIoBusConfig {
  Duration poll{std::chrono::milliseconds(10)};
  Duration response_timeout{std::chrono::milliseconds(100)};
};

/// The simulated terminal itself: its size, unit and whether peers may reach it on TCP.
struct SimTerminalOptions {
  std::uint16_t coils = 64;
  std::uint16_t discrete_inputs = 64;
  std::uint8_t unit = 1;
  bool listen = false;
  std::string listen_host = "127.0.0.1";
  std::uint16_t listen_port = 0;  ///< 0: any free port (see SimModbusIoBus::server().port())
};

class SimModbusIoBus final : public ModbusIoBus {
 public:
  /// Build the terminal and, with `options.listen`, start serving it. Error: why it cannot listen.
  [[nodiscard]] static std::expected<std::unique_ptr<SimModbusIoBus>, std::string> create(
      const SimTerminalOptions& options, const modbus::BitPlan& reads, const modbus::BitPlan& writes,
      SimModbusIoBusConfig config);
  /// `server` serves an IoTerminal (started or not: started only when peers are to connect).
  SimModbusIoBus(std::unique_ptr<mocks::ModbusDriveServer> server, const modbus::BitPlan& reads,
                 const modbus::BitPlan& writes, SimModbusIoBusConfig config);

  void fetch(TimePoint now, std::span<std::uint8_t> inputs, ModbusIoStatus& status) noexcept override;
  void put(TimePoint now, std::span<const std::uint8_t> outputs) noexcept override;
  [[nodiscard]] const std::string& describe() const noexcept override { return describe_; }

  void set_answering(bool answering) noexcept { answering_ = answering; }
  [[nodiscard]] mocks::ModbusDriveServer& server() noexcept { return *server_; }

 private:
  void poll(TimePoint now, std::span<std::uint8_t> inputs) noexcept;

  std::unique_ptr<mocks::ModbusDriveServer> server_;
  std::vector<modbus::BitBlock> reads_;
  std::vector<modbus::BitBlock> writes_;
  SimModbusIoBusConfig config_;
  std::string describe_;
  bool answering_ = true;
  bool started_ = false;
  TimePoint start_{};
  TimePoint next_poll_{};
  std::optional<TimePoint> attempt_;  ///< a poll waiting for an answer that does not come
  TimePoint stamp_{};
  ModbusIoStatus status_;
  modbus::ModbusError write_error_ = modbus::ModbusError::none;  ///< the last put()'s refusal
  std::vector<std::uint8_t> written_;                            ///< outputs as last written
  bool rewrite_all_ = true;                                      ///< first write, and after the terminal answers again
};

}  // namespace hil::controllers
