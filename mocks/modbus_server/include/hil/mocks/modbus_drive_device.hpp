// SPDX-License-Identifier: MIT
#pragma once
// The simulated drive behind the Modbus drive server: a register table laid out by a profile,
// the profile's device-side state machine (CiA 402 FSA or vendor bits) and the plant model.
// Requests are served by libmodbus (ModbusResponder) against the device's register table; the
// device reacts to control-word writes at once and steps the plant when told. Not thread-safe: ModbusDriveServer
// serialises access.

#include <cstdint>
#include <span>

#include "hil/core/clock.hpp"
#include "hil/core/drive.hpp"
#include "hil/core/fault.hpp"
#include "hil/mocks/modbus_responder.hpp"
#include "hil/mocks/plant.hpp"
#include "hil/modbus/profile.hpp"
#include "hil/modbus/request_handler.hpp"

namespace hil::mocks {

struct DriveDeviceConfig {
  PlantConfig plant{};
  double quick_stop_deceleration_inc_per_s2 = 1.0e8;
  double standstill_velocity_inc_per_s = 10.0;  ///< |v| below this ends quick_stop_active
  std::int64_t target_window_inc = 10;          ///< CiA 402 status bit 10 "target reached"
};

class DriveDevice {
 public:
  DriveDevice(modbus::Profile profile, DriveDeviceConfig config = {});

  /// Serve one request ADU (see ModbusResponder::handle); control-word writes take effect at once.
  modbus::HandleResult handle(std::span<const std::uint8_t> adu, std::span<std::uint8_t> out,
                              const modbus::HandlerOptions& options) noexcept;

  /// Advance the plant and the state machine by `dt` and refresh the feedback registers.
  void step(Duration dt) noexcept;

  /// Start/stop a plant fault (the drive enters fault; the fault-code register names it).
  void inject(PlantFault fault, bool active) noexcept;

  [[nodiscard]] DriveState state() const noexcept { return state_; }
  [[nodiscard]] const Plant& plant() const noexcept { return plant_; }
  [[nodiscard]] const modbus::Profile& profile() const noexcept { return profile_; }
  [[nodiscard]] modbus::RegisterTable& table() noexcept { return table_; }
  /// The fault-code register value for a plant fault (CiA 402 error codes for cia402 profiles:
  /// encoder 0x7305, not_ready 0x3100, following 0x8611; the plant fault number otherwise).
  [[nodiscard]] std::uint32_t fault_code_for(PlantFault f) const noexcept;

 private:
  [[nodiscard]] std::int64_t read_field(modbus::FieldRole r) const noexcept;
  void write_field(modbus::FieldRole r, std::int64_t raw) noexcept;
  void apply_control(bool stopped) noexcept;
  /// Homing (profiles with modes.homing): a rising edge of control word bit 4 in the homing mode
  /// while enabled homes on the current position (CiA 402 methods 35/37: it becomes 0).
  void run_homing() noexcept;
  [[nodiscard]] bool in_homing_mode() const noexcept;
  void publish() noexcept;

  modbus::Profile profile_;
  DriveDeviceConfig config_;
  modbus::RegisterTable table_;
  ModbusResponder responder_;
  Plant plant_;
  DriveState state_ = DriveState::not_ready;
  std::uint16_t prev_cw_ = 0;
  std::uint32_t latched_fault_code_ = 0;
  double hold_position_inc_ = 0.0;
  double qs_velocity_ = 0.0;
  bool prev_start_bit_ = false;   ///< control word bit 4 at the last look (homing start edge)
  bool homing_attained_ = false;  ///< status bits 12 + 10 while the homing mode stays selected
};

}  // namespace hil::mocks
