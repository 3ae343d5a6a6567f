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
// Digital I/O where the layout routes it: 0x60FD into DriveFeedback::digital_inputs (TPDO or
// SDO poll), DriveCommand::digital_outputs masked by the layout's bit mask into 0x60FE:1 (RPDO
// or SDO write on change). Homing (HM) on request in every setup. EMCY / 0x603F / heartbeat loss / boot failures become
// the axis's Fault (category "cia402", value = the CiA 402 error code, text from the table).
// Thread: the motion thread, the same one that runs its Network. Non-blocking, never throws.

#include <map>
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include "hil/cia402/cia402.hpp"
#include "hil/cia402/layout.hpp"
#include "hil/cia402/network.hpp"
#include "hil/core/drive.hpp"

namespace hil::cia402 {

struct DriveOptions {
  std::string name;                            ///< "canopen:vbus/5"
  OperatingSetup setup = OperatingSetup::csp;  ///< must match AxisOptions::setup of the node's configuration
  double csv_position_gain_per_s = 100.0;      ///< csv: master-side position loop gain (1/s)
  bool homing = true;                          ///< accepts DriveRequest::home (mode 6 with the node's 0x6098 method)
  Duration homing_timeout{std::chrono::seconds(30)};
  Duration stale_after{std::chrono::milliseconds(50)};  ///< feedback older than this counts as lost
  /// After request(fault_reset) the drive reports not_ready (no fault) while it walks the
  /// fault-reset edge, for at most this long; a fault that is still there afterwards is reported
  /// again ("fault reset refused").
  Duration reset_timeout{std::chrono::milliseconds(200)};
  /// How each object is reached (make_axis_config). Empty (no routes): every object in a PDO, as
  /// for the simulated drive.
  AxisLayout layout{};
  Duration poll_period{std::chrono::milliseconds(100)};  ///< SDO-polled objects: one upload per period
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
  /// Mode in effect: 0x6061 when the layout has it, else the commanded mode once it has stood
  /// for a few cycles and its SDO write (if any) is done.
  Mode mode_display(const canopen::ObjectDictionary& img) const;
  [[nodiscard]] bool routed(std::uint16_t index, std::uint8_t sub = 0) const noexcept;
  /// SDO side of the layout: one poll per period, writes of changed set-points.
  void sdo_service(TimePoint now, canopen::ObjectDictionary& img);
  [[nodiscard]] bool sdo_writes_settled(const canopen::ObjectDictionary& img) const;

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
  // SDO side of the layout.
  std::vector<ObjectKey> polled_, written_;
  std::size_t next_poll_ = 0;
  TimePoint next_poll_at_{};
  bool poll_in_flight_ = false;
  std::map<std::uint32_t, std::vector<std::uint8_t>> last_written_;  ///< by index << 8 | sub
  int writes_in_flight_ = 0;
  Mode commanded_mode_ = Mode::no_mode;
  int commanded_mode_cycles_ = 0;
  std::shared_ptr<bool> alive_ = std::make_shared<bool>(true);  ///< SDO completions after destruction are ignored
};

}  // namespace hil::cia402
