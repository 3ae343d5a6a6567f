// SPDX-License-Identifier: MIT
#include "hil/mocks/legacy/elg_run_endpoint.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <utility>

#include "hil/mocks/sim_drive.hpp"

namespace hil::mocks::legacy {

namespace elg = controllers::elg;
using serial::tape::ElgSectionKind;

namespace {
constexpr std::uint8_t dc2 = 0x12;  // remote Data Start (docs/serial.md)

std::unique_ptr<motion::Axis> sim_axis(const motion::AxisConfig& config) {
  SimDriveConfig d;
  d.name = "sim:" + config.name;
  d.plant.kv_per_s = 200.0;
  d.plant.velocity_feedforward = 1.0;
  d.plant.max_velocity_inc_per_s = 1e9;
  return std::make_unique<motion::Axis>(config, std::make_unique<SimDrive>(d));
}
}  // namespace

ElgRunEndpoint::ElgRunEndpoint(ElgDatumCheck check, elg::ElgSetup setup, elg::NcProgram program, Duration cycle,
                               ElgEndpointOptions o, ElgRunOptions r)
    : tape_(check, o), setup_(std::move(setup)), program_(std::move(program)), period_(cycle), run_(r) {
  pc_check_ = [check](elg::DatumKind k, int n, const std::string& v) -> std::optional<std::string> {
    if (!check) return std::nullopt;
    return check(k == elg::DatumKind::machine_data ? ElgSectionKind::machine_data : ElgSectionKind::setting_data, n, v);
  };
  for (const auto& a : setup_.axes) own_axes_.push_back(sim_axis(a.config));
  for (auto& a : own_axes_) axes_.push_back(a.get());
  build();
}

ElgRunEndpoint::~ElgRunEndpoint() = default;

void ElgRunEndpoint::build() {
  auto* y = axes_.size() > 4 ? axes_[4] : nullptr;
  machine_ = std::make_unique<elg::HobbingMachine>(program_, setup_.config,
                                                   elg::HobbingAxes{axes_[0], axes_[1], axes_[2], axes_[3], y});
  // Axis numbers 1..4 of B, C, Z, Y from the measuring circuits (MD 5020/5021).
  auto number = [&](std::size_t i) { return i < setup_.circuits.size() ? setup_.circuits[i] + 1 : 0; };
  const elg::ElgAxisDeclaration decl{number(0), number(1), number(2), number(4)};
  pc_ = std::make_unique<elg::PcDataImage>(machine_->gearbox(), tape_.store(ElgSectionKind::machine_data),
                                           tape_.store(ElgSectionKind::setting_data), pc_check_, decl);
}

void ElgRunEndpoint::use_axes(std::vector<motion::Axis*> axes, std::function<void(const CycleTime&)> update) {
  axes_ = std::move(axes);
  own_axes_.clear();
  external_update_ = std::move(update);
  build();
}

elg::AxisFeedback ElgRunEndpoint::feedback() const {
  elg::AxisFeedback fb;
  fb.b = axes_[0]->status().position_inc;
  fb.z = axes_[2]->status().position_inc;
  if (axes_.size() > 4) fb.y = axes_[4]->status().position_inc;
  const auto& c = axes_[1]->status();
  fb.c = c.position_inc;
  fb.c_following_error = c.command_inc - c.position_inc;
  fb.c_in_position = !c.busy;
  return fb;
}

void ElgRunEndpoint::cycle(TimePoint t) {
  const CycleTime c{t, period_};
  if (external_update_) {
    external_update_(c);
  } else {
    for (auto* a : axes_) a->update(c);
  }
  // Power-up: the PC's controller enables, then NC start once every axis stands.
  if (!enabled_) {
    for (auto* a : axes_) (void)a->enable();
    enabled_ = true;
  }
  if (!nc_started_ && (run_.auto_start || start_requested_)) {
    bool ready = true;
    for (auto* a : axes_) ready = ready && a->status().state == motion::AxisState::standstill;
    if (ready) {
      machine_->start();
      nc_started_ = true;
    }
  }
  auto& s = machine_->pc_signals();
  s.reset = std::exchange(reset_pulse_, false);
  s.fe_monitor = fe_monitor_;
  s.data_start = data_start_pending_;
  machine_->step(c);
  pc_->update(feedback());
  if (data_start_pending_) {
    // Data Start sampled this cycle: with the coupling ON the gearbox raised 2214 and nothing
    // is transferred; otherwise the next section of the store is punched.
    if (machine_->gearbox().status().coupled) {
      tape_.report(2214, "ELG - OPERATION OF V.24 INTERFACE NOT PERMITTED: Data Start during Gearing ON");
    } else {
      outbox_ += tape_.data_start_output();
    }
    data_start_pending_ = false;
  }
  ++cycles_;
}

void ElgRunEndpoint::tick(TimePoint now) {
  if (!ticking_) {
    ticking_ = true;
    next_cycle_ = now;
  }
  for (int n = 0; next_cycle_ <= now && n < 5000; ++n) {
    cycle(next_cycle_);
    next_cycle_ += period_;
  }
  if (next_cycle_ <= now) next_cycle_ = now + period_;  // too far behind: skip, do not replay
}

TimePoint ElgRunEndpoint::next_deadline() const {
  if (!outbox_.empty() || !ticking_) return TimePoint{};
  return std::min(next_cycle_, tape_.next_deadline());
}

std::string ElgRunEndpoint::on_bytes(std::span<const std::uint8_t> data, TimePoint now) {
  tick(now);
  std::string out = std::exchange(outbox_, {});
  for (std::size_t i = 0; i < data.size(); ++i) {
    const std::uint8_t b = data[i];
    if (b == dc2 && !tape_.reading()) {
      data_start_pending_ = true;  // answered after the next ELG cycle (on_idle)
      continue;
    }
    if (machine_->gearbox().status().coupled) {
      // No V.24 transfer while coupled: the tape is not read in.
      if (b != 0x00 && !refusing_tape_) {
        machine_->gearbox().raise_message(elg::Alarm::v24_not_permitted);
        tape_.report(2214, "ELG - OPERATION OF V.24 INTERFACE NOT PERMITTED: tape input during Gearing ON");
        refusing_tape_ = true;
      }
      continue;
    }
    refusing_tape_ = false;
    out += tape_.on_bytes(data.subspan(i, 1), now);
  }
  return out;
}

std::string ElgRunEndpoint::on_line_error(std::error_code ec, TimePoint now) {
  tick(now);
  return tape_.on_line_error(ec, now);
}

std::string ElgRunEndpoint::on_idle(TimePoint now) {
  tick(now);
  std::string out = std::exchange(outbox_, {});
  out += tape_.on_idle(now);
  return out;
}

elg::PcReply ElgRunEndpoint::pc_request(const elg::PcRequest& request) {
  auto reply = pc_->request(request);
  if (reply.performed && request.write) tape_.mark_dirty();
  return reply;
}

std::vector<int> ElgRunEndpoint::alarms() const {
  std::vector<int> out;
  for (auto a : machine_->gearbox().alarms()) out.push_back(static_cast<int>(a));
  if (tape_.alarm() != 0 && std::find(out.begin(), out.end(), tape_.alarm()) == out.end()) out.push_back(tape_.alarm());
  return out;
}

std::string ElgRunEndpoint::status() const {
  const auto& st = machine_->gearbox().status();
  const char* nc = machine_->nc().state() == elg::NcState::running ? "running"
                   : machine_->nc().state() == elg::NcState::ended ? "ended"
                                                                   : "idle";
  std::string alarms;
  for (int a : this->alarms()) alarms += fmt::format(" {}", a);
  return fmt::format("coupled {} computed {} tooth {} gaps {} nc {} C {:.4f} B {:.4f} Z {:.4f} alarms{}",
                     st.coupled ? 1 : 0, st.computed ? 1 : 0, st.tooth, machine_->couplings(), nc,
                     axes_[1]->status().position, axes_[0]->status().position, axes_[2]->status().position,
                     alarms.empty() ? " none" : alarms);
}

}  // namespace hil::mocks::legacy
