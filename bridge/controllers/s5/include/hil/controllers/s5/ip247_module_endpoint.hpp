// SPDX-License-Identifier: MIT
#pragma once
// A running IP247 module behind 3964R/RK512 (`hilbridge emulate ip247`): the data-block policy of
// hil::mocks::legacy::S5BlockEndpoint over one Ip247Module (three live axes, the program memory,
// the MD images, the SYS-ID and the data channel). Our mapping (docs/ip247.md):
//   DB n (RK512 SEND/FETCH, data type 'D'): the module's MD DB (70 words; the axis from DR 3)
//     and VP DB images, as the data BAs 20/22 (write), 67/69 (read) and 21/23 (delete = SEND of
//     one word 0000 to DW0). No overwrite; a rejected image is not stored (reaction 10h; the MD
//     error / syntax error is in `last_rejection()`).
//   DX 1..3 (data type 'X'): the axis interface DB of ip247_interface.hpp: write BA, parameters
//     and a command bit in DW4; read actual value, remaining distance, BA/M, attributes/error.
//   DX 4: the data-job block (ip247_data_job.hpp, FB165's 15 words; DW 60..74 of the
//     controller's interface DB): the PLC writes Q-DB, QANF, Z-DB, ZANF, SSNR, then DW0 = BA;
//     the job runs at once (BA20-24, 64-70 of Ip247Module) and the block shows the result,
//     DW0 = 0000h.
//   DX 5..255: the PLC's data blocks DB 5..255 that the data jobs read from (Q-DB of 20/22/24) and
//     write to (Z-DB of 64-70), created by the first SEND (a DB's length is what the PLC wrote).
// The module steps its axes at the module cycle on the time the endpoint host passes in; the
// limit switches and the reference cam of each axis are mock inputs, actuated as a function of
// the pulses output (options). The endpoint's DB store mirrors the module's images (persisted).
// Thread: the endpoint host's thread only.

#include <array>
#include <chrono>
#include <functional>
#include <memory>
#include <optional>
#include <string>
#include <utility>

#include "hil/controllers/s5/ip247_axis.hpp"
#include "hil/controllers/s5/ip247_module.hpp"
#include "hil/mocks/legacy/s5_block_endpoint.hpp"

namespace hil::controllers::s5 {

/// Mock switches of one axis, as motor pulse positions.
struct Ip247AxisSwitches {
  std::optional<std::int64_t> limit_start_at;                ///< "start" switch actuated at position <= this
  std::optional<std::int64_t> limit_end_at;                  ///< "end" switch actuated at position >= this
  std::optional<std::pair<std::int64_t, std::int64_t>> cam;  ///< reference cam within [a, b]
};

inline constexpr std::uint8_t ip247_job_block_dx = 4;  ///< DX 4: the data-job block
inline constexpr std::uint8_t ip247_first_plc_dx = 5;  ///< DX 5..255: the PLC's DB 5..255

struct Ip247ModuleOptions {
  std::chrono::nanoseconds cycle{std::chrono::milliseconds(1)};
  int sysid_module = 0;
  int tile = 0;  ///< SSNR of axis 1 (switch S2, a multiple of 4): axes tile..tile+2, data channel tile+3
  std::array<Ip247AxisSwitches, 3> switches{};
};

/// Per-cycle hooks of a module whose axes drive machine axes (`hilbridge emulate ip247 --machine`).
struct Ip247ModuleHooks {
  /// The raw inputs of axis n (1..3) for this cycle, after the mock switches; may change them
  /// (the drive's limit and reference lines, BB from the machine axis).
  std::function<void(int axis, Ip247Inputs& in)> inputs;
  /// After each module cycle ending at `now` (the module's axes have stepped).
  std::function<void(TimePoint now)> after_cycle;
};

class Ip247ModulePolicy final : public mocks::legacy::DbPolicy {
 public:
  explicit Ip247ModulePolicy(Ip247ModuleOptions o = {});
  Ip247ModulePolicy(const Ip247ModulePolicy&) = delete;  // plc_ may point at own_plc_
  Ip247ModulePolicy& operator=(const Ip247ModulePolicy&) = delete;

  [[nodiscard]] std::string name() const override { return "ip247"; }
  serial::s5::Rk512Error on_write(mocks::legacy::DbStore& store, std::uint8_t db, std::uint8_t dw,
                                  const std::vector<std::uint16_t>& w) override;
  serial::s5::Rk512Error on_read(const mocks::legacy::DbStore& store, std::uint8_t db, std::uint8_t dw,
                                 std::uint16_t length, std::vector<std::uint16_t>& out) override;
  serial::s5::Rk512Error on_write_dx(mocks::legacy::DbStore& store, std::uint8_t dx, std::uint8_t dw,
                                     const std::vector<std::uint16_t>& w) override;
  serial::s5::Rk512Error on_read_dx(const mocks::legacy::DbStore& store, std::uint8_t dx, std::uint8_t dw,
                                    std::uint16_t length, std::vector<std::uint16_t>& out) override;
  void on_time(TimePoint now) override;
  [[nodiscard]] TimePoint next_deadline() const override;

  void set_hooks(Ip247ModuleHooks hooks) { hooks_ = std::move(hooks); }
  /// Load persisted images (battery-backed MD and programs) into the module.
  void adopt(mocks::legacy::DbStore& store);
  [[nodiscard]] Ip247Axis& axis(int n) { return module_.axis(n); }
  [[nodiscard]] Ip247ProgramStore& programs() noexcept { return module_.programs(); }
  [[nodiscard]] Ip247Module& module() noexcept { return module_; }
  /// The PLC's data blocks of the data jobs (DX 5..255).
  [[nodiscard]] const S5Blocks& plc_blocks() const noexcept { return *plc_; }
  /// Uses `blocks` (non-null; shared by the modules of one rack, `hilbridge emulate ip247` with
  /// several modules: the PLC's DBs are one PLC's; must outlive the policy) as the PLC's DBs of the
  /// data jobs; nullptr: the policy's own again. Thread: the endpoint host's (every module of the
  /// rack on the same thread).
  void use_plc_blocks(S5Blocks* blocks) noexcept { plc_ = blocks != nullptr ? blocks : &own_plc_; }
  [[nodiscard]] const std::string& last_rejection() const noexcept { return rejection_; }
  /// Current raw inputs of axis n (from the mock switches).
  [[nodiscard]] Ip247Inputs inputs(int n) const;

 private:
  std::vector<std::uint16_t>& refresh(int n);
  /// The endpoint's DB store = the module's MD images and stored VP images.
  void mirror(mocks::legacy::DbStore& store) const;
  serial::s5::Rk512Error delete_image(mocks::legacy::DbStore& store, std::uint8_t db);
  serial::s5::Rk512Error job_block_written(mocks::legacy::DbStore& store);

  Ip247ModuleOptions o_;
  Ip247Module module_;
  std::array<std::vector<std::uint16_t>, 3> iface_;
  std::vector<std::uint16_t> job_block_;
  S5Blocks own_plc_;
  S5Blocks* plc_ = &own_plc_;
  TimePoint t_{};
  bool started_ = false;
  std::string rejection_;
  Ip247ModuleHooks hooks_;
};

}  // namespace hil::controllers::s5
