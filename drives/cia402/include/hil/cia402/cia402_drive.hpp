// SPDX-License-Identifier: MIT
#pragma once
// hil::Drive for a CiA 402 servo on CANopen. Walks the power state machine (CiA 402-2 §6.3)
// from the statusword, runs CSP/CSV cyclically through the PDO layout of layout.hpp, homing (HM)
// on request, and turns EMCY / 0x603F / heartbeat loss / boot failures into the axis's Fault
// (category "cia402", value = the CiA 402 error code, text from the error-code table).
// Thread: the motion thread, the same one that runs its Network. Non-blocking, never throws.

#include <optional>
#include <string>

#include "hil/cia402/cia402.hpp"
#include "hil/cia402/network.hpp"
#include "hil/core/drive.hpp"

namespace hil::cia402 {

struct DriveOptions {
  std::string name;                       ///< "canopen:vbus/5"
  bool homing = true;                     ///< accepts DriveRequest::home (mode 6 with the node's 0x6098 method)
  Duration homing_timeout{std::chrono::seconds(30)};
  Duration stale_after{std::chrono::milliseconds(50)};  ///< feedback older than this counts as lost
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
};

}  // namespace hil::cia402
