// SPDX-License-Identifier: MIT
#pragma once
// The `sim` transport: a hil::Drive directly on the plant, with a CiA 402-like power state
// machine and fault injection. Used by `hilbridge run` with no hardware and by motion tests.

#include <expected>
#include <string>

#include <yaml-cpp/yaml.h>

#include "hil/config/yaml_config.hpp"
#include "hil/core/config_error.hpp"
#include "hil/core/drive.hpp"
#include "hil/core/fault_injection.hpp"
#include "hil/mocks/plant.hpp"
#include "hil/mocks/switches.hpp"

namespace hil::mocks {

struct SimDriveConfig {
  std::string name = "sim";
  PlantConfig plant;
  Duration transition_time{std::chrono::milliseconds(1)};  ///< per power-state step (shutdown, switch on, enable)
  double quick_stop_deceleration_inc_per_s2 = 1.0e8;
  Duration homing_time{std::chrono::milliseconds(200)};
  std::int64_t home_position_inc = 0;  ///< position after homing (method: current position)
  PlantSwitches switches;              ///< limit and home switches reported as digital inputs
};

/// Parse a scenario's `drive:` block for `transport: sim`. Keys (all optional):
/// kv [1/s], max_velocity [inc/s], velocity_lag [s], feedforward [0..1], encoder_step [inc],
/// initial_position [inc], transition_time [s], quick_stop_deceleration [inc/s^2],
/// homing_time [s], home_position [inc], switches {negative, positive, home: [from, to]} [inc].
[[nodiscard]] std::expected<SimDriveConfig, ConfigError> parse_sim_drive_config(const YAML::Node& node,
                                                                                const yaml::Where& where);

/// Thread: all members on the motion thread.
class SimDrive final : public Drive, public FaultInjectable {
 public:
  explicit SimDrive(SimDriveConfig config);

  [[nodiscard]] std::string_view name() const noexcept override { return name_; }
  [[nodiscard]] DriveCapabilities capabilities() const noexcept override;
  void read(const CycleTime& cycle) override;
  void write(const CycleTime& cycle, const DriveCommand& command) override;
  [[nodiscard]] const DriveFeedback& feedback() const noexcept override { return feedback_; }
  bool request(DriveRequest r) override;

  /// Injectable: "encoder", "not_ready", "following_blowup" (plant), "stale_feedback" (the image
  /// stops updating and its age grows, as with a lost connection).
  [[nodiscard]] std::vector<std::string> injectable_faults() const override;
  bool inject_fault(std::string_view fault, bool active) override;

  [[nodiscard]] Plant& plant() noexcept { return plant_; }
  /// The digital inputs (switches from the plant position, bits a test forces).
  [[nodiscard]] SimulatedInputs& inputs() noexcept { return inputs_; }
  /// DriveCommand::digital_outputs as last written (every bit is applied: the sim has no mask).
  [[nodiscard]] std::uint32_t digital_outputs() const noexcept { return digital_outputs_; }

 private:
  void advance_state(TimePoint now);
  void enter_fault(PlantFault f);

  SimDriveConfig config_;
  std::string name_;
  Plant plant_;
  DriveFeedback feedback_;
  DriveState state_ = DriveState::switch_on_disabled;
  DriveRequest pending_ = DriveRequest::disable;
  bool has_pending_ = false;
  TimePoint last_{};
  bool started_ = false;
  TimePoint next_transition_{};
  TimePoint homing_done_{};
  bool homing_ = false;
  bool referenced_ = false;
  bool stale_ = false;
  TimePoint stale_since_{};
  double hold_position_inc_ = 0.0;  ///< position command while not following the motion core
  double qs_velocity_ = 0.0;        ///< velocity during the drive-side quick stop ramp
  Fault fault_;
  SimulatedInputs inputs_;
  std::uint32_t digital_outputs_ = 0;
};

}  // namespace hil::mocks
