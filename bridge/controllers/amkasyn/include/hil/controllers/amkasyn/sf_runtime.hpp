// SPDX-License-Identifier: MIT
#pragma once
// The SF scheduler and commanding (manual §2.1-§2.3, digest §1.2-§1.4, §1.9):
//   - FB 207 init(): binds a slot SF0..SF15 to an SF type with its interfaces;
//   - FB 208 command(): RESET (0), START (1), VALUE NEW (5), READ VALUE (6) with the state machine
//     RESET -> SF-ACTIVE; errors set the MB 232 error bit (bit 0) and the number in MB 233, valid
//     right after the command (shared by all SFs);
//   - cycle(): once per drive cycle (ID 2). The process data are copied first (a snapshot all
//     SFs see), then SF0..SF15 run in slot order, each every `cycle factor` drive cycles; a
//     source at address 255 + n reads SF n's sink of this cycle (producers have lower numbers).
// SFs keep running when the PLC program faults or "controller enable" drops: nothing here
// stops them except RESET.

#include <array>
#include <cstdint>
#include <memory>
#include <optional>
#include <string>
#include <string_view>

#include "hil/controllers/amkasyn/fast_function.hpp"

namespace hil::controllers::amkasyn {

/// MB 232 / MB 233 after a command.
struct SfStatus {
  bool error = false;
  SfError code = SfError::none;
  std::string text;  ///< what, where, which rule
};

enum class SfState : std::uint8_t { unassigned, reset, active };

class SfRuntime {
 public:
  /// `id2_half_ms`: drive parameter ID 2 in 0.5 ms units (2 = 1 ms). `dbs` must outlive the runtime.
  SfRuntime(int id2_half_ms, DbStore& dbs) noexcept : id2_(id2_half_ms > 0 ? id2_half_ms : 2), dbs_(&dbs) {}

  /// FB 207 with an init DB. Re-initialising an active slot is refused (RESET it first).
  SfStatus init(const DataBlock& init_db, ProcessImage& image);
  /// FB 208 with a commanding DB (DR0 = SF number, DR1 = code).
  SfStatus command(const DataBlock& cmd, ProcessImage& image);
  /// The same; READ VALUE also writes its output value into DD32 of `cmd`, as FB 208 does.
  SfStatus command(DataBlock& cmd, ProcessImage& image);
  /// One drive cycle. An SF that reports a running time error (APSF) stops: RESET state, MB 232
  /// error bit and MB 233 = its error number, status() says what.
  void cycle(ProcessImage& image) noexcept;
  /// Loads (or replaces) FB `number` (0..63) from its AWL listing, for APSF (awl.hpp). A started
  /// APSF keeps the FB it was started with.
  std::expected<void, std::string> load_fb(int number, std::string_view listing);

  [[nodiscard]] SfState state(int sf) const noexcept;
  [[nodiscard]] const SfStatus& status() const noexcept { return status_; }
  /// The decisions where the manual is ambiguous; they take effect at the next START.
  void set_options(const SfOptions& o) noexcept { options_ = o; }
  [[nodiscard]] const SfOptions& options() const noexcept { return options_; }
  /// The output value of the last command if it was a successful READ VALUE (DD32).
  [[nodiscard]] std::optional<std::int32_t> read_value() const noexcept { return read_value_; }
  [[nodiscard]] std::int32_t link(int sf) const noexcept { return links_[static_cast<std::size_t>(sf & 15)]; }
  /// Output bytes written by SFs (excluded from the PLC's PAA update): bit per byte of A (or M).
  [[nodiscard]] bool owns_output_byte(int byte, bool flag_area) const noexcept;
  [[nodiscard]] int id2_half_ms() const noexcept { return id2_; }
  [[nodiscard]] std::uint64_t cycles() const noexcept { return tick_; }

 private:
  struct Slot {
    std::optional<InitDb> init;
    std::unique_ptr<FastFunction> sf;
    SfTables tables{};
    bool active = false;
  };
  SfStatus finish(ProcessImage& image, SfStatus s);
  void refresh_tables(Slot& slot) noexcept;
  SfIo make_io(Slot& slot, ProcessImage& image, const ProcessImage& snapshot) noexcept;
  void apply(Slot& slot, SfIo& io, ProcessImage& image) noexcept;

  int id2_;
  DbStore* dbs_;
  std::array<Slot, max_sf> slots_{};
  std::array<std::int32_t, max_sf> links_{};
  SfStatus status_{};
  std::optional<std::int32_t> read_value_;
  FbStore fbs_;
  SfOptions options_{};
  std::uint64_t tick_ = 0;
  ProcessImage snapshot_{};
};

/// The SF object for a type, or nullptr when hilbridge does not implement that type (START then
/// fails with SfError::start_invalid naming the type).
[[nodiscard]] std::unique_ptr<FastFunction> make_fast_function(SfType type);

}  // namespace hil::controllers::amkasyn
