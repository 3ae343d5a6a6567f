// SPDX-License-Identifier: MIT
#pragma once
// Emulated Rexroth CLM1.4 serial side (manual §9.2): program memory (3000 lines), parameters
// (writable only in Parameter mode, validated when leaving it), variables V000..V999 (V600..V999
// writable), logic task lines (1000), status queries, interface commands and the status-01
// error telegram. One object is one station; Clm14Line puts up to 32 of them on one RS-485 line.
// Pure state machine: a received line in, the reply bytes out. No I/O, no clock.

#include <array>
#include <expected>
#include <map>
#include <memory>
#include <string>
#include <string_view>
#include <utility>
#include <vector>

#include <nlohmann/json_fwd.hpp>

#include "hil/core/clock.hpp"
#include "hil/serial/clm14/device_data.hpp"
#include "hil/serial/clm14/telegram.hpp"

namespace hil::mocks::legacy {

/// Mode inputs I0.00.0 (Parameter) and I0.00.1 (Auto), manual §7.1.
enum class ClmMode { parameter, manual, automatic };

class Clm14Station {
 public:
  static constexpr int program_lines = 3000;
  static constexpr int logic_lines = 1000;
  static constexpr int variables = 1000;

  /// `station` 0 = RS-232 (station character must be a space); 1..32 = RS-485 station number.
  Clm14Station(int station, std::shared_ptr<const serial::clm14::DeviceData> data, int axes = 2);

  /// Handle one received line (without CR LF). Returns the bytes to send; empty = stay silent
  /// (wrong station, broadcast, or nothing to confirm).
  [[nodiscard]] std::string on_line(std::string_view line);

  /// A line that arrived with a character error (parity, framing, overrun): the addressed
  /// station answers "RS Format Error" (02), others stay silent.
  [[nodiscard]] std::string on_damaged_line(std::string_view line);

  /// Change the mode inputs. Leaving Parameter mode validates every parameter (fault 02 and
  /// status 60 name the first invalid one).
  void set_mode(ClmMode m);
  [[nodiscard]] ClmMode mode() const noexcept { return mode_; }
  [[nodiscard]] int station() const noexcept { return station_; }
  /// Current fault code (hex per manual §6; 0x00/0x01 = none).
  [[nodiscard]] int fault() const noexcept { return fault_; }
  /// True when state changed since the last take_dirty() (for debounced persistence).
  [[nodiscard]] bool take_dirty() noexcept { return std::exchange(dirty_, false); }

  /// RS-485 response delay: field DDD (ms) of B005, "H C NN E DDD RRR" (manual: B003/B005 "RS
  /// Interface Functions"). Zero on RS-232 (the field applies in RS-485 mode only) or when the
  /// field is missing or not a number.
  [[nodiscard]] hil::Duration response_delay() const;

  [[nodiscard]] const std::string& program_line(int n) const { return program_.at(static_cast<std::size_t>(n)); }
  [[nodiscard]] std::string parameter(std::string_view number) const;

  [[nodiscard]] nlohmann::json to_json() const;
  /// Restore from to_json(); unknown keys are ignored, bad entries reported.
  [[nodiscard]] std::expected<void, std::string> from_json(const nlohmann::json& j);

 private:
  [[nodiscard]] std::string reply(char lead, std::string_view body) const;
  [[nodiscard]] std::string error(int code) const;
  [[nodiscard]] std::string confirm() const;
  [[nodiscard]] bool checksum_required() const;
  [[nodiscard]] bool confirmation_on() const;

  std::string on_program(const serial::clm14::Telegram& t);
  std::string on_parameter(const serial::clm14::Telegram& t);
  std::string on_variable(const serial::clm14::Telegram& t);
  std::string on_logic(const serial::clm14::Telegram& t);
  std::string on_status(const serial::clm14::Telegram& t);
  std::string on_command(const serial::clm14::Telegram& t);
  void reset_parameters();
  void validate_parameters();

  int station_;
  char station_char_;
  std::shared_ptr<const serial::clm14::DeviceData> data_;
  int axes_;
  ClmMode mode_ = ClmMode::manual;
  bool checksum_off_latched_ = false;  // checksum check state frozen while in Parameter mode
  int fault_ = 0x00;
  std::string invalid_item_;  // status 60: "0 B002"
  bool running_ = false;
  std::array<bool, 4> axis_enabled_{true, true, true, true};
  std::vector<std::string> program_;  // body after "Nbbbb ": "NOP   ", "AEA Q1.00.3 1 "
  std::vector<std::string> logic_;
  std::vector<std::string> variables_;
  std::map<std::string, std::string, std::less<>> parameters_;
  std::vector<std::string> parameter_order_;
  bool dirty_ = false;
};

}  // namespace hil::mocks::legacy
