// SPDX-License-Identifier: MIT
// CLM1.4 master encoder 1 and coupled motion (manual §5.7 FOL/FUN/AEO/VEO/SRP/MLO/MLT, §7.6;
// digest §4.2, §5.10, §5.12) on the coupling layer: a slave or synchronous axis is a
// hil::motion::Coupling with the gear law at the exact ratio of the FOL factor and both axes'
// scalings; moves programmed for it are the coupling's superimposed move.
#include <fmt/format.h>

#include <algorithm>
#include <cmath>

#include "hil/controllers/clm14/controller.hpp"
#include "hil/motion/gear_ratio.hpp"

namespace hil::controllers::clm14 {

namespace {

using motion::abs128;
using motion::gcd128;
using motion::i128;

std::int64_t e5(double feed_constant) {
  return static_cast<std::int64_t>(std::llround(feed_constant * 1e5));
}

/// FUN channels 0..6: axes 1..4, master encoder 1, master encoder 2, material through the tool;
/// the variables holding the running value and the buffer (§5.6).
constexpr std::array<std::pair<int, int>, 7> fun_vars{
    {{111, 112}, {211, 212}, {311, 312}, {411, 412}, {40, 41}, {42, 43}, {26, 25}}};

}  // namespace

motion::GearRatio clm_gear_ratio(Micro factor, std::int64_t slave_pulses, std::int64_t slave_feed_e5,
                                 std::int64_t master_pulses, std::int64_t master_feed_e5,
                                 Micro master_factor) noexcept {
  // slave inc / master inc = factor × (Ps·4 / Fs) / (Pm·4 / (Fm·k)) = factor·k·Ps·Fm / (Fs·Pm)
  i128 num = static_cast<i128>(factor) * master_factor * slave_pulses * master_feed_e5;
  i128 den = static_cast<i128>(micro_one) * micro_one * slave_feed_e5 * master_pulses;
  if (den <= 0 || slave_pulses <= 0 || master_feed_e5 <= 0) return {0, 1};
  if (const i128 g = gcd128(num, den); g > 1) {
    num /= g;
    den /= g;
  }
  const i128 lim = motion::max_gear_term;
  if (abs128(num) <= lim && den <= lim) return {static_cast<std::int64_t>(num), static_cast<std::int64_t>(den)};
  // The nearest fraction within the gear's bounds: the last continued-fraction convergent that
  // fits (its error is below 1 / (q·q'), far under one increment per 2^31 master increments).
  const bool neg = num < 0;
  i128 a = abs128(num), b = den;
  i128 p0 = 0, q0 = 1, p1 = 1, q1 = 0;
  while (b != 0) {
    const i128 q = a / b;
    const i128 p2 = q * p1 + p0, q2 = q * q1 + q0;
    if (p2 > lim || q2 > lim) break;
    p0 = p1;
    q0 = q1;
    p1 = p2;
    q1 = q2;
    const i128 r = a - q * b;
    a = b;
    b = r;
  }
  if (q1 == 0) return {neg ? -motion::max_gear_term : motion::max_gear_term, 1};
  return {static_cast<std::int64_t>(neg ? -p1 : p1), static_cast<std::int64_t>(q1)};
}

// ---- master encoder 1 -------------------------------------------------------------------------------

void Controller::attach_master_encoder(MasterEncoderPort* port) {
  me1_ = MasterIn{};
  me1_.port = port;
}

bool Controller::master_available() const noexcept {
  // test mode: the internal material clock stands in for the encoder (§7.12)
  return (me1_.port != nullptr || (flying_cutoff() && settings_.axes[0].test_mode)) && settings_.me1.used();
}

double Controller::me_iu_per_count() const noexcept {
  const auto& me = settings_.me1;
  if (!me.used()) return 0.0;
  return me.feed_constant * to_double(fak5_) / (static_cast<double>(me.pulses) * 4.0);
}

double Controller::master_position() const noexcept {
  return static_cast<double>(me1_.count) * me_iu_per_count();
}

double Controller::master_velocity() const noexcept {
  return me1_.velocity * me_iu_per_count();
}

void Controller::update_master_in() {
  std::int64_t encoder = 0;
  if (me1_.port != nullptr) {
    const std::int64_t raw = me1_.input.update(me1_.port->count());
    encoder = settings_.me1.inverted ? -raw : raw;
  }
  // test mode / No Material (C008): the count integrates the internal material speed instead
  update_internal_material(encoder, me1_.port != nullptr);
  if (me1_.port == nullptr && !me1_.internal) return;
  if (me1_.seen == 0) me1_.last = me1_.count;
  me1_.record(settings_.cycle_ms, !me1_.internal);  // the internal material sets its own velocity
  // status 54 (flying cutoff): material = all travel in Manual and Automatic; product = travel
  // in Automatic while the cut is not inhibited
  const double travel = static_cast<double>(me1_.count - me1_.last) * me_iu_per_count();
  me1_.last = me1_.count;
  if (flying_cutoff() && mode_ != Mode::parameter) {
    material_length_ += travel;
    if (mode_ == Mode::automatic && !cut_.inhibited) product_length_ += travel;
  }
}

// ---- coupling helpers ---------------------------------------------------------------------------------

double Controller::inc_per_iu(int axis) const {
  const auto& as = settings_.axes[static_cast<std::size_t>(axis - 1)];
  return static_cast<double>(std::max(1, as.encoder_pulses)) * 4.0 / as.feed_constant;
}

std::optional<std::int64_t> Controller::master_counts(int axis) const {
  const auto& as = settings_.axes[static_cast<std::size_t>(axis - 1)];
  if (as.mode == 5 || as.master == 5) {
    if (!master_available()) return std::nullopt;
    return me1_.count;
  }
  if (as.master >= 1 && as.master < axis) {
    const auto& m = axes_[static_cast<std::size_t>(as.master - 1)];
    if (m.port == nullptr || !settings_.axes[static_cast<std::size_t>(as.master - 1)].enabled) return std::nullopt;
    // synchronous (mode 1): the master's commanded moves; slave (mode 2): its actual position
    return as.mode == 1 ? m.fb.command_inc : m.fb.position_inc;
  }
  return std::nullopt;
}

std::optional<motion::GearRatio> Controller::follow_ratio(int axis, Micro factor) const {
  const auto& as = settings_.axes[static_cast<std::size_t>(axis - 1)];
  if (as.mode == 5 || as.master == 5) {
    if (!settings_.me1.used()) return std::nullopt;
    return clm_gear_ratio(factor, as.encoder_pulses, e5(as.feed_constant), settings_.me1.pulses,
                          e5(settings_.me1.feed_constant), fak5_);
  }
  if (as.master < 1 || as.master >= axis) return std::nullopt;
  const auto& ms = settings_.axes[static_cast<std::size_t>(as.master - 1)];
  return clm_gear_ratio(factor, as.encoder_pulses, e5(as.feed_constant), ms.encoder_pulses, e5(ms.feed_constant));
}

motion::SlaveLimits Controller::slave_limits(int axis) const {
  const auto& as = settings_.axes[static_cast<std::size_t>(axis - 1)];
  const double ipu = inc_per_iu(axis);
  motion::SlaveLimits l;
  // [decided] the coupled demand may reach 1.25 × Ax06 (as VEO 5's error 4D) and 10 × Ax08
  // (the axis' quick-stop rate); beyond that the coupling brakes the slave and the CLM reports
  // the slave's "Excess Pos Lag".
  l.velocity = 1.25 * as.vmax * ipu;
  l.acceleration = 10.0 * as.acceleration * ipu;
  int filter = static_cast<int>(velocity_window);
  if ((as.mode == 5 || as.master == 5) && settings_.me1.averaging > 0)
    filter = std::max(filter, 1 << settings_.me1.averaging);
  if (as.feedforward >= 2) filter = std::max(filter, 1 << (as.feedforward - 1));
  l.acceleration_filter_cycles = std::min(filter, 64);
  return l;
}

bool Controller::coupled(int axis) const noexcept {
  return axis >= 1 && axis <= 4 && follow_[static_cast<std::size_t>(axis - 1)].active;
}

std::int64_t Controller::follow_ramp(int axis, double dr) const {
  // FOL mode 2: the ratio changes over the master travel in which the slave reaches the new
  // velocity at its acceleration (Ax08 × ACC/Ax09 ‰): L = |Δr|·v_m² / a_slave.
  const auto& as = settings_.axes[static_cast<std::size_t>(axis - 1)];
  double vm = 0.0;
  if (as.master == 5)
    vm = me1_.velocity;
  else if (as.master >= 1 && as.master < axis)
    vm = axes_[static_cast<std::size_t>(as.master - 1)].fb.velocity * inc_per_iu(as.master);
  const double acc = limits_for(axis, as.vmax).acceleration * inc_per_iu(axis);
  const double l = std::abs(dr) * vm * vm / acc;
  return static_cast<std::int64_t>(std::min(std::ceil(l), static_cast<double>(std::int64_t{1} << 30)));
}

void Controller::pause_follow(int axis, bool pause) {
  // FOL mode 2 (§5.7): ramps down on Immediate Stop / JST, re-synchronises on Start.
  auto& f = follow_[static_cast<std::size_t>(axis - 1)];
  if (!f.active || !f.fol || f.mode != 2 || f.ending || f.paused == pause) return;
  auto& g = f.coupling.gear();
  if (g.phase() == motion::GearPhase::ramping) return;  // [decided] a running ratio ramp is not interrupted
  const auto ratio = pause ? std::optional<motion::GearRatio>{motion::GearRatio{0, 1}} : follow_ratio(axis, f.factor);
  if (!ratio) return;
  if (!g.change({*ratio, follow_ramp(axis, ratio->value() - g.ratio().value()), {}})) f.paused = pause;
}

void Controller::end_coupling(int axis, bool stop_axis) {
  auto& f = follow_[static_cast<std::size_t>(axis - 1)];
  if (!f.active) return;
  f.active = f.ending = f.paused = false;
  f.fol = false;
  f.coupling.use(motion::Coupling::Law::none);
  auto& a = axes_[static_cast<std::size_t>(axis - 1)];
  if (stop_axis && a.port != nullptr) a.port->stop();
}

void Controller::reset_coupled_state() {
  for (int ax = 1; ax <= 4; ++ax) {
    end_coupling(ax, true);
    auto& f = follow_[static_cast<std::size_t>(ax - 1)];
    f.mode = 1;  // §5.7 FOL: default after Parameter mode or an error
    f.factor = micro_one;
    auto& a = axes_[static_cast<std::size_t>(ax - 1)];
    a.override_master = false;
    a.aeo = false;
  }
  end_cutoff();
  mlo_ = {};
  srp_ = {};
  fak5_ = micro_one;
}

bool Controller::superimpose(int axis, double distance, double velocity, int t) {
  auto& f = follow_[static_cast<std::size_t>(axis - 1)];
  const double ipu = inc_per_iu(axis);
  const MoveLimits l = limits_for(axis, velocity);
  motion::Limits ml;
  ml.velocity = l.velocity * ipu;
  ml.acceleration = l.acceleration * ipu;
  ml.jerk = l.jerk * ipu;
  if (f.coupling.superimposed().move_by(distance * ipu, ml)) {
    fail(t, static_cast<int>(ClmError::invalid_program_command),
         fmt::format("the superimposed move of {:.3f} IU on following axis {} cannot be planned", distance, axis));
    return false;
  }
  return true;
}

double Controller::processed_length() const {
  // Material through the tool: master encoder 1 travel, minus the carriage's for a flying cutoff
  // (in sync the tool moves with the material, so nothing passes it).
  const double carriage = flying_cutoff() ? clm_position(1) : 0.0;
  return master_position() - carriage;
}

void Controller::update_measurements() {
  vars_[11] = master_available() ? to_micro(std::clamp(master_velocity(), -9.9e7, 9.9e7)) : 0;
  for (std::size_t ch = 0; ch < 7; ++ch) {
    std::optional<double> m;
    if (ch < 4) {
      if (axes_[ch].port != nullptr) m = clm_position(static_cast<int>(ch) + 1);
    } else if (ch == 4) {
      if (master_available()) m = master_position();
    } else if (ch == 5) {
      if (master2_available()) m = master2_position();
    } else if (ch == 6) {
      if (master_available()) m = processed_length();
    }
    if (!m) continue;
    vars_[static_cast<std::size_t>(fun_vars[ch].first)] = to_micro(std::clamp(*m - fun_ref_[ch], -9.9e7, 9.9e7));
  }
}

void Controller::step_srp() {
  if (!srp_.measuring) return;
  auto& a = axes_[0];
  const bool in = image_.bit(sys::raster1);
  const bool edge = in && !srp_.raster_last;
  srp_.raster_last = in;
  const double pos = clm_position(1);
  const double travelled = std::abs(pos - srp_.start);
  const auto var = [&](int k) { return to_double(vars_[static_cast<std::size_t>(srp_.base + k)]); };
  const double begin = std::abs(var(3));
  const double end = std::abs(var(4));
  if (edge && travelled >= begin && (end == 0.0 || travelled <= end)) {
    const double measured = a.target - pos;  // distance from the mark to the end position
    vars_[static_cast<std::size_t>(srp_.base)] = to_micro(measured);
    image_.set_byte(srp_.flag, static_cast<std::uint8_t>(image_.byte(srp_.flag) | 0x10U));
    const double maxc = std::abs(var(2));
    const double corr = std::clamp(var(1) - measured, -maxc, maxc);
    if (srp_.mode == 1) {
      srp_.correction = corr;
    } else if (srp_.mode == 2 && a.has_target && a.feeding) {
      a.target += corr;
      if (!a.held && !a.pending) a.port->move_to(raw_of(1, a.target), limits_for(1, a.velocity));
    }
    srp_.measuring = false;
  } else if (end != 0.0 && travelled > end) {
    srp_.measuring = false;
    srp_.missed = true;
  }
}

// ---- per cycle ------------------------------------------------------------------------------------------

void Controller::step_couplings(TimePoint now) {
  (void)now;
  step_srp();
  // MLO: each time the processed length passes another programmed length (Automatic only).
  if (mlo_.on && master_available() && mode_ == Mode::automatic && processed_length() - mlo_.ref > mlo_.length) {
    mlo_.ref += mlo_.length;
    write_bit(mlo_.bit, options_.mlo_toggles ? !image_.bit(mlo_.bit) : true);
  }
  // VEO source 5: the override follows master encoder 1 every cycle; a running feed is re-planned
  // when its velocity moves by more than 0.1 % [decided].
  for (int ax = 1; ax <= 4; ++ax) {
    auto& a = axes_[static_cast<std::size_t>(ax - 1)];
    if (!a.override_master || a.port == nullptr || error_ != 0) continue;
    const double ov = encoder_override(ax);
    if (ov > 1.25) {
      const bool me2 = a.override_encoder == 2;
      raise(axis_code(ClmError::max_override, ax),
            fmt::format("axis {}: VEO {} override {:.3f} from master encoder {} ({:.3f} IU/s) exceeds 1.25 × Vmax", ax,
                        me2 ? 6 : 5, ov, me2 ? 2 : 1, me2 ? master2_velocity() : master_velocity()));
      return;
    }
    a.master_override = ov;
    if (a.has_target && a.feeding && !a.held && !a.pending) {
      const double v = feed_velocity(ax, a.feed_permille);
      if (std::abs(v - a.velocity) > 0.001 * std::max(a.velocity, 1e-9)) {
        a.velocity = v;
        a.port->move_to(raw_of(ax, a.target), limits_for(ax, v));
      }
    }
  }
  step_cutoff();
  for (int ax = 1; ax <= 4; ++ax) {
    auto& f = follow_[static_cast<std::size_t>(ax - 1)];
    if (!f.active) continue;
    auto& a = axes_[static_cast<std::size_t>(ax - 1)];
    const auto master = master_counts(ax);
    if (!master || a.port == nullptr) {
      end_coupling(ax, true);
      continue;
    }
    f.coupling.superimposed().update(cycle_time());
    const auto& out = f.coupling.update(*master, cycle_time(), a.fb.position_inc);
    if (out.faulted) {
      const std::string text = f.coupling.fault().text;
      end_coupling(ax, true);
      if (error_ == 0) raise(axis_code(ClmError::position_lag, ax), fmt::format("axis {}: {}", ax, text));
      continue;
    }
    a.port->follow(out.position_inc, out.velocity_inc_per_s, out.acceleration_inc_per_s2);
    const auto& g = f.coupling.gear();
    if (f.ending && g.phase() == motion::GearPhase::steady && g.ratio().num == 0 && !f.coupling.superimposed().busy())
      end_coupling(ax, true);
  }
}

// ---- commands -------------------------------------------------------------------------------------------

Controller::Flow Controller::exec_coupled(int t, Task& k, const Instruction& in) {
  (void)k;
  const auto need_master = [&](std::string_view what) {
    if (master_available()) return true;
    fail(t, static_cast<int>(ClmError::invalid_program_command),
         fmt::format("{} needs master encoder 1 ({})", what,
                     settings_.me1.used() ? "none is attached: name it in the scenario's controller block"
                                          : "C002 = 0: not used"));
    return false;
  };
  switch (in.op) {
    case Op::fol: {
      auto ax_or = integer(in.n[0], t, 1, 4);
      auto m = integer(in.n[1], t, 0, 2);
      if (!ax_or || !m) return Flow::halt;
      const int ax = *ax_or;
      const Micro factor = *value(in.n[2], t);
      if (factor <= -10 * micro_one || factor >= 10 * micro_one) {
        fail(t, static_cast<int>(ClmError::variable_value), "FOL factor must be -9.999999..+9.999999");
        return Flow::halt;
      }
      if (t == 3) {
        fail(t, static_cast<int>(ClmError::invalid_program_command), "task 3 must not move axes");
        return Flow::halt;
      }
      auto& a = axes_[static_cast<std::size_t>(ax - 1)];
      const auto& as = settings_.axes[static_cast<std::size_t>(ax - 1)];
      if (!as.enabled || !a.software_enabled || a.port == nullptr) {
        fail(t, axis_code(ClmError::axis_disabled, ax),
             fmt::format("axis {} is not enabled (B000 or !M{}OFF)", ax, ax));
        return Flow::halt;
      }
      if (as.mode == 5) {
        fail(t, static_cast<int>(ClmError::invalid_program_command), "FOL on the flying cutoff axis");
        return Flow::halt;
      }
      auto& f = follow_[static_cast<std::size_t>(ax - 1)];
      f.factor = factor;                                    // also the VEO 5 multiplier
      if (as.mode != 1 && as.mode != 2) return Flow::next;  // a normal axis: only the multiplier [decided]
      if (as.master == 5 && !need_master("FOL from master encoder 1")) return Flow::halt;
      const auto master = master_counts(ax);
      const auto ratio = follow_ratio(ax, factor);
      if (!master || !ratio) {
        fail(t, static_cast<int>(ClmError::invalid_program_command),
             fmt::format("FOL axis {}: Ax00 names no usable master (master field {}: a lower axis or 5 = encoder 1)",
                         ax, as.master));
        return Flow::halt;
      }
      const auto ramp = [&](double dr) -> std::int64_t { return *m == 2 ? follow_ramp(ax, dr) : 0; };
      if (*m == 0) {
        if (!f.active) return Flow::next;
        if (f.mode == 2 && f.coupling.gear().phase() != motion::GearPhase::ramping) {
          if (f.coupling.gear().disengage(ramp(f.coupling.gear().ratio().value()))) return Flow::wait;
          f.ending = true;
        } else if (f.mode == 2) {
          return Flow::wait;  // a ratio ramp runs: the new one follows it
        } else {
          end_coupling(ax, true);
        }
        return Flow::next;
      }
      if (f.active && !f.ending) {
        // factor change: mode 1 steps, mode 2 re-synchronises over a ramp
        if (f.coupling.gear().phase() == motion::GearPhase::ramping) return Flow::wait;
        const double dr = ratio->value() - f.coupling.gear().ratio().value();
        f.mode = *m;
        f.paused = false;  // ramped out (Immediate Stop, B015): this FOL re-synchronises it
        if (f.coupling.gear().change({*ratio, ramp(dr), {}})) {
          fail(t, static_cast<int>(ClmError::invalid_program_command), "FOL: the ratio change was refused");
          return Flow::halt;
        }
        return Flow::next;
      }
      if (f.active && f.ending) return Flow::wait;  // still ramping out
      a.has_target = a.feeding = a.held = a.pending = a.con = false;
      if (a.jog) {
        a.port->stop();
        a.jog = false;
      }
      f.coupling = motion::Coupling(fmt::format("CLM axis {}", ax), slave_limits(ax));
      f.coupling.use(motion::Coupling::Law::gear);
      f.coupling.start(*master, a.fb.command_inc);
      if (f.coupling.gear().engage(*ratio, ramp(ratio->value()))) {
        fail(t, static_cast<int>(ClmError::invalid_program_command), "FOL: the ratio was refused");
        return Flow::halt;
      }
      f.active = f.fol = true;
      f.mode = *m;
      f.ending = f.paused = false;
      return Flow::next;
    }
    case Op::fun: {
      if (in.pattern[5] != 2 && !master2_available()) {
        fail(t, static_cast<int>(ClmError::invalid_program_command),
             "FUN: master encoder 2 (C004-C006) is not used or not connected; give 2 for its channel");
        return Flow::halt;
      }
      if ((in.pattern[4] != 2 || in.pattern[6] != 2) && !need_master("FUN on master encoder 1 / the tool"))
        return Flow::halt;
      update_measurements();  // the running values as of now
      for (std::size_t ch = 0; ch < 7; ++ch) {
        if (in.pattern[ch] == 2) continue;
        if (ch < 4 && axes_[ch].port == nullptr) continue;
        const auto [running, buffer] = fun_vars[ch];
        const Micro now_value = vars_[static_cast<std::size_t>(running)];
        if (in.pattern[ch] == 0) vars_[static_cast<std::size_t>(buffer)] = now_value;
        fun_ref_[ch] += to_double(now_value);
        vars_[static_cast<std::size_t>(running)] = 0;
      }
      return Flow::next;
    }
    case Op::aeo: {
      auto ax_or = integer(in.n[0], t, 1, 4);
      auto on = integer(in.n[1], t, 0, 1);
      auto enc = integer(in.n[2], t, 1, 1);
      auto scale = integer(in.n[3], t, 0, 999);
      auto min = integer(in.n[4], t, 0, 999);
      if (!ax_or || !on || !enc || !scale || !min) return Flow::halt;
      const auto& as = settings_.axes[static_cast<std::size_t>(*ax_or - 1)];
      if (as.mode != 0 || !master_available()) return Flow::next;  // §5.7 AEO: skipped
      auto& a = axes_[static_cast<std::size_t>(*ax_or - 1)];
      a.aeo = *on == 1;
      a.aeo_scale = *scale;
      a.aeo_min = *min;
      return Flow::next;
    }
    case Op::mlo:
    case Op::mlt: {
      auto ax = integer(in.n[0], t, 1, 1);
      auto len = length(in.n[1], t);
      if (!ax || !len) return Flow::halt;
      if (!need_master(mnemonic(in.op))) return Flow::halt;
      const double l = std::abs(to_double(*len));
      if (in.op == Op::mlt) {
        write_bit(in.bit, processed_length() - fun_ref_[6] > l);
        return Flow::next;
      }
      mlo_.on = l > 0.0;
      mlo_.bit = in.bit;
      mlo_.length = l;
      mlo_.ref = processed_length();
      return Flow::next;
    }
    case Op::srp: {
      auto ax = integer(in.n[0], t, 1, 4);
      auto m = integer(in.n[1], t, 0, 3);
      auto x = integer(in.n[2], t, 0, 9);
      if (!ax || !m || !x) return Flow::halt;
      if (*ax != 1) {
        fail(t, static_cast<int>(ClmError::invalid_program_command), "SRP measures on axis 1 (Raster 1) only");
        return Flow::halt;
      }
      if (in.var < 600 || in.var > 990) {
        fail(t, static_cast<int>(ClmError::variable_number),
             fmt::format("SRP variable block V{:03d} is outside V600..V990", in.var));
        return Flow::halt;
      }
      if (*m == 0) {
        srp_ = {};
        return Flow::next;
      }
      srp_.mode = *m;
      srp_.base = in.var;
      srp_.flag = in.byte;
      srp_.armed = true;
      srp_.measuring = srp_.missed = false;
      srp_.correction = 0.0;
      return Flow::next;
    }
    default:
      return exec_cutoff(t, k, in);
  }
}

}  // namespace hil::controllers::clm14
