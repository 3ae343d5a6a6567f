// SPDX-License-Identifier: MIT
#pragma once
// Simulated CiA 402 servo drive on CANopen: a CiA 301 slave whose object dictionary comes from
// the shipped EDS (profiles/canopen/hil_cia402_drive.eds, compiled in), with the CiA 402 power
// state machine, modes CSP, CSV, PP, PV and HM, driven by the simulated plant (mocks/sim_drive).
// Digital inputs 0x60FD from the plant's switches (limit and home switches at mechanical
// positions) and bits a test forces; digital outputs 0x60FE:1 applied through the 0x60FE:2 bit mask.
// Fault injection: CiA 402 error codes, plant faults, following error, slow or missing SDO
// answers, heartbeat loss — in-process through the API, remotely through objects 0x2100..0x2103.
// Runs on any hil::can::Channel: the in-process virtual bus, SocketCAN, socketcand.
// Thread: the channel's executor; step() and the receive handler must run on it.

#include <expected>
#include <memory>
#include <string>
#include <string_view>
#include <vector>

#include "hil/can/channel.hpp"
#include "hil/can/filter.hpp"
#include "hil/canopen/eds.hpp"
#include "hil/canopen/slave.hpp"
#include "hil/cia402/cia402.hpp"
#include "hil/core/config_error.hpp"
#include "hil/core/fault.hpp"
#include "hil/mocks/plant.hpp"
#include "hil/mocks/switches.hpp"

namespace hil::mocks {

/// The EDS text the simulated node is built from (profiles/canopen/hil_cia402_drive.eds).
[[nodiscard]] std::string_view cia402_node_eds() noexcept;

/// Acceptance filter of a node on the predefined connection set (CiA 301 §7.3.5): NMT, SYNC,
/// its SDO request, its guarding RTR and its four RPDOs at 0x200/0x300/0x400/0x500 + id. Like a
/// CAN controller's hardware filter: apply it only while the RPDO COB-IDs stay predefined.
[[nodiscard]] can::FilterSet predefined_filters(canopen::NodeId node);

struct Cia402NodeOptions {
  canopen::NodeId node = 1;
  PlantConfig plant{};
  PlantSwitches switches{};  ///< 0x60FD bits 0..2 from the plant's mechanical position
  canopen::SdoServerOptions sdo{};
  Duration fault_reaction_time{std::chrono::milliseconds(20)};  ///< fault reaction active -> fault
  /// The node's own EDS/DCF text (object dictionary, PDO defaults, identity); empty = the shipped
  /// one. Objects the drive model uses but the EDS lacks take sensible internal values (no
  /// 0x6502: every mode; no 0x6065: no following-error supervision; no 0x6081/0x6083/0x6084/
  /// 0x6085: 100 000 inc/s and 1 000 000 inc/s^2; no 0x6067: a window of 10 increments).
  std::string eds_text{};
  std::string eds_name{};  ///< for messages ("drive.eds")
};

/// Check that `eds_text` can be a simulated node's EDS: it must parse, and hold a statusword
/// and a controlword. The error names the file, line and key (parser) or the missing objects.
[[nodiscard]] std::expected<canopen::DeviceDescription, ConfigError> load_node_eds(std::string_view eds_text,
                                                                                   std::string_view eds_name,
                                                                                   canopen::NodeId node);

struct Cia402NodeStats {
  std::uint64_t syncs = 0;
  std::uint64_t steps = 0;
  std::uint64_t faults = 0;
};

class Cia402Node {
 public:
  /// Attaches to `channel` (which must outlive the node). Throws std::runtime_error if the EDS
  /// fails load_node_eds() (check it first; for the compiled-in one that is a build defect).
  Cia402Node(can::Channel& channel, Cia402NodeOptions options);
  ~Cia402Node();
  Cia402Node(const Cia402Node&) = delete;
  Cia402Node& operator=(const Cia402Node&) = delete;

  /// Power on: boot-up message, pre-operational.
  void start(TimePoint now);
  /// Heartbeat, EMCY, SDO timeouts, event PDOs and the plant between SYNCs. Call every 1 ms or so.
  void step(TimePoint now);
  /// Handle one frame (the channel's receive handler calls this).
  void on_frame(const can::Frame& f, TimePoint now);

  [[nodiscard]] canopen::NodeId node_id() const noexcept { return options_.node; }
  [[nodiscard]] DriveState state() const noexcept { return state_; }
  [[nodiscard]] canopen::NmtState nmt_state() const noexcept { return slave_.state(); }
  [[nodiscard]] Plant& plant() noexcept { return plant_; }
  [[nodiscard]] canopen::ObjectDictionary& od() noexcept { return slave_.od(); }
  [[nodiscard]] const Cia402NodeStats& stats() const noexcept { return stats_; }
  /// The switches behind 0x60FD, and bits a test forces (seen at the next SYNC or step).
  [[nodiscard]] SimulatedInputs& inputs() noexcept { return inputs_; }
  /// The physical outputs: 0x60FE:1 masked by 0x60FE:2 (0x60FE:1 alone when the EDS has no
  /// bit mask; 0 without 0x60FE:1).
  [[nodiscard]] std::uint32_t digital_outputs() const;

  /// Fault injection (names as hil::FaultInjectable uses them).
  [[nodiscard]] static std::vector<std::string> fault_names();
  bool inject_fault(std::string_view name, bool active, TimePoint now);
  /// Raise a CiA 402 error code (0 clears the injected one; the drive stays in Fault until reset).
  void inject_error_code(std::uint16_t code, TimePoint now);
  void set_heartbeat_lost(bool lost);
  void set_sdo_delay(Duration delay);  ///< Duration::max() = no answer at all
  void set_following_error_offset(std::int32_t inc) noexcept { following_offset_ = inc; }

 private:
  void on_sync(TimePoint now);
  void advance(TimePoint now);
  void run_device(double dt_s, TimePoint now);
  std::uint16_t active_fault_code() const noexcept;
  void enter_fault(std::uint16_t code, TimePoint now);
  void publish(bool target_reached, bool bit12, bool bit13);

  can::Channel& channel_;
  Cia402NodeOptions options_;
  canopen::Slave slave_;
  Plant plant_;
  DriveState state_ = DriveState::not_ready;
  std::uint16_t last_cw_ = 0;
  std::uint16_t injected_code_ = 0;
  std::uint16_t fault_code_ = 0;
  std::int32_t following_offset_ = 0;
  TimePoint last_{};
  bool started_ = false;
  TimePoint fault_since_{};
  std::optional<TimePoint> following_since_;
  // profile generator (PP / PV / quick stop)
  double demand_ = 0.0;
  double demand_velocity_ = 0.0;
  double pp_target_ = 0.0;
  bool pp_active_ = false;
  bool setpoint_ack_ = false;
  bool homing_attained_ = false;
  bool homing_error_ = false;
  bool homing_running_ = false;
  cia402::Mode mode_ = cia402::Mode::no_mode;
  Duration pending_sdo_delay_{};
  bool sdo_delay_pending_ = false;
  Cia402NodeStats stats_;
  SimulatedInputs inputs_;
};

}  // namespace hil::mocks
