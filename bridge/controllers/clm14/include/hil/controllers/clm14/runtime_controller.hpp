// SPDX-License-Identifier: MIT
#pragma once
// The CLM1.4 model on the controller runtime (issue 14): a hil::controllers::Controller that owns
// a clm14::Controller, whose I/O image is the runtime's IoImage (CLM groups at byte group*64+yy,
// io_address_clm.hpp) and whose axes are the runtime's motion::Axis objects. A scenario names
// it with `controller: {device: clm14, parameters: clm.par, program: clm.prg}`; the key
// `master_encoder: NAME` declares one more axis, NAME, whose actual increments are master
// encoder 1's counts (C000 × 4 per C002 IU): the material of a flying cutoff, a FOL master;
// `master_encoder2: NAME` likewise master encoder 2 (C004 × 4 per C006 IU); `homing: clm | drive`
// (Options::drive_homing) and `marker1` .. `marker4` (the marker pulse of an axis: a count offset of the encoder's
// marker, or a CLM input address, MarkerSource).
//
// Parameter files: one parameter per line, either the hilbridge text form "B002 019200 0 1 8 1"
// or the CLM telegram "# K B002 019200 0 1 8 1$E4"; program files "0000 POI 1 +000100.000 999".
// Thread: the cycle thread; on_cycle never throws.

#include <map>
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include "hil/controllers/clm14/controller.hpp"
#include "hil/controllers/clm14/motion_axis_port.hpp"
#include "hil/controllers/controller.hpp"
#include "hil/controllers/controller_registry.hpp"

namespace hil::controllers::clm14 {

class RuntimeController final : public hil::controllers::Controller {
 public:
  /// Builds the controller from the scenario's block: reads and checks parameter and program
  /// files (errors name file and line, with the device's error number), declares the enabled
  /// axes in IU.
  [[nodiscard]] static std::expected<std::unique_ptr<hil::controllers::Controller>, ConfigError> create(
      const ControllerSpec& spec);

  [[nodiscard]] std::expected<hil::controllers::BitAddress, std::string> resolve_bit(
      std::string_view text) const override;
  /// The CLM's values for `expect: {controller: NAME, value: V}` (runtime_values.cpp,
  /// docs/clm14.md "Scenarios"): "V000".."V999" (variables, exact millionths), "I1.02" / "Q1.02" /
  /// "M2.00" (a byte, 0..255), "counter.0002" (the count of the COU/BAC on line 0002),
  /// "task1.line" / "task1.depth" / "task1.active" (tasks 1..5: current instruction, subroutine
  /// levels, running), "error" (the current error number, 0 = none: write 0x43 for error 43),
  /// "axis1.position" / "axis1.latched" (CLM coordinates in IU: status 00 and the SRM latch of
  /// status 41), "mode" (0 Parameter, 1 Manual, 2 Automatic), "run" (0 idle, 1 running, 2 stopped),
  /// "cuts" / "cut.last" (flying cutoff: cuts so far, the last cut's material point in IU),
  /// "length.material" / "length.product" (the status 54 length counters, IU).
  [[nodiscard]] std::expected<std::size_t, std::string> resolve_value(std::string_view name) const override;
  [[nodiscard]] double value(std::size_t handle) const noexcept override;
  /// The analog inputs "AE1".."AE4" for `io: - {analog: AE1, value: V}`: volts, −10 .. +10;
  /// set_analog rounds to the model's mV (Controller::set_analog_input).
  [[nodiscard]] std::expected<AnalogInputSpec, std::string> resolve_analog(std::string_view name) const override;
  void set_analog(std::size_t handle, double value) noexcept override;
  [[nodiscard]] clm14::Controller& model() noexcept { return model_; }

  RuntimeController(std::shared_ptr<const profiles::Profile> profile, std::map<std::string, std::string> parameters,
                    Duration cycle, Options options = {});

 protected:
  void on_cycle(const CycleTime& cycle) noexcept override;
  [[nodiscard]] std::optional<DeviceErrorCode> map_axis_fault(std::size_t axis, const hil::Fault& fault,
                                                              const motion::AxisStatus& status) const noexcept override;

 private:
  std::map<std::string, std::string> parameters_;
  clm14::Controller model_;
  std::vector<std::unique_ptr<MotionAxisPort>> ports_;
  std::size_t clm_axes_ = 0;  ///< axes 1..n of the CLM, declared first
  bool has_master_ = false;   ///< then master encoder 1's axis (controller key master_encoder)
  std::unique_ptr<MotionMasterEncoder> master_;
  bool has_master2_ = false;  ///< then master encoder 2's axis (controller key master_encoder2)
  std::unique_ptr<MotionMasterEncoder> master2_;
  std::optional<int> test_step_;  ///< controller key test_speed_step
  Mode last_mode_ = Mode::manual;
  int shown_error_ = 0;
  int shown_axis_ = -1;  ///< the runtime axis index shown_error_ was raised on (-1: the controller)
};

/// Registers "clm14" in `registry`.
void register_clm14(ControllerRegistry& registry);

}  // namespace hil::controllers::clm14
