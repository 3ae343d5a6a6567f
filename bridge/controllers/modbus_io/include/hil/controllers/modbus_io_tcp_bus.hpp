// SPDX-License-Identifier: MIT
#pragma once
// A real Modbus/TCP digital I/O terminal as a ModbusIoBus (scenario `bus: "tcp://host:port"`):
// libmodbus' client on one worker thread per link (libmodbus contexts are not thread-safe,
// upstream issue #246), the same pattern as hil::drives::ModbusDrive's free-running mode.
//
// Threads:
//  - the worker connects (with exponential back-off after a failure), and every `poll` (and at
//    once when put() changed an output) writes the output blocks that changed (FC 5 for one
//    coil, FC 15 for several; every block after a (re)connect), then reads the input blocks
//    (FC 1 coils, FC 2 discrete inputs) and publishes them stamped with clock.now() taken when
//    the poll started. After a timeout, lost connection or invalid response the connection is
//    closed (a late reply would be taken for the next request, libmodbus #451) and reopened after
//    the back-off; an exception response keeps it.
//  - the cycle thread calls fetch()/put(): copies under a mutex the worker holds only to copy;
//    never blocks on the network.
// `clock` must be thread-safe (SteadyClock): the worker stamps with it and fetch() measures the
// age with it, whatever time the cycle runs on.

#include <condition_variable>
#include <cstdint>
#include <mutex>
#include <string>
#include <thread>
#include <vector>

#include "hil/controllers/modbus_io_bus.hpp"

namespace hil::controllers {

struct TcpModbusIoBusConfig {
  std::string host = "127.0.0.1";
  std::uint16_t port = 502;
  int unit = 1;
  Duration poll{std::chrono::milliseconds(10)};
  Duration response_timeout{std::chrono::milliseconds(100)};  ///< per request, and the connect timeout
  Duration backoff_min{std::chrono::milliseconds(100)};
  Duration backoff_max{std::chrono::seconds(5)};
};

struct TcpModbusIoStats {
  std::uint64_t polls = 0;
  std::uint64_t write_requests = 0;  ///< FC 5 / FC 15 requests answered
  std::uint64_t errors = 0;
  std::uint64_t connects = 0;
};

class TcpModbusIoBus final : public ModbusIoBus {
 public:
  /// Starts the worker; `clock` must outlive the bus.
  TcpModbusIoBus(TcpModbusIoBusConfig config, const modbus::BitPlan& reads, const modbus::BitPlan& writes,
                 const Clock& clock);
  ~TcpModbusIoBus() override;
  TcpModbusIoBus(const TcpModbusIoBus&) = delete;
  TcpModbusIoBus& operator=(const TcpModbusIoBus&) = delete;

  void fetch(TimePoint now, std::span<std::uint8_t> inputs, ModbusIoStatus& status) noexcept override;
  void put(TimePoint now, std::span<const std::uint8_t> outputs) noexcept override;
  [[nodiscard]] const std::string& describe() const noexcept override { return describe_; }
  /// Any thread.
  [[nodiscard]] TcpModbusIoStats stats() const;

 private:
  void worker();

  TcpModbusIoBusConfig config_;
  std::vector<modbus::BitBlock> reads_;
  std::vector<modbus::BitBlock> writes_;
  const Clock& clock_;
  std::string describe_;
  TimePoint created_;

  mutable std::mutex mutex_;
  std::condition_variable cv_;
  bool stop_ = false;
  std::vector<std::uint8_t> shared_inputs_;
  std::vector<std::uint8_t> shared_outputs_;
  bool outputs_dirty_ = false;
  bool outputs_given_ = false;  ///< put() was called at least once (nothing is written before)
  ModbusIoStatus shared_status_;
  TimePoint stamp_{};
  TcpModbusIoStats stats_;
  std::thread thread_;
};

}  // namespace hil::controllers
