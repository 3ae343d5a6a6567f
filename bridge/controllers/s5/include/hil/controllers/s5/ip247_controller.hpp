// SPDX-License-Identifier: MIT
#pragma once
// The IP247 module on the controller runtime (issue 19): a hil::controllers::Controller that owns
// one Ip247Module (three axes sharing one program memory, the data channel) and drives one
// machine axis per module axis that has machine data at start, on any transport, through
// hil::Drive: every controller cycle the axis' pulse position (motor pulses, 1 increment = 1
// pulse) is its machine axis' cyclic set-point (motion::Axis::follow), so the programmed speed,
// the IP247 ramp and the reference approach reach the drive exactly. A scenario names it with
//   controller: {device: ip247, parameters: MD-DBs.s5db, programs: [VP.txt, ...], interface_db: 10,
//                plc_dbs: PLC-DBs.s5db}
// The MD listing holds one 70-word MD DB per axis the module has at start (battery-backed); the
// axis is DR 3 of each set (1..3), as on the module. Several modules: the module number of each
// set (DL 3, what the SYS-ID check compares) says which module it belongs to; module k (in
// ascending module number) has SSNR base tile + 4k, interface DB interface_db + k, I/O bytes
// 3k..3k+2, its own program memory (every program file is written into each), and its machine
// axes are named m<module>a<axis> (docs/ip247.md, "Several modules").
//
// The PLC side is the interface DB (`interface_db`, default 10) in the image's data area, laid out
// as FB164/FB165 lay their blocks: DW 20(k-1) .. 20(k-1)+19 = the axis DB of axis k
// (ip247_interface.hpp: BA, parameters, command bits in, actual value, remaining distance, BA/M,
// attributes/error out), DW 60..74 = the data-job block of ip247_data_job.hpp (FB165: BA 20-24,
// 64-70 between the PLC's DBs and the module; DW60 = 0 when done). The PLC's own DBs (the source
// and target DBs of data jobs) come from `plc_dbs` (an S5 DB listing; each DB keeps its length)
// and are read and written word by word. The module's DBs (MD images, VP images; a VP refused by
// the syntax check carries its syntax error in DW3 and block in DW4) are readable as DB n where no
// PLC DB has that number.
//
// Inputs (image input byte k-1 for axis k): bit 0 limit_minus (E ANF), bit 1 limit_plus (E END),
// as wired (NC from the MD: 1 = not actuated), bit 2 reference_cam (BERO), bit 3 external_stop
// (START-N/STOP). BB (ready) is the machine axis: enabled and not faulted (an axis without machine
// axis has BB low: 53). Outputs byte k-1: bit 0 in_position (PE), bit 1 moving, bit 2 error.
// Module errors >= 10 are device errors `ip247.module:N` on their axis (the module has braked
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
#include "hil/controllers/s5/ip247_module.hpp"

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

  /// `modules`: how many IP247 modules (1..8) the controller holds, at tiles tile + 4k and
  /// interface DBs interface_db + k.
  Ip247Controller(std::shared_ptr<const profiles::Profile> profile, int interface_db,
                  std::vector<Ip247ProgramFile> programs, S5Blocks plc_dbs, Duration cycle, int tile = 0,
                  int modules = 1);

  [[nodiscard]] std::expected<hil::controllers::BitAddress, std::string> resolve_bit(
      std::string_view text) const override;
  [[nodiscard]] std::expected<std::uint16_t, std::string> read_data_word(int db, int dw) const override;
  std::expected<void, std::string> write_data_word(int db, int dw, std::uint16_t value) override;
  [[nodiscard]] std::span<const S5DataBlock> data_blocks() const noexcept override { return interfaces_; }
  [[nodiscard]] std::vector<std::string> trace_signals() const override;
  [[nodiscard]] double trace_value(std::size_t i) const noexcept override;

  /// The module axis of the first machine axis.
  [[nodiscard]] const Ip247Axis& module_axis() const noexcept { return module_axis(0); }
  /// The module axis of machine axis i.
  [[nodiscard]] const Ip247Axis& module_axis(std::size_t i) const noexcept {
    return modules_[axes_[i].module]->axis(axes_[i].axis);
  }
  /// Module k (0 = the lowest module number).
  [[nodiscard]] const Ip247Module& module(std::size_t k = 0) const noexcept { return *modules_[k]; }
  [[nodiscard]] std::size_t module_count() const noexcept { return modules_.size(); }
  /// The PLC's data blocks (plc_dbs).
  [[nodiscard]] const S5Blocks& plc_blocks() const noexcept { return plc_; }

 protected:
  void on_cycle(const CycleTime& cycle) noexcept override;
  /// The module's pulses are a cyclic set-point: a drive-profile drive cannot follow them.
  [[nodiscard]] std::expected<void, std::string> check_axes() override;
  [[nodiscard]] std::optional<DeviceErrorCode> map_axis_fault(std::size_t axis, const hil::Fault& fault,
                                                              const motion::AxisStatus& status) const noexcept override;

 private:
  /// BA22 of every program file at start: stores it or keeps the refusal for the first cycle.
  void write_programs();
  void report_errors(TimePoint now) noexcept;
  /// Status words of every axis (its DW4 cleared) into the interface DB.
  void publish_status() noexcept;

  /// A machine axis: module index and module axis number (1..3).
  struct AxisRef {
    std::size_t module = 0;
    int axis = 1;
  };
  /// The machine axis of module k's axis n, or axis_count() when it has none.
  [[nodiscard]] std::size_t machine_axis(std::size_t k, int n) const noexcept;

  std::vector<S5DataBlock> interfaces_;  ///< interface DB of each module
  std::vector<Ip247ProgramFile> program_files_;
  std::vector<std::pair<int, std::string>> refused_;  ///< module error and text of refused VPs
  S5Blocks plc_;                                      ///< the PLC's DBs
  std::vector<std::unique_ptr<Ip247Module>> modules_;
  std::vector<AxisRef> axes_;  ///< module and module axis of each machine axis, in declaration order
  std::vector<Ip247Follower> followers_;
  std::vector<int> shown_error_;
  std::vector<int> shown_data_error_;  ///< per module
  std::vector<std::uint16_t> words_;   ///< scratch: the interface DB of module k at k * interface words
  bool started_ = false;               ///< the refusals of the programs are reported
  std::int64_t period_ns_ = 0;
};

/// Registers "ip247" (the module) in `registry`.
void register_ip247(ControllerRegistry& registry);

}  // namespace hil::controllers::s5
