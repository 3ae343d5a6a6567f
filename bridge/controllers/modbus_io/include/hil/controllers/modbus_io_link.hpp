// SPDX-License-Identifier: MIT
#pragma once
// A Modbus/TCP digital I/O terminal on the I/O image: ModbusIoLink reads discrete inputs and
// coils into image bits once per controller cycle (IoSource) and writes image bits (outputs,
// markers) to coils when they change (IoSink), through a ModbusIoBus (simulated terminal or
// libmodbus on a worker thread).
//
// When the terminal does not answer (decision, docs/controllers.md "Modbus I/O"): a link is
// healthy while its last poll was answered, no newer attempt failed and the inputs are at most
// `stale_after` old. Otherwise the inputs it owns read 0 (the de-energised state of a 24 V input:
// an NC limit switch then reads active, the fail-safe side), its status bit (if any) reads 0, and
// a fault is latched: code `modbus:<n>` (the exception code, or 257 timeout, 258 connection lost,
// 259 connect failed, 260 invalid response; 257 as well when the data is only too old) with a
// text naming the link and the terminal. A stale input never keeps its last value. When polls are
// answered again the inputs follow the terminal again; the fault stays latched (fault_count()
// counts the outages) until reset(). Until the first answer the inputs read 0 without a fault,
// for at most `stale_after` (then: fault).
// Thread: the cycle thread (IoImage calls read/write); configuration before the run.

#include <cstdint>
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include "hil/controllers/io_image.hpp"
#include "hil/controllers/modbus_io_bus.hpp"
#include "hil/core/fault.hpp"
#include "hil/modbus/bit_plan.hpp"

namespace hil::controllers {

struct ModbusIoBit {
  modbus::BitRef ref;  ///< coil or discrete input (outputs: coils only)
  BitAddress bit;      ///< image bit
};

struct ModbusIoLinkConfig {
  std::string name = "modbus";                           ///< for messages, e.g. "io_links[1]"
  std::vector<ModbusIoBit> inputs;                       ///< terminal -> image
  std::vector<ModbusIoBit> outputs;                      ///< image -> coils
  Duration stale_after{std::chrono::milliseconds(120)};  ///< older inputs are not valid
  std::optional<BitAddress> status_bit;                  ///< set to 1 while the link is healthy
};

/// The read and write plans of a link's bit lists. Errors: see modbus::make_bit_plan.
struct ModbusIoPlans {
  modbus::BitPlan reads;
  modbus::BitPlan writes;
};
[[nodiscard]] std::expected<ModbusIoPlans, std::string> make_io_plans(const ModbusIoLinkConfig& config);

class ModbusIoLink final : public IoSource, public IoSink {
 public:
  /// `plans` from make_io_plans(config); `bus` was built on the same plans.
  ModbusIoLink(ModbusIoLinkConfig config, ModbusIoPlans plans, std::unique_ptr<ModbusIoBus> bus);

  /// IoSource: fetch the newest poll and write the inputs (0 while not healthy).
  void read(TimePoint now, IoImage& image) noexcept override;
  /// IoSink: hand the output bits to the bus (written when changed).
  void write(TimePoint now, const IoImage& image) noexcept override;

  [[nodiscard]] bool healthy() const noexcept { return healthy_; }
  /// The latched fault (empty until the first outage); reset() clears it.
  [[nodiscard]] const Fault& fault() const noexcept { return fault_; }
  /// Outages so far (healthy -> not healthy after the start, or no answer at the start).
  [[nodiscard]] std::uint64_t fault_count() const noexcept { return fault_count_; }
  void reset() noexcept { fault_ = {}; }
  [[nodiscard]] const ModbusIoStatus& status() const noexcept { return status_; }
  [[nodiscard]] const ModbusIoLinkConfig& config() const noexcept { return config_; }
  [[nodiscard]] ModbusIoBus& bus() noexcept { return *bus_; }

 private:
  void raise(modbus::ModbusError error) noexcept;

  ModbusIoLinkConfig config_;
  ModbusIoPlans plans_;
  std::unique_ptr<ModbusIoBus> bus_;
  std::vector<std::uint8_t> inputs_;   ///< flattened read blocks
  std::vector<std::uint8_t> outputs_;  ///< flattened write blocks
  ModbusIoStatus status_;
  bool healthy_ = false;
  bool faulted_ = false;  ///< currently in an outage (fault_count_ counted it)
  Fault fault_;
  std::uint64_t fault_count_ = 0;
};

}  // namespace hil::controllers
