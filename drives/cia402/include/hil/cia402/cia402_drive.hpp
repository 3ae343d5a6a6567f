// SPDX-License-Identifier: MIT
#pragma once
// hil::Drive for a CiA 402 servo on CANopen. Walks the power state machine (CiA 402-2 §6.3)
// from the statusword and runs one of three operating setups through the PDO layout of
// layout.hpp:
//   csp  cyclic synchronous position: the motion core's set-point every cycle (default);
//   csv  cyclic synchronous velocity: the master closes the position loop, 0x60FF =
//        feed-forward + position_gain * (set-point - actual);
//   pp   the drive generates the trajectory: positioning moves in profile position (PP, the
//        set-point handshake on controlword bit 4 / statusword bit 12, "change set immediately"),
//        velocity moves in profile velocity (PV), stops with halt (bit 8) under 0x6084.
// Homing (HM) on request in every setup. EMCY / 0x603F / heartbeat loss / boot failures become
// the axis's Fault (category "cia402", value = the CiA 402 error code, text from the table).
// Thread: the motion thread, the same one that runs its Network. Non-blocking, never throws.

#include <optional>
#include <string>

#include "hil/cia402/cia402.hpp"
#include "hil/cia402/network.hpp"
#include "hil/core/drive.hpp"

namespace hil::cia402 {

/// How the drive is commanded (see the file comment).
enum class OperatingSetup : std::uint8_t { csp, csv, pp };
[[nodiscard]] std::string_view to_string(OperatingSetup s) noexcept;

struct DriveOptions {
  std::string name;                            ///< "canopen:vbus/5"
  OperatingSetup setup = OperatingSetup::csp;  ///< pp needs the profile objects mapped (AxisOptions::profile_objects)
  double csv_position_gain_per_s = 100.0;      ///< csv: master-side position loop gain (1/s)
  bool homing = true;                          ///< accepts DriveRequest::home (mode 6 with the node's 0x6098 method)
  Duration homing_timeout{std::chrono::seconds(30)};
  Duration stale_after{std::chrono::milliseconds(50)};  ///< feedback older than this counts as lost
  /// After request(fault_reset) the drive reports not_ready (no fault) while it walks the
  /// fault-reset edge, for at most this long; a fault that is still there afterwards is reported
  /// again ("fault reset refused").
  Duration reset_timeout{std::chrono::milliseconds(200)};
};

class Cia402Drive final : public Drive {
 public:
  /// The node must already be added to `network.master()` (make_axis_node_config).
  Cia402Drive(Network& network, canopen::NodeId node, DriveOptions options);
  ~Cia402Drive() override;

  [[nodiscard]] std::string_view name() const noexcept override { return options_.name; }
  [[nodiscard]] DriveCapabilities capabilities() const noexcept override;
  void read(const CycleTime& cycle) override;
  void write(const CycleTime& cycle, const DriveCommand& command) override;
  [[nodiscard]] const DriveFeedback& feedback() const noexcept override { return feedback_; }
  bool request(DriveRequest r) override;

  [[nodiscard]] canopen::NodeId node() const noexcept { return node_; }
  [[nodiscard]] std::uint16_t statusword() const noexcept { return statusword_; }
  [[nodiscard]] std::uint16_t controlword() const noexcept { return controlword_; }

  // Network callbacks.
  void on_boot(std::error_code ec);
  void on_emcy(std::uint16_t code, std::uint8_t error_register);
  void on_heartbeat_lost(Duration consumer_time);
  void on_heartbeat_resumed();

 private:
  void set_fault(std::error_code code, std::string text);
  /// pp: controlword bits, mode and profile objects for `move` (PP / PV / halt).
  Mode write_profile(const DriveMove& move, std::uint16_t& cwv, canopen::ObjectDictionary& img);

  Network& network_;
  canopen::NodeId node_;
  DriveOptions options_;
  DriveFeedback feedback_;
  DriveState goal_ = DriveState::switch_on_disabled;
  std::uint16_t statusword_ = 0;
  std::uint16_t controlword_ = 0;
  std::uint16_t emcy_code_ = 0;
  bool heartbeat_lost_ = false;
  bool booted_ = false;
  std::error_code boot_error_;
  bool homing_requested_ = false;
  bool homing_started_ = false;
  TimePoint homing_deadline_{};
  std::optional<TimePoint> last_feedback_;
  DriveState raw_state_ = DriveState::not_ready;  ///< from the statusword, before reset masking
  bool reset_pending_ = false;
  bool fault_latched_ = false;  ///< the drive reported a fault: disabled and reported until fault_reset
  std::optional<TimePoint> reset_deadline_;
  // pp set-point handshake: the move whose set-point is being handed over, and how far.
  enum class SetPoint : std::uint8_t { waiting, raised, acknowledged };
  std::uint32_t set_point_id_ = 0;
  SetPoint set_point_ = SetPoint::acknowledged;
  Mode profile_mode_ = Mode::profile_position;  ///< the profile mode last commanded (halt stays in it)
};

}  // namespace hil::cia402
