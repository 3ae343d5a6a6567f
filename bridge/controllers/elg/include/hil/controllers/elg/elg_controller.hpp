// SPDX-License-Identifier: MIT
#pragma once
// The SINUMERIK ELG as a controller of the runtime (docs/elg.md): a scenario's
//   controller: {device: sinumerik-elg, parameters: md.tape, programs: [hobbing.nc]}
// configures the gearbox from the MD/SD tape the serial link reads (MD 396* pulses, MD 5002
// units, MD 5020/5021 axis declaration, MD 252* contour factor, MD 166/169/170 limits, MD 280*
// speeds), declares the axes B (hob), C (table), Z (axial feed), X (radial infeed) and, with
// MD 5021 naming a tangential axis, Y, and runs the System 3 NC program on them
// (HobbingMachine). ELG alarms are device errors of the profile's catalogue "alarms".
//
// Options (controller block keys, as text): `start: auto | input` (NC start at power-up, the
// default, or on the rising edge of the input `cycle_start`), `m_functions: "50=gearing_on,..."`
// (the PC program's M assignment; default in pc_interface.hpp), `r_parameters:
// "z0=20,z2=21,ud_z=12,ud_y=13,toler=40"`, `index: grid | relative`.
//
// I/O image (names): inputs `cycle_start`, `fe_monitor` (A67.1), `reset` (ELG-RESET);
// outputs `computed` (E66.6), `coupled` (E66.7), `tooth_gap_reached` (E66.3), `elg_alarm`
// (E65.5), `contact_closed` (FE relay), `program_running`, `referenced` (E69..72.1 of C),
// `c_traversing` (a JOG/INC/REF motion of C); marker byte `tooth` (TOOTH NO.).
// Machine control panel (12.4.3; setup_modes.hpp): inputs `key_plus`, `key_minus`, `rapid`,
// `rapid_override`, `ref_cam` (C's deceleration cam actuated), the override code
// `override_1/_2/_4/_8` (position = code + 1; code 0 = 0 %), the mode code `mode_1/_2/_4`
// (1 JOG, 2 INC, 3 REF), the INC selector code `inc_1/_2/_4` (0..4 = 1, 10, 100, 1000, 10000
// increments) and `data_start` (V.24 Data Start: 2214 while coupled).

#include <memory>

#include "hil/controllers/controller.hpp"
#include "hil/controllers/controller_registry.hpp"
#include "hil/controllers/elg/hobbing_machine.hpp"
#include "hil/controllers/parameter_file.hpp"

namespace hil::controllers::elg {

class ElgController final : public Controller {
 public:
  /// `circuits`: per axis (in `axes` order) the ELG's measuring circuit 0..3 (MD 5020/5021), -1 for
  /// an axis the ELG does not measure (X): the axis alarms 104*..184* are numbered base + circuit.
  ElgController(LoadedParameters parameters, HobbingConfig config, NcProgram program, std::vector<ControllerAxis> axes,
                std::vector<int> circuits, bool auto_start, Duration cycle);

  [[nodiscard]] const HobbingMachine* machine() const noexcept { return machine_.get(); }
  /// "C_linkage_error_deg": C's actual position against the hobbing linkage (HobbingMachine).
  [[nodiscard]] std::vector<std::string> trace_signals() const override { return {"C_linkage_error_deg"}; }
  [[nodiscard]] double trace_value(std::size_t i) const noexcept override {
    return i == 0 && machine_ ? machine_->c_linkage_error_deg() : 0.0;
  }

 protected:
  void on_cycle(const CycleTime& cycle) noexcept override;
  [[nodiscard]] PanelSignals read_panel() const noexcept;
  [[nodiscard]] std::optional<DeviceErrorCode> map_axis_fault(std::size_t axis, const hil::Fault& fault,
                                                              const motion::AxisStatus& status) const noexcept override;

 private:
  HobbingConfig config_;
  NcProgram program_;
  std::unique_ptr<HobbingMachine> machine_;
  bool auto_start_ = true;
  bool started_ = false;
  std::vector<Alarm> reported_;  ///< the ELG's alarms as last reported as device errors
  std::vector<int> circuits_;    ///< measuring circuit per axis, -1: none
  const profiles::ErrorCatalogue* alarms_ = nullptr;
};

/// What the MD tape configures: the gearbox and setting-up data, the axes B, C, Z, X (Y) with
/// their scaling and speeds, and each axis' measuring circuit (-1: none).
struct ElgSetup {
  HobbingConfig config;
  std::vector<ControllerAxis> axes;
  std::vector<int> circuits;
};
/// Reads the %TEA1 tape (MD 396*, 5002, 5020/5021, 252*, 166, 169, 170, 100-114, 240*, 280*-300*,
/// 564*) onto `options` (the controller's M functions, R numbers, index option). `cycle` is the
/// ELG cycle. Error: the datum that is missing or wrong, with the tape's file.
std::expected<ElgSetup, ConfigError> elg_setup_from_tape(const LoadedParameters& loaded, const HobbingConfig& options,
                                                         Duration cycle);

/// Registers `sinumerik-elg` in `registry`.
void register_elg(ControllerRegistry& registry);

}  // namespace hil::controllers::elg
