// SPDX-License-Identifier: MIT
#pragma once
// The one drive interface. Every transport (CiA 402 over CANopen, Modbus register drives,
// open-loop step/dir, serial legacy controllers, the simulated plant) implements it; the
// motion core never knows which bus is behind an axis.
//
// Cycle contract (ros2_control style): once per cycle, on the motion thread, the axis calls
//   read(cycle)  -> feedback() is the freshest consistent image,
//   write(cycle, command) -> the command and any pending request go out.
// Both are non-blocking and never throw; transports whose I/O blocks (libmodbus, serial)
// run it off the cycle thread and expose the latest image with its age.

#include <cstdint>
#include <memory>
#include <string>
#include <string_view>

#include "hil/core/clock.hpp"
#include "hil/core/fault.hpp"

namespace hil {

/// Where a cycle is in time. `period` is the nominal cycle period.
struct CycleTime {
  TimePoint now{};
  Duration period{std::chrono::milliseconds(1)};
};

/// Power state in CiA 402 terms (CiA 402-2 §6.3). Other transports map onto these:
/// a step/dir stage is `switch_on_disabled` while reset, `operation_enabled` when enabled and ready.
enum class DriveState : std::uint8_t {
  not_ready,  ///< Not ready to switch on (booting, no communication yet)
  switch_on_disabled,
  ready_to_switch_on,
  switched_on,
  operation_enabled,
  quick_stop_active,
  fault_reaction_active,
  fault,
};
[[nodiscard]] std::string_view to_string(DriveState s) noexcept;

/// What the cyclic command means.
enum class CommandMode : std::uint8_t {
  position,  ///< cyclic synchronous position (CSP; step/dir; a register drive's target position)
  velocity,  ///< cyclic synchronous velocity (CSV)
};

/// The move in progress, for drives that generate the trajectory themselves
/// (DriveCapabilities::drive_profile: CiA 402 profile position / profile velocity, a legacy
/// controller's positioning block). Cyclic drives ignore it.
struct DriveMove {
  enum class Kind : std::uint8_t {
    hold,      ///< stand still; a drive still moving brakes under `deceleration` (CiA 402 halt)
    position,  ///< go to `target_inc` at up to `velocity`
    velocity,  ///< run at the signed `velocity`
  };
  Kind kind = Kind::hold;
  std::uint32_t id = 0;  ///< changes with every new move: the drive starts a new set-point
  std::int64_t target_inc = 0;
  double velocity_inc_per_s = 0.0;  ///< position: profile velocity (> 0); velocity: signed target
  double acceleration_inc_per_s2 = 0.0;
  double deceleration_inc_per_s2 = 0.0;
};

/// One cycle's set-point, in drive increments. The motion core fills all fields; a drive uses
/// what its mode needs (velocity/acceleration are feed-forward in position mode; `move` is what
/// a drive-profile drive executes, `position_inc` then being the motion core's reference).
struct DriveCommand {
  CommandMode mode = CommandMode::position;
  std::int64_t position_inc = 0;
  double velocity_inc_per_s = 0.0;
  double acceleration_inc_per_s2 = 0.0;
  DriveMove move{};
  /// Digital outputs of the drive, CiA 402 0x60FE sub 1 layout (bit 0 set brake, 1..15 reserved,
  /// 16..31 manufacturer specific). A drive applies only the bits of
  /// DriveCapabilities::digital_output_mask; the others are ignored.
  std::uint32_t digital_outputs = 0;
};

/// Requests progress over the following cycles (a CiA 402 drive walks its state machine, a
/// step/dir stage pulses its reset line for 100 ms); feedback().state shows the outcome.
enum class DriveRequest : std::uint8_t {
  enable,       ///< to operation_enabled
  disable,      ///< to switch_on_disabled (power off)
  quick_stop,   ///< drive-side quick stop, then quick_stop_active / switch_on_disabled
  fault_reset,  ///< acknowledge a fault (rising edge where the spec asks for one)
  home,         ///< drive-side homing / reference-point run with the drive's configured method
};
[[nodiscard]] std::string_view to_string(DriveRequest r) noexcept;

struct DriveCapabilities {
  bool closed_loop = true;    ///< false: actual position is the commanded one (open-loop step/dir)
  bool velocity_mode = true;  ///< accepts CommandMode::velocity
  bool homing = false;        ///< accepts DriveRequest::home
  /// Generates the trajectory itself from DriveCommand::move (CiA 402 PP/PV). The axis then
  /// supervises the end position (in-position, standstill), not the path: the drive watches its
  /// own following error and reports a violation as its fault.
  bool drive_profile = false;
  Duration min_period{};  ///< shortest cycle period the transport can serve (0 = any)
  /// DriveFeedback::digital_inputs is read from the drive (CiA 402 0x60FD, simulated switches).
  bool digital_inputs = false;
  /// The DriveCommand::digital_outputs bits the drive applies (CiA 402 0x60FE sub 2 bit mask as
  /// configured); 0 = no digital outputs.
  std::uint32_t digital_output_mask = 0;
};

/// Bits of DriveFeedback::digital_inputs (CiA 402-2 object 0x60FD): 1 = active (the drive applies
/// the switch polarity). Bits 4..15 are reserved, 16..31 manufacturer specific.
namespace digital_input {
inline constexpr std::uint32_t negative_limit = 1u << 0;
inline constexpr std::uint32_t positive_limit = 1u << 1;
inline constexpr std::uint32_t home_switch = 1u << 2;
inline constexpr std::uint32_t interlock = 1u << 3;
}  // namespace digital_input

struct DriveFeedback {
  DriveState state = DriveState::not_ready;
  std::int64_t position_inc = 0;
  double velocity_inc_per_s = 0.0;
  bool referenced = false;  ///< position is referenced (homed); false after lost synchronisation
  bool homing_active = false;
  Fault fault;     ///< set while state is fault / fault_reaction_active
  Duration age{};  ///< age of the freshest data in this image (transport staleness)
  /// Digital inputs, CiA 402 0x60FD layout (namespace digital_input); 0 when the drive has none
  /// (DriveCapabilities::digital_inputs).
  std::uint32_t digital_inputs = 0;
};

class Drive {
 public:
  virtual ~Drive() = default;

  /// Human name for logs ("canopen:can0/5", "modbus:127.0.0.1:1502/1", "sim:x").
  [[nodiscard]] virtual std::string_view name() const noexcept = 0;
  [[nodiscard]] virtual DriveCapabilities capabilities() const noexcept = 0;

  /// Refresh feedback() from the transport. Motion thread; non-blocking; never throws.
  virtual void read(const CycleTime& cycle) = 0;
  /// Send `command` and progress pending requests. Motion thread; non-blocking; never throws.
  virtual void write(const CycleTime& cycle, const DriveCommand& command) = 0;

  [[nodiscard]] virtual const DriveFeedback& feedback() const noexcept = 0;

  /// Ask for a transition. Returns false (and changes nothing) when the drive cannot do it at
  /// all (e.g. `home` without homing support); otherwise it progresses over the next cycles.
  virtual bool request(DriveRequest r) = 0;
};

using DrivePtr = std::unique_ptr<Drive>;

}  // namespace hil
