// SPDX-License-Identifier: MIT
// CLM1.4 flying cutoff functions (manual §7.12, Ax33-Ax42, C008; digest §5.11, §3.8, §3.10):
// immediate cut and the manual cut vector (A134, indexing), cut inhibit (A133), rapid stop (A136,
// error 3B), maximum stroke (A137, error 3C), crop cut (A142), reverse optimisation (A139/A140),
// test mode (A100: the internal material clock) and No Material (C008: the material speed from a
// variable), and the material / product length counters of status 54. Decisions where the manual
// lost a detail are listed in docs/clm14.md ("Flying cutoff functions").
#include <fmt/format.h>

#include <algorithm>
#include <cmath>

#include "hil/controllers/clm14/controller.hpp"

namespace hil::controllers::clm14 {

double Controller::length_counter(int which) const noexcept {
  return which == 1 ? material_length_ : which == 2 ? product_length_ : 0.0;
}

void Controller::clear_length_counter(int which) noexcept {
  if (which == 1) material_length_ = 0.0;
  if (which == 2) product_length_ = 0.0;
}

double Controller::carriage_counts() const {
  const auto& a = axes_[0];
  const double ipc = me_iu_per_count();
  if (ipc <= 0.0) return 0.0;
  return (static_cast<double>(a.fb.command_inc) / inc_per_iu(1) + a.base + a.sac) / ipc;
}

bool Controller::carriage_home() const {
  // "carriage at position 0": no sync ramp has begun and the carriage stands at its origin
  const auto& f = follow_[0];
  const bool ramp_started =
      cut_.phase == Cutoff::Phase::synchronous || cut_.phase == Cutoff::Phase::returning ||
      cut_.phase == Cutoff::Phase::inhibited ||
      (cut_.phase == Cutoff::Phase::armed && f.active &&
       (f.coupling.gear().phase() == motion::GearPhase::ramping || f.coupling.gear().ratio().num != 0));
  const double window = std::max(settings_.axes[0].reached_window, 0.01);
  return !ramp_started && std::abs(clm_position(1)) <= window;
}

bool Controller::command_start_0000() {
  if (mode_ != Mode::manual) return false;
  start_0000_ = true;
  return true;
}

int Controller::cutoff_start_line() {
  // §7.12: "task 1 starts immediately on Manual -> Automatic at 'previous length instruction - 1',
  // or at 0000 per A138 / !CL0 / keys". 0000 also when no length instruction ran since power-up
  // or Parameter mode, or that line no longer holds one [decided].
  const auto& as = settings_.axes[0];
  const bool input = as.start_0000_input && image_.bit(*as.start_0000_input);
  const bool request = start_0000_ || input || as.always_0000;
  start_0000_ = false;
  const int l = cutoff_length_line_;
  if (request || l < 1 || l >= program_lines) return 0;
  const Op op = program_[static_cast<std::size_t>(l)].op;
  if (op != Op::lml && op != Op::lmk && op != Op::lmr) return 0;
  return l - 1;
}

void Controller::update_internal_material(std::int64_t encoder, bool have_encoder) {
  const auto& as = settings_.axes[0];
  const bool cutoff = flying_cutoff() && settings_.me1.used();
  const auto& nm = settings_.me1.no_material_input;
  const int var = settings_.me1.no_material_variable;
  const bool test = cutoff && as.test_mode;
  const bool no_material = cutoff && nm && image_.bit(*nm) && var >= 600 && var <= 999;
  if (test || no_material) {
    // The internal material: test mode's clock (32 key steps, 0..A106), or the speed in the C008
    // variable (IU/s, 0..A106) while "No Material" is set; the switch is instantaneous.
    double v = test ? as.vmax * test_step_ / (test_speed_steps - 1) : to_double(vars_[static_cast<std::size_t>(var)]);
    if (!test && (v < 0.0 || v > as.vmax)) {
      if (error_ == 0)
        raise(static_cast<int>(ClmError::variable_value),
              fmt::format("C008 No Material: V{:03d} = {:.3f} IU/s is outside 0..A106 ({:.3f} IU/s)", var, v, as.vmax),
              3, var);
      v = 0.0;
    }
    const double counts_per_s = v / me_iu_per_count();
    me1_.internal_rest += counts_per_s * settings_.cycle_ms / 1000.0;
    const double whole = std::floor(me1_.internal_rest);
    me1_.internal_rest -= whole;
    me1_.count += static_cast<std::int64_t>(whole);
    me1_.velocity = counts_per_s;
    me1_.internal = true;
    me1_.encoder = encoder;
    return;
  }
  if (me1_.internal) {
    // back on the encoder: it continues from where the internal material stands, with this
    // cycle's encoder travel
    me1_.internal = false;
    me1_.internal_rest = 0.0;
    me1_.offset = me1_.count - me1_.encoder;
  }
  if (have_encoder) me1_.count = encoder + me1_.offset;
  me1_.encoder = encoder;
}

void Controller::cutoff_program(int line, int code) {
  // Task 1 continues at the function's program (it ends with EOS, still in sync); its EOS stops
  // the carriage with the function's error.
  Task& t1 = tasks_[0];
  t1.pc = line;
  t1.stack.clear();
  t1.phase = 0;
  if (mat_owner_ == 1) mat_owner_ = -1;
  cut_.pending_error = code;
}

void Controller::cutoff_stop(int code, std::string message) {
  raise(code, std::move(message));
  // command 0 V without a ramp (the coupling ended with the error)
  if (axes_[0].port != nullptr) axes_[0].port->quick_stop();
}

double Controller::optimised_return_acceleration() const {
  // A139/A140: the return is planned to arrive at the origin A140's wait time before the next
  // sync ramp starts, assuming the next part is as long as this one [decided]; the acceleration
  // lies between A140's minimum (‰ of A108, at least 1 ‰) and A108.
  const auto& as = settings_.axes[0];
  const double a108 = limits_for(1, as.vmax).acceleration;
  const double amin = std::min(a108, std::max(a108 * as.reverse_min_accel_permille / 1000.0, a108 / 1000.0));
  const double ipc = me_iu_per_count();
  const double vm = std::abs(master_velocity());
  const double d = std::abs(clm_position(1));
  const double vr = feed_velocity(1, 1000);
  if (vm <= 0.0 || d <= 0.0 || cut_.part <= 0 || ipc <= 0.0) return a108;
  const double ramp_start = static_cast<double>(cut_.last_cut + cut_.part - cutoff_ramp() / 2);
  const double t = (ramp_start - static_cast<double>(me1_.count)) * ipc / vm - as.reverse_wait_s;
  double a = a108;
  if (t <= 0.0)
    return a108;
  else if (2.0 * d / t <= vr)
    a = 4.0 * d / (t * t);  // triangle: d = a (t/2)²
  else if (t > d / vr)
    a = vr / (t - d / vr);  // trapezoid at the return velocity: t = d/v + v/a
  return std::clamp(a, amin, a108);
}

void Controller::command_return(bool optimise) {
  const auto& as = settings_.axes[0];
  cut_.return_acceleration = 0.0;
  cut_.phase = Cutoff::Phase::returning;
  if (optimise && as.reverse_opt_input && image_.bit(*as.reverse_opt_input)) {
    // A139: the forward motion brakes at A108; the reverse move is planned once the carriage stands
    cut_.braking = true;
    axes_[0].port->stop();
    return;
  }
  (void)command_move(1, 0.0, feed_velocity(1, 1000), 1);
}

void Controller::step_optimised_return() {
  if (cut_.phase != Cutoff::Phase::returning || !cut_.braking || axes_[0].fb.busy) return;
  cut_.braking = false;
  cut_.return_acceleration = optimised_return_acceleration();
  cut_.return_material_speed = std::abs(master_velocity());
  (void)command_move(1, 0.0, feed_velocity(1, 1000), 1);
}

void Controller::step_cutoff_inputs() {
  const auto& as = settings_.axes[0];
  const auto edge = [&](const std::optional<BitAddress>& b) {
    return b && image_.bit(*b) && !previous_inputs_.bit(*b);
  };
  // A138 input "start at instruction 0000": a rising edge in Manual makes the next entry into
  // Automatic start at 0000 (its level at that entry does too).
  if (mode_ == Mode::manual && edge(as.start_0000_input)) start_0000_ = true;
  auto& f = follow_[0];
  auto& g = f.coupling.gear();
  // The manual cut vector (A134 in Manual): the program at A134's start line, ending with RTS
  // (no feeds; jog is off meanwhile). Its material point is the reference for indexing.
  if (mode_ == Mode::manual && error_ == 0 && !tasks_[0].manual_vector && edge(as.immediate_cut_input)) {
    start_manual_vector(as.manual_cut_line);
    if (master_available()) manual_cut_ = me1_.count - std::llround(carriage_counts());
  }
  if (as.reverse_opt_output)
    write_bit(*as.reverse_opt_output,
              cut_.phase == Cutoff::Phase::returning && (cut_.braking || cut_.return_acceleration > 0.0));
  if (as.cut_inhibit_output) write_bit(*as.cut_inhibit_output, cut_.inhibited);
  if (mode_ != Mode::automatic || error_ != 0 || !master_available()) return;
  const bool waiting =
      cut_.phase == Cutoff::Phase::armed && f.active && !cut_.at_once &&
      (g.phase() == motion::GearPhase::armed || (g.phase() == motion::GearPhase::steady && g.ratio().num == 0));
  // Cut inhibit (A133): a pulse suppresses the sync until Immediate cut; an engage armed and not
  // yet begun is withdrawn. A pulse during the ramp or in sync acts from the next part [decided].
  if (edge(as.cut_inhibit_input)) cut_.inhibited = true;
  if (cut_.inhibited && waiting && g.phase() == motion::GearPhase::armed) (void)g.engage(motion::GearRatio{0, 1});
  // Immediate cut (A134 in Automatic, carriage at its origin): sync now and cut; ends the inhibit.
  if (edge(as.immediate_cut_input) && carriage_home()) {
    cut_.inhibited = false;
    const auto ratio = follow_ratio(1, micro_one);
    if (waiting && ratio) {
      cut_.ramp = cutoff_ramp();
      if (!g.engage(*ratio, cut_.ramp)) cut_.at_once = true;
    } else {
      cut_.immediate = true;  // the next length instruction syncs at once
    }
  }
  // Crop cut (A142): a rising edge while the carriage is home makes this part (or the next) the
  // crop length, measured from the last cut.
  if (edge(as.crop_input) && carriage_home() && as.crop_length > 0.0) {
    if (waiting && cut_.have_last) {
      cut_.part = std::llround(as.crop_length / me_iu_per_count());
      cut_.cut_at = cut_.last_cut + cut_.part;
      if (!cut_.inhibited) (void)arm_cutoff_engage();
    } else {
      cut_.crop = true;
    }
  }
  // Travel limit first: 0 V and 47 (46 below A103); the carriage's origin is position 0.
  const double pos = clm_position(1);
  if (pos > as.max_limit || pos < as.min_limit) {
    const bool above = pos > as.max_limit;
    cutoff_stop(axis_code(above ? ClmError::max_travel : ClmError::min_travel, 1),
                fmt::format("flying cutoff: the carriage at {:.3f} IU is beyond {} ({:.3f})", pos,
                            above ? "A104" : "A103", above ? as.max_limit : as.min_limit));
    return;
  }
  if (cut_.pending_error != 0) return;
  // Rapid stop (A136): in sync the rapid-stop program runs (still in sync) and its EOS stops with
  // 3B; otherwise 0 V and 3B at once.
  if (edge(as.rapid_stop_input)) {
    if (cut_.phase == Cutoff::Phase::synchronous && as.rapid_stop_line != 0)
      cutoff_program(as.rapid_stop_line, static_cast<int>(ClmError::rapid_stop));
    else
      cutoff_stop(static_cast<int>(ClmError::rapid_stop), "flying cutoff: rapid stop input (A136)");
    return;
  }
  // Maximum stroke (A137): in sync with less than the stroke left to A104, the program runs and
  // its EOS stops with 3C (no program, or still in the ramp: 0 V and 3C at once).
  const bool moving = cut_.phase == Cutoff::Phase::synchronous ||
                      (cut_.phase == Cutoff::Phase::armed && g.phase() == motion::GearPhase::ramping);
  if (as.max_stroke > 0.0 && moving && as.max_limit - pos < as.max_stroke) {
    if (cut_.phase == Cutoff::Phase::synchronous && as.max_stroke_line != 0)
      cutoff_program(as.max_stroke_line, static_cast<int>(ClmError::max_stroke_limit));
    else
      cutoff_stop(static_cast<int>(ClmError::max_stroke_limit),
                  fmt::format("flying cutoff: maximum stroke (A137): {:.3f} IU left to A104, stroke {:.3f} IU",
                              as.max_limit - pos, as.max_stroke));
    return;
  }
  // Reverse optimisation: the material speeds up by more than A140's window -> back to A108.
  if (cut_.phase == Cutoff::Phase::returning && cut_.return_acceleration > 0.0 &&
      std::abs(master_velocity()) - cut_.return_material_speed >
          as.vmax * as.reverse_velocity_window_permille / 1000.0) {
    cut_.return_acceleration = 0.0;
    (void)command_move(1, 0.0, feed_velocity(1, 1000), 1);
  }
}

}  // namespace hil::controllers::clm14
