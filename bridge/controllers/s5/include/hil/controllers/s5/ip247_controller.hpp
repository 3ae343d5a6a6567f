// SPDX-License-Identifier: MIT
#pragma once
// The IP247 module on the controller runtime (issue 19): a hil::controllers::Controller that owns
// one Ip247Axis (the module's modes, programs and pulse generator) and drives the machine axis the
// scenario gives it, on any transport, through hil::Drive: every controller cycle the module's
// pulse position (motor pulses, 1 increment = 1 pulse) is the axis' cyclic set-point
// (motion::Axis::follow), so the programmed speed, the IP247 ramp and the reference approach reach
// the drive exactly. A scenario names it with
//   controller: {device: ip247, parameters: MD-DB.s5db, programs: [VP.txt, ...], interface_db: 10}
//
// The PLC side is the axis interface DB of ip247_interface.hpp (20 words), laid into the image's
// data area (DB `interface_db`, default 10): a scenario's `plc:` steps write BA, parameters and a
// command bit, the module takes the job at its next cycle (clears DW4) and writes actual value,
// remaining distance, BA/M, attributes/error there. The program files are the VP DBs the PLC
// writes at start (BA22), in program-number order; each is readable as DB n (n = program number):
// a program refused by the syntax check gives module error 48 and its image carries the syntax
// error in DW3 and the block in DW4. The MD DB is readable as its DB number.
//
// Inputs (image byte 0 of the input area): bit 0 limit_minus_A (E ANF), bit 1 limit_plus_A (E END),
// as wired (NC from the MD: 1 = not actuated), bit 2 reference_cam_A (BERO), bit 3 external_stop_A
// (START-N/STOP). BB (ready) is the machine axis: enabled and not faulted. Outputs byte 0: bit 0
// in_position_A (PE), bit 1 moving_A (job running), bit 2 error_A (module error >= 10).
// Module errors >= 10 are device errors `ip247.module:N` on the axis (the module has braked
// itself; the runtime applies no reaction); they clear when the error byte clears (the next
// operating command acknowledges, as on the module). Messages 1..9 stay in the error byte only.
// Thread: the cycle thread; on_cycle never throws.

#include <expected>
#include <filesystem>
#include <map>
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include "hil/controllers/controller.hpp"
#include "hil/controllers/controller_registry.hpp"
#include "hil/controllers/s5/ip247_axis.hpp"
#include "hil/controllers/s5/ip247_follower.hpp"
#include "hil/controllers/s5/ip247_machine_data.hpp"
#include "hil/controllers/s5/ip247_program_store.hpp"

namespace hil::controllers::s5 {

/// A VP DB the PLC writes at start: the program file and its text.
struct Ip247ProgramFile {
  std::filesystem::path file;
  int number = 0;
  std::string text;
};

class Ip247Controller final : public hil::controllers::Controller {
 public:
  /// Reads the MD DB (an S5 DB listing, 70 words; MD errors name the file and the IP247 MD error
  /// number) and the program files (program text, or a VP DB listing), declares the axis.
  [[nodiscard]] static std::expected<std::unique_ptr<hil::controllers::Controller>, ConfigError> create(
      const ControllerSpec& spec);

  Ip247Controller(std::shared_ptr<const profiles::Profile> profile, const Ip247MachineData& md, int md_db,
                  int interface_db, std::vector<Ip247ProgramFile> programs, Duration cycle);

  [[nodiscard]] std::expected<hil::controllers::BitAddress, std::string> resolve_bit(
      std::string_view text) const override;
  [[nodiscard]] std::expected<std::uint16_t, std::string> read_data_word(int db, int dw) const override;
  std::expected<void, std::string> write_data_word(int db, int dw, std::uint16_t value) override;
  [[nodiscard]] std::span<const S5DataBlock> data_blocks() const noexcept override { return {&interface_, 1}; }
  [[nodiscard]] std::vector<std::string> trace_signals() const override;
  [[nodiscard]] double trace_value(std::size_t i) const noexcept override;

  [[nodiscard]] const Ip247Axis& module_axis() const noexcept { return axis_; }

 protected:
  void on_cycle(const CycleTime& cycle) noexcept override;
  /// The module's pulses are a cyclic set-point: a drive-profile drive cannot follow them.
  [[nodiscard]] std::expected<void, std::string> check_axes() override;
  [[nodiscard]] std::optional<DeviceErrorCode> map_axis_fault(std::size_t axis, const hil::Fault& fault,
                                                              const motion::AxisStatus& status) const noexcept override;

 private:
  /// BA22 of every program file at start: stores it or keeps the refusal for the first cycle.
  void write_programs();
  void report_error(TimePoint now) noexcept;
  /// Status words (DW5..DW13, DW4 cleared) of the module into the interface DB.
  void publish_status() noexcept;

  Ip247MachineData md_;
  int md_db_ = 1;
  S5DataBlock interface_{};
  std::vector<Ip247ProgramFile> program_files_;
  std::map<int, std::vector<std::uint16_t>> vp_images_;  ///< VP DB images by program number
  std::vector<std::pair<int, std::string>> refused_;     ///< module error and text of refused VPs
  Ip247ProgramStore store_;
  Ip247Axis axis_;
  Ip247Kinematics kin_{};
  std::vector<std::uint16_t> words_;  ///< scratch: the interface DB of this cycle
  bool started_ = false;              ///< the refusals of the programs are reported
  Ip247Follower follower_;
  int shown_error_ = 0;
  std::int64_t period_ns_ = 0;
};

/// Registers "ip247" (the module) in `registry`.
void register_ip247(ControllerRegistry& registry);

}  // namespace hil::controllers::s5
