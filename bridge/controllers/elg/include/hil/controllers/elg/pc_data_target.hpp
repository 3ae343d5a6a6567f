// SPDX-License-Identifier: MIT
// The ELG's data behind the PC data channel (12.5): what a request reads or writes, and the
// dispatcher that turns a request into a reply with the manual's 3016/3018 rules.
// The target is a virtual interface: the emulator's ELG (MD/SD held as tape text, the running
// gearbox for R parameters, actual values, alarms and service data) and tests implement it.
#pragma once

#include <expected>
#include <optional>
#include <string>
#include <vector>

#include "hil/controllers/elg/pc_data_channel.hpp"

namespace hil::controllers::elg {

enum class DatumKind : std::uint8_t { machine_data, setting_data };

class PcDataTarget {
 public:
  virtual ~PcDataTarget() = default;
  /// Coupling ON: MD and SD are not writable then (the "$" of 12.5).
  [[nodiscard]] virtual bool coupled() const = 0;
  /// An MD or SD as the tape writes it ("180000", "00010010"); nullopt when the number does not exist.
  [[nodiscard]] virtual std::optional<std::string> datum(DatumKind kind, int number) const = 0;
  /// Stores an MD/SD value (tape text). Error: the reason it is invalid (range, format).
  virtual std::expected<void, std::string> store_datum(DatumKind kind, int number, const std::string& value) = 0;
  /// R parameter 0..99 (nullopt: not present).
  [[nodiscard]] virtual std::optional<PcValue> r_parameter(int number) const = 0;
  /// Stores an R parameter; error: the value is out of the parameter's range (3016).
  virtual std::expected<void, std::string> store_r_parameter(int number, const PcValue& value) = 0;
  /// Actual value of axis 1..4 in input units with three decimals; nullopt when not declared.
  [[nodiscard]] virtual std::optional<PcValue> actual_value(int axis) const = 0;
  /// The pending ELG alarms in the order raised.
  [[nodiscard]] virtual std::vector<int> alarms() const = 0;
  /// Service datum 8000..8999; nullopt when not present.
  [[nodiscard]] virtual std::optional<PcValue> service_datum(int number) const = 0;
};

/// Performs one request on `target` (12.5). Never throws; the reply says what happened.
PcReply handle_pc_request(const PcRequest& request, PcDataTarget& target);

}  // namespace hil::controllers::elg
