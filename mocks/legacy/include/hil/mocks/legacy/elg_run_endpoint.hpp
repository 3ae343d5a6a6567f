// SPDX-License-Identifier: MIT
#pragma once
// The SINUMERIK ELG running behind its serial universal interface (`hilbridge emulate elg-tape
// --program`): the gearbox with its NC and PC (controllers::elg::HobbingMachine) steps cycle by cycle
// on the host's time, on simulated axes or, in retrofit mode (use_axes), on real-transport axes;
// the V.24 side (ElgTapeEndpoint) answers from the running model:
// - Data Start (a DC2 byte) is the PC signal A64.0, sampled at the next ELG cycle: with the coupling
//   ON the gearbox raises 2214 and nothing is transferred (manual 7.1, 11); otherwise the MD tape
//   (then the SD tape) is punched from the ELG's data store, which the PC data channel also writes.
// - A tape arriving while coupled is not read in (no V.24 transfer while coupled): 2214.
// - MD read in are stored (and punched again) but the running gearbox keeps the data it started
//   with: the ELG takes machine data at POWER ON (docs/elg.md).
// Thread: the host's (EndpointHost runs every call on one thread).

#include <functional>
#include <memory>
#include <vector>

#include "hil/controllers/elg/elg_controller.hpp"
#include "hil/controllers/elg/pc_data_image.hpp"
#include "hil/mocks/legacy/elg_tape_endpoint.hpp"

namespace hil::mocks::legacy {

struct ElgRunOptions {
  bool auto_start = true;  ///< NC start once the axes are enabled (else: start())
};

class ElgRunEndpoint final : public Endpoint {
 public:
  /// `setup` from controllers::elg::elg_setup_from_tape (the cycle is `cycle`); the MD/SD store of
  /// the tape side starts empty (set_datum / load_state fill it).
  ElgRunEndpoint(ElgDatumCheck check, controllers::elg::ElgSetup setup, controllers::elg::NcProgram program,
                 Duration cycle, ElgEndpointOptions o = {}, ElgRunOptions r = {});
  ~ElgRunEndpoint() override;

  /// Retrofit mode: the ELG's axes B, C, Z, X (, Y) in that order are these (real transports);
  /// `update` runs them one cycle (their transports and motion core) before each ELG cycle.
  /// Call before the first tick; needs at least four axes.
  void use_axes(std::vector<motion::Axis*> axes, std::function<void(const CycleTime&)> update);

  std::string on_bytes(std::span<const std::uint8_t> data, TimePoint now) override;
  std::string on_line_error(std::error_code ec, TimePoint now) override;
  std::string on_idle(TimePoint now) override;
  [[nodiscard]] TimePoint next_deadline() const override;
  bool take_dirty() override { return tape_.take_dirty(); }
  std::string save_state() const override { return tape_.save_state(); }
  std::expected<void, std::string> load_state(const std::string& text) { return tape_.load_state(text); }

  /// Runs the ELG cycles due up to `now` (at most 5000 at once; further behind: skipped).
  void tick(TimePoint now);
  /// NC start (cycle start), for `auto_start = false`.
  void start() noexcept { start_requested_ = true; }
  /// ELG-RESET for the next ELG cycle (a pulse: the ELG acts on its rising edge).
  void pulse_reset() noexcept { reset_pulse_ = true; }
  /// "Following error monitoring active" (A67.1), a level the NC does not drive here.
  void set_fe_monitor(bool on) noexcept { fe_monitor_ = on; }
  /// One request of the PC data channel (12.5) on the running ELG.
  controllers::elg::PcReply pc_request(const controllers::elg::PcRequest& request);

  [[nodiscard]] ElgTapeEndpoint& tape() noexcept { return tape_; }
  [[nodiscard]] const controllers::elg::HobbingMachine& machine() const noexcept { return *machine_; }
  /// The pending alarms: the gearbox's, then the V.24 alarm of the tape side (0 = none).
  [[nodiscard]] std::vector<int> alarms() const;
  /// One line: coupling, constants, tooth, NC state, C/B/Z actual values, alarms.
  [[nodiscard]] std::string status() const;
  [[nodiscard]] std::int64_t cycles() const noexcept { return cycles_; }

 private:
  void build();
  void cycle(TimePoint t);
  [[nodiscard]] controllers::elg::AxisFeedback feedback() const;

  ElgTapeEndpoint tape_;
  controllers::elg::ElgSetup setup_;
  controllers::elg::NcProgram program_;
  controllers::elg::DatumCheck pc_check_;
  Duration period_;
  ElgRunOptions run_;
  std::vector<std::unique_ptr<motion::Axis>> own_axes_;
  std::vector<motion::Axis*> axes_;
  std::function<void(const CycleTime&)> external_update_;
  std::unique_ptr<controllers::elg::HobbingMachine> machine_;
  std::unique_ptr<controllers::elg::PcDataImage> pc_;
  bool ticking_ = false;
  TimePoint next_cycle_{};
  bool enabled_ = false;
  bool nc_started_ = false;
  bool start_requested_ = false;
  bool reset_pulse_ = false;
  bool fe_monitor_ = false;
  bool data_start_pending_ = false;
  bool refusing_tape_ = false;
  std::string outbox_;
  std::int64_t cycles_ = 0;
};

}  // namespace hil::mocks::legacy
