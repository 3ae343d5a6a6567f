// SPDX-License-Identifier: MIT
#pragma once
// Emulated Rexroth CLM1.4 (manual §9.2 on the wire, §5-§7 inside): the serial side (program
// memory, parameters writable only in Parameter mode and validated when leaving it, variables,
// logic task lines, status queries, interface commands, the status-01 error telegram) in front
// of the running controller model (hil::controllers::clm14::Controller) whose axes are simulated
// drives, or real-transport drives in retrofit mode (use_axes()). Every status reply comes from
// the running model. One object is one station; Clm14Line puts up to 32 on one RS-485 line.
// A received line in, the reply bytes out; time only through tick(now). No I/O.

#include <array>
#include <expected>
#include <functional>
#include <map>
#include <memory>
#include <string>
#include <string_view>
#include <utility>
#include <vector>

#include <nlohmann/json_fwd.hpp>

#include "hil/controllers/clm14/controller.hpp"
#include "hil/core/clock.hpp"
#include "hil/core/drive.hpp"
#include "hil/mocks/legacy/clm14_sim_axes.hpp"
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
  /// An empty program line as the device reads it back: "NOP" + the blank operand field's two
  /// spaces (manual §9.2 checksum example "#5N0123 NOP  $45").
  static constexpr std::string_view empty_line = "NOP  ";

  /// `station` 0 = RS-232 (station character must be a space); 1..32 = RS-485 station number.
  Clm14Station(int station, std::shared_ptr<const serial::clm14::DeviceData> data, int axes = 2);

  /// Handle one received line (without CR LF). Returns the bytes to send; empty = stay silent
  /// (wrong station, broadcast, or nothing to confirm).
  [[nodiscard]] std::string on_line(std::string_view line);

  /// A line that arrived with a character error (parity, framing, overrun): the addressed
  /// station answers "RS Format Error" (02), others stay silent.
  [[nodiscard]] std::string on_damaged_line(std::string_view line);

  /// Change the mode inputs (I0.00.0 / I0.00.1) and run one cycle so the mode takes effect.
  /// Leaving Parameter mode validates every parameter (fault 02 and status 60 name the first
  /// invalid one).
  void set_mode(ClmMode m);
  [[nodiscard]] ClmMode mode() const noexcept;
  [[nodiscard]] int station() const noexcept { return station_; }
  /// Current fault code (hex per manual §6; 0x00 = none).
  [[nodiscard]] int fault() const noexcept { return clm_.error(); }

  /// Run the controller's NC cycles up to `now` (at most 5000 per call: a long gap is skipped,
  /// not replayed). The emulator calls it from its idle loop.
  void tick(TimePoint now);
  /// When the next NC cycle is due.
  [[nodiscard]] TimePoint next_cycle() const noexcept { return next_cycle_; }
  /// True once tick() ran (the unit is "powered" on the emulator's clock).
  [[nodiscard]] bool ticking() const noexcept { return started_; }
  /// Retrofit mode: the controller's axes are `ports` (axis 1..4, null = none), advanced once per
  /// NC cycle by `update` after the controller's step. Replaces the simulated drives.
  void use_axes(std::array<controllers::clm14::AxisPort*, 4> ports, std::function<void(const CycleTime&)> update);
  /// Retrofit mode: master encoder `n` (1 or 2) is `port` (a machine axis' actual increments)
  /// instead of the simulated measuring wheel (1) / none (2); null gives it back.
  void use_master_encoder(int n, controllers::clm14::MasterEncoderPort* port);
  /// Whether master encoder 1 is a machine axis (use_master_encoder).
  [[nodiscard]] bool external_master_encoder() const noexcept { return external_me_[0] != nullptr; }
  /// The simulated measuring wheel (master encoder 1, when C002 > 0): the material runs at
  /// `iu_per_s` (0 = stops). False when master encoder 1 is not used or is a machine axis.
  bool set_material_velocity(double iu_per_s) { return external_me_[0] == nullptr && wheel_.set_velocity(iu_per_s); }
  [[nodiscard]] controllers::clm14::Controller& controller() noexcept { return clm_; }
  [[nodiscard]] const controllers::clm14::Controller& controller() const noexcept { return clm_; }
  /// True when state changed since the last take_dirty() (for debounced persistence).
  [[nodiscard]] bool take_dirty() noexcept { return std::exchange(dirty_, false); }

  /// RS-485 response delay: field DDD (ms) of B005, "H C NN E DDD RRR" (manual: B003/B005 "RS
  /// Interface Functions"). Zero on RS-232 (the field applies in RS-485 mode only) or when the
  /// field is missing or not a number.
  [[nodiscard]] hil::Duration response_delay() const;

  /// Program line n as the device sends it after "Nnnnn ": "AEA Q1.00.3 1 ", "NOP  ".
  [[nodiscard]] std::string program_line(int n) const;
  [[nodiscard]] std::string parameter(std::string_view number) const;

  /// The station's state file: parameters, the controller's battery-buffered state
  /// (Controller::to_json, with the status 54 length counters) and the unit's hardware settings
  /// the console made ("hardware": analog inputs AE1..AE4 in mV, the test mode's speed step).
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
  [[nodiscard]] std::string status_content(int n, std::string_view arg, bool& ok, int& error) const;
  void reset_parameters();
  void attach_axes();
  void cycle(TimePoint now);

  int station_;
  char station_char_;
  std::shared_ptr<const serial::clm14::DeviceData> data_;
  int axes_;
  bool checksum_off_latched_ = false;  // checksum check state frozen while in Parameter mode
  std::map<std::string, std::string, std::less<>> parameters_;
  controllers::clm14::Controller clm_;
  Clm14SimAxes sim_;
  Clm14SimWheel wheel_;
  bool external_axes_ = false;
  std::array<controllers::clm14::AxisPort*, 4> external_ports_{};
  std::function<void(const CycleTime&)> external_update_;
  std::array<controllers::clm14::MasterEncoderPort*, 2> external_me_{};
  TimePoint next_cycle_{};
  TimePoint last_save_{};
  bool started_ = false;
  std::vector<std::string> parameter_order_;
  bool dirty_ = false;
  /// The unit's hardware settings last saved (analog inputs AE1..AE4 mV, test speed step) and the
  /// length counters: a change is persisted (hardware at once, the counters about once a second).
  std::array<int, 5> saved_hardware_{};
  std::array<double, 2> saved_lengths_{};
};

}  // namespace hil::mocks::legacy
