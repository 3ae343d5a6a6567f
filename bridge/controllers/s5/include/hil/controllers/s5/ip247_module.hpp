// SPDX-License-Identifier: MIT
#pragma once
// One IP247 module (manual §1.1, §4.3.11-4.3.23; digest ip247.md §1.1, §4.12, §5.5): three axes
// (Ip247Axis) sharing one program memory, the MD DB images of the axes (with their MD error byte),
// the SYS-ID, and the data channel that executes the data jobs of ip247_data_job.hpp against the
// PLC's data blocks.
//
// Tiles: the module occupies SSNR base .. base+3 (switch S2, `Ip247SysId::tile` is only the
// documented value): base+0..2 = axes 1..3, base+3 = the data channel. Which job runs on which
// tile (§4.4): 20/21/66 on the axis tile; 22/23/24 on the data channel; 64/65/68/69/70 anywhere;
// 67 on the axis tile, or on the data channel when every MD DB number differs. Otherwise module
// error 46. The module's own errors (its numbers): 4 axis running (MD write/delete), 12 module
// number locked, 13 DB not present, 15 faulty MD (the MD error goes into the stored set's DR 4),
// 18 max programs, 22 VP change during teach-in, 24 memory, 48 VP faulty (the refused image keeps
// the syntax error in DW3 and the block in DW4 and is readable by BA69, not in the directory),
// 49 VP exists, 51 VP running, 61 deleted from the directory only (a message). An error of a job
// on an axis tile is also latched on that axis; the data channel keeps its own error until its
// next job or BA17. Data jobs are not operating commands: they never abort a motion.
// Thread: the module cycle only. Never throws.

#include <array>
#include <cstdint>
#include <map>
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include "hil/controllers/s5/ip247_axis.hpp"
#include "hil/controllers/s5/ip247_data_job.hpp"
#include "hil/controllers/s5/ip247_program_store.hpp"

namespace hil::controllers::s5 {

/// SYS-ID (BA24 write, BA70 read): module number 0..99 (checked against the MD), slot and tile
/// (documentation only).
struct Ip247SysId {
  int module = 0;
  int slot = 0;
  int tile = 0;
  friend bool operator==(const Ip247SysId&, const Ip247SysId&) = default;
};

inline constexpr int ip247_axes = 3;
inline constexpr int ip247_data_channel = 4;

class Ip247Module {
 public:
  /// `base_tile`: SSNR of axis 1 (S2, a multiple of 4).
  explicit Ip247Module(int base_tile = 0, Ip247InterpreterOptions io = {});

  [[nodiscard]] Ip247Axis& axis(int n) noexcept { return *axes_[static_cast<std::size_t>(n - 1)]; }
  [[nodiscard]] const Ip247Axis& axis(int n) const noexcept { return *axes_[static_cast<std::size_t>(n - 1)]; }
  [[nodiscard]] Ip247ProgramStore& programs() noexcept { return store_; }
  [[nodiscard]] const Ip247ProgramStore& programs() const noexcept { return store_; }
  [[nodiscard]] const Ip247SysId& sysid() const noexcept { return sysid_; }
  [[nodiscard]] int base_tile() const noexcept { return base_tile_; }
  /// 1..3 axis tile, 4 data channel, 0 not a tile of this module.
  [[nodiscard]] int channel(int tile) const noexcept;

  /// BA20 on axis `n`'s tile with an MD DB image as DB `db`: the module's checks and the
  /// interface errors of the image (wrong identifier, DB exists).
  Ip247DataResult write_md(int n, int db, const std::vector<std::uint16_t>& image);
  /// BA22 of a VP DB image as DB (program) `db`; `fault` receives the syntax error on 48.
  Ip247DataResult write_vp(int db, const std::vector<std::uint16_t>& image, Ip247SyntaxFault* fault = nullptr);
  /// A data job on `job.tile`, against the PLC's blocks `plc` (read: source; written: targets).
  Ip247DataResult data_job(const Ip247DataJob& job, S5Blocks& plc);
  /// An operating command on axis n (BA17 also clears the other axes and the data channel).
  void command(int n, const Ip247Job& job);

  /// The MD DB image of axis n as stored (DR 4 = its MD error), or nullptr; its DB number.
  [[nodiscard]] const std::vector<std::uint16_t>* md_image(int n) const noexcept;
  [[nodiscard]] int md_db(int n) const noexcept { return md_db_[static_cast<std::size_t>(n - 1)]; }
  /// The VP DB image of program `number` (stored, or refused with DW3/DW4), or nullopt.
  [[nodiscard]] std::optional<std::vector<std::uint16_t>> vp_image(int number) const;
  [[nodiscard]] int data_channel_error() const noexcept { return data_error_; }

 private:
  Ip247DataResult md_write(int n, const Ip247DataJob& job, const S5Blocks& plc);
  Ip247DataResult md_delete(int n, int db);
  Ip247DataResult vp_delete(int db);
  Ip247DataResult sysid_write(const Ip247DataJob& job, const S5Blocks& plc);
  Ip247DataResult read_into(const std::vector<std::uint16_t>& words, const Ip247DataJob& job, S5Blocks& plc) const;
  Ip247DataResult vp_directory(const Ip247DataJob& job, S5Blocks& plc) const;
  Ip247DataResult actual_values(int n, const Ip247DataJob& job, S5Blocks& plc) const;

  int base_tile_ = 0;
  Ip247ProgramStore store_;
  std::array<std::unique_ptr<Ip247Axis>, ip247_axes> axes_;
  std::array<std::vector<std::uint16_t>, ip247_axes> md_images_;
  std::array<int, ip247_axes> md_db_{-1, -1, -1};
  std::map<int, std::vector<std::uint16_t>> refused_vp_;  ///< images refused with error 48
  Ip247SysId sysid_{};
  int data_error_ = 0;
};

}  // namespace hil::controllers::s5
