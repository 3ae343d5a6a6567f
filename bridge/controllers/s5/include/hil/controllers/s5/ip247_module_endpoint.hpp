// SPDX-License-Identifier: MIT
#pragma once
// A running IP247 module behind 3964R/RK512 (`hilbridge emulate ip247`): the data-block policy of
// hil::mocks::legacy::S5BlockEndpoint with three live axes (Ip247Axis) and the program memory.
//   DB n (RK512 SEND/FETCH, data type 'D'): the MD DB (70 words; the axis from DR 3) and VP DB
//     images, as the data BAs 20/22 (write), 67/69 (read) and 21/23 (delete = SEND of one word
//     0000 to DW0). No overwrite; a rejected image is not stored (reaction 10h; the MD error /
//     syntax error is in `last_rejection()`).
//   DX 1..3 (data type 'X'): the axis interface DB of ip247_interface.hpp: write BA, parameters
//     and a command bit in DW4; read actual value, remaining distance, BA/M, attributes/error.
// The module steps its axes at the module cycle on the time the endpoint host passes in; the
// limit switches and the reference cam of each axis are mock inputs, actuated as a function of
// the pulses output (options). Thread: the endpoint host's thread only.

#include <array>
#include <chrono>
#include <functional>
#include <memory>
#include <optional>
#include <string>
#include <utility>

#include "hil/controllers/s5/ip247_axis.hpp"
#include "hil/controllers/s5/ip247_program_store.hpp"
#include "hil/mocks/legacy/s5_block_endpoint.hpp"

namespace hil::controllers::s5 {

/// Mock switches of one axis, as motor pulse positions.
struct Ip247AxisSwitches {
  std::optional<std::int64_t> limit_start_at;                ///< "start" switch actuated at position <= this
  std::optional<std::int64_t> limit_end_at;                  ///< "end" switch actuated at position >= this
  std::optional<std::pair<std::int64_t, std::int64_t>> cam;  ///< reference cam within [a, b]
};

struct Ip247ModuleOptions {
  std::chrono::nanoseconds cycle{std::chrono::milliseconds(1)};
  int sysid_module = 0;
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
  [[nodiscard]] Ip247Axis& axis(int n) { return *axes_[static_cast<std::size_t>(n - 1)]; }
  [[nodiscard]] Ip247ProgramStore& programs() noexcept { return programs_; }
  [[nodiscard]] const std::string& last_rejection() const noexcept { return rejection_; }
  /// Current raw inputs of axis n (from the mock switches).
  [[nodiscard]] Ip247Inputs inputs(int n) const;

 private:
  std::vector<std::uint16_t>& refresh(int n);

  Ip247ModuleOptions o_;
  Ip247ProgramStore programs_;
  std::array<std::unique_ptr<Ip247Axis>, 3> axes_;
  std::array<std::vector<std::uint16_t>, 3> iface_;
  std::array<int, 3> md_db_{-1, -1, -1};
  TimePoint t_{};
  bool started_ = false;
  std::string rejection_;
  Ip247ModuleHooks hooks_;
};

}  // namespace hil::controllers::s5
