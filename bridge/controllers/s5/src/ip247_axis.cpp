// SPDX-License-Identifier: MIT
#include "hil/controllers/s5/ip247_axis.hpp"

#include <cmath>
#include <cstdlib>

namespace hil::controllers::s5 {

using stepdir::Ip247Error;
using stepdir::Ip247MdError;
using Kind = Ip247Action::Kind;

namespace {
constexpr std::int64_t far_pulses = std::int64_t{1} << 40;  ///< "endless" jog / search target
bool outside(std::int64_t v) noexcept {
  return v <= -ip247_coordinate_limit || v >= ip247_coordinate_limit;
}
}  // namespace

Ip247Axis::Ip247Axis(Ip247ProgramStore& store, int axis_number, Ip247InterpreterOptions io)
    : store_(store), axis_(axis_number), interp_([&store](int n) { return store.find(n); }, io) {}

void Ip247Axis::raise(Ip247Error e) {
  error_ = static_cast<int>(e);
}

bool Ip247Axis::busy() const noexcept {
  return planner_ && (planner_->moving() || planner_->target() != planner_->position());
}

std::int64_t Ip247Axis::range() const noexcept {
  return md_ ? std::int64_t{md_->sw_end} - md_->sw_start : 1;
}

std::int64_t Ip247Axis::internal_position() const noexcept {
  return planner_ ? kin_.bu(planner_->position()) : 0;
}

std::int64_t Ip247Axis::actual() const noexcept {
  std::int64_t x = internal_position() + off_.zero() + off_.tool();
  if (md_ && md_->rotary) {
    const std::int64_t lo = md_->sw_start + off_.zero();
    x = lo + ip247_mod(x - lo, range());
  }
  return x;
}

std::int64_t Ip247Axis::remaining() const noexcept {
  return has_target_ ? target_p_ - internal_position() : 0;
}

int Ip247Axis::m_output() const noexcept {
  return phase_ == Phase::program || ba_ == 8 || ba_ == 9 ? m_ : 2;
}

std::uint8_t Ip247Axis::attributes() const noexcept {
  std::uint8_t a = 0;
  if (md_) {
    // Unit bits as printed (metric 10b, inch 00b, degree 01b).
    if (md_->unit == Ip247Unit::mm) a |= 0x02;
    if (md_->unit == Ip247Unit::degree) a |= 0x01;
  } else if (!faulty_md_) {
    a |= ip247_attr::md_missing;
  }
  if (pe_) a |= ip247_attr::position_reached;
  if (sync_) a |= ip247_attr::synchronous;
  if (teach_in_) a |= ip247_attr::teach_in;
  if (!referenced_) a |= ip247_attr::reference_missing;
  if (!running_) a |= ip247_attr::finished;
  return a;
}

Ip247MdError Ip247Axis::load_machine_data(const Ip247MachineData& md, int sysid_module) {
  if (running_) {
    raise(Ip247Error::axis_running);
    return static_cast<Ip247MdError>(1);
  }
  const Ip247MdError e = check_ip247_md(md, sysid_module);
  if (e != Ip247MdError::none) {
    raise(Ip247Error::faulty_machine_data);
    return e;
  }
  auto timing = stepdir::make_ip247_timing(
      md.pulse_us, stepdir::PulseRounding::up, md.fmax_hz,
      md.positive_edge ? stepdir::Polarity::positive_edge : stepdir::Polarity::negative_edge, 5'000, 5'000);
  if (!timing) {
    raise(Ip247Error::faulty_machine_data);
    return timing.error();
  }
  auto ramp = stepdir::Ip247Ramp::make(ip247_ramp_params(md), timing->min_period_ns());
  if (!ramp) {
    raise(Ip247Error::ramp_table_generation);
    return ramp.error();
  }
  // The reference point survives only if the reference-relevant MD are unchanged (§2.5).
  const auto& old = md_ ? md_ : deleted_md_;
  const bool keep_ref = old && referenced_ && old->reference_coordinate == md.reference_coordinate &&
                        old->pulses_per_rev == md.pulses_per_rev && old->gear_bu_per_rev == md.gear_bu_per_rev &&
                        old->reference_direction == md.reference_direction && old->reference_sync == md.reference_sync;
  const std::int64_t pulses = planner_ ? planner_->position() : deleted_pulses_;
  faulty_md_ = false;
  deleted_md_.reset();
  md_ = md;
  md_->md_error = 0;
  kin_ = ip247_kinematics(md);
  ramp_ = std::make_shared<const stepdir::Ip247Ramp>(std::move(*ramp));
  planner_ = std::make_unique<stepdir::StepPlanner>(*timing, ramp_, kin_.pulses(md.backlash));
  planner_->set_mode(stepdir::PlannerMode::ramp);
  planner_->set_position(keep_ref ? pulses : 0, 0);
  referenced_ = keep_ref;
  off_ = {};  // every MD input clears the zero and tool offsets
  return Ip247MdError::none;
}

Ip247Error Ip247Axis::delete_machine_data() {
  if (running_) return Ip247Error::axis_running;
  if (md_) deleted_md_ = md_;
  if (planner_) deleted_pulses_ = planner_->position();
  md_.reset();  // the "reference set" bit stays as it was
  planner_.reset();
  faulty_md_ = false;
  return Ip247Error::none;
}

void Ip247Axis::clear_error() {
  if (!running_) error_ = 0;
}

void Ip247Axis::power_restart(bool battery_ok) {
  if (phase_ == Phase::program && program_ >= 0) store_.release(program_);
  interp_.abort();
  phase_ = Phase::idle;
  running_ = false;
  pe_ = false;
  referenced_ = false;
  ba_ = 4;
  next_.reset();
  has_target_ = false;
  ext_wait_ = false;
  if (teach_in_) {
    teach_in_ = false;
    store_.teach_axis = 0;
  }
  if (!battery_ok) {
    md_.reset();
    planner_.reset();
    off_ = {};
  } else if (planner_) {
    planner_->set_position(kin_.pulses(md_->reference_coordinate), 0);
  }
  raise(Ip247Error::state_after_power_failure);
}

double Ip247Axis::clamp_speed(std::int32_t v, std::int32_t md_speed, bool& clamped) const noexcept {
  clamped = false;
  double s = v == 0 ? md_speed : v;
  if (s > kin_.vmax()) {
    s = kin_.vmax();
    clamped = true;
  } else if (s < 1.0 || kin_.frequency_hz(s) < 1.0) {
    s = std::max(1.0, 60.0 * kin_.resolution_bu() / 1000.0);
    clamped = true;
  }
  return s;
}

bool Ip247Axis::actuated_start(const Ip247Inputs& in) const noexcept {
  return md_ && (md_->limits_normally_closed ? !in.limit_start : in.limit_start);
}
bool Ip247Axis::actuated_end(const Ip247Inputs& in) const noexcept {
  return md_ && (md_->limits_normally_closed ? !in.limit_end : in.limit_end);
}

void Ip247Axis::go(std::int64_t target_pulses, double f_hz) {
  if (prev_in_.external_stop) {  // held until the falling edge of the start/stop input (message 6)
    ext_wait_ = true;
    held_target_ = target_pulses;
    held_f_ = f_hz;
    raise(Ip247Error::waits_for_external_start);
    return;
  }
  if (!planner_->move_to(target_pulses, f_hz)) raise(Ip247Error::speed_out_of_range);
}

void Ip247Axis::start_move(std::int64_t target_p, double speed, bool clamped) {
  if (clamped) raise(Ip247Error::speed_out_of_range);
  target_p_ = target_p;
  has_target_ = true;
  pe_ = false;
  go(kin_.pulses(target_p), kin_.frequency_hz(speed));
}

void Ip247Axis::set_m(int m) {
  if (m >= 0 && m != m_) {
    m_ = m;
    m_history_.push_back(m);
  }
}

void Ip247Axis::abort_job() {
  if (planner_ && busy()) planner_->halt();
  if (phase_ == Phase::program) {
    interp_.abort();
    if (program_ >= 0) store_.release(program_);
    program_ = -1;
    next_.reset();
  }
  ext_wait_ = false;
  phase_ = Phase::idle;  // running_ drops when the axis stands still (step)
}

void Ip247Axis::finish_job() {
  if (phase_ == Phase::program && program_ >= 0) store_.release(program_);
  program_ = -1;
  phase_ = Phase::idle;
  running_ = false;
}

void Ip247Axis::command(const Ip247Job& job) {
  if (job.ba == 17) {
    if (running_) {
      raise(Ip247Error::job_not_allowed);
      abort_job();
    } else {
      error_ = 0;
    }
    return;
  }
  error_ = 0;  // the next operating command acknowledges the latched error
  if (!md_ && job.ba != 4) {
    raise(Ip247Error::no_machine_data);
    return;
  }
  if (ext_wait_) {  // one job may wait for the external start; any new command deletes it
    ext_wait_ = false;
    if (job.command != Ip247Command::stop) raise(Ip247Error::job_not_allowed);
    if (phase_ == Phase::program) {
      abort_job();
    } else {
      phase_ = Phase::idle;
      running_ = false;
    }
    return;
  }
  // BB must be high while the power section is on (digest §1.2, error 53): a job that would
  // output pulses is not started while BB is low, since a drive that is off (or still in its reset
  // pulse) does not take them and the module's pulse count would no longer be the motor's.
  const bool moves = job.command != Ip247Command::stop && !(teach_in_ && job.command == Ip247Command::takeover) &&
                     (job.ba == 1 || job.ba == 2 || (job.ba == 5 && job.byte_param == 0) || job.ba == 6 ||
                      job.ba == 7 || job.ba == 8 || job.ba == 9);
  if (moves && !running_ && !bb_) {
    raise(Ip247Error::power_section_off);
    return;
  }
  if (phase_ == Phase::program && prog_ == ProgState::interrupted && !running_) {
    if (job.ba == ba_ && job.command == Ip247Command::takeover) {
      ++takeovers_;
      running_ = true;
      if (resume_ == Resume::motion) {
        prog_ = ProgState::motion;
        if (next_) {  // inside a G10 chain: the rest of the chain at the interrupted block's speed
          pe_ = false;
          target_p_ = next_->target;
          has_target_ = true;
          go(kin_.pulses(next_->target), kin_.frequency_hz(action_.speed));
        } else {
          start_move(action_.target, action_.speed, false);
        }
      } else if (resume_ == Resume::action) {
        execute(action_, now_);
      } else {
        prog_ = ProgState::fetch;
      }
      return;
    }
    abort_job();  // Stop, Start (restart below) or another BA ends the interrupted program
    if (!(job.ba == ba_ && job.command == Ip247Command::start)) return;
  }
  if (running_) {
    if (job.command == Ip247Command::stop || job.ba == 4) {
      if (phase_ == Phase::program && job.command == Ip247Command::stop) {
        interrupt();
      } else {
        abort_job();  // BA4: stop of the running BA; the BA shown stays the aborted one
      }
      return;
    }
    if (phase_ == Phase::program && prog_ == ProgState::wait_takeover && job.command == Ip247Command::takeover &&
        job.ba == ba_) {
      ++takeovers_;
      execute(action_, now_);
      return;
    }
    if (phase_ == Phase::jog && (job.ba == 1 || job.ba == 2) && job.ba != ba_ &&
        (job.command == Ip247Command::forward || job.command == Ip247Command::backward)) {
      pending_jog_ = job;  // switching jog 1/2 in motion: stop, then continue in the new mode
      planner_->halt();
      return;
    }
    raise(Ip247Error::job_not_allowed);
    abort_job();
    return;
  }
  if (job.ba == 4 || job.command == Ip247Command::stop) return;  // nothing runs
  const bool fwd = job.command == Ip247Command::forward;
  const bool dir_cmd = fwd || job.command == Ip247Command::backward;
  if (teach_in_) {
    const bool motion_ba = job.ba == 1 || job.ba == 2 || job.ba == 6 || job.ba == 7;
    if (motion_ba && job.command == Ip247Command::takeover) {
      teach_store();
      return;
    }
    if (!motion_ba && job.ba != 11) {
      raise(Ip247Error::mode_not_allowed_in_teach_in);
      return;
    }
  }
  const Ip247MachineData& md = *md_;
  const std::int64_t p = internal_position();
  bool clamped = false;
  switch (job.ba) {
    case 1:
    case 2: {
      if (!dir_cmd) return raise(Ip247Error::job_not_allowed);
      const int d = fwd ? 1 : -1;
      if (d == lock_dir_) return raise(d > 0 ? Ip247Error::limit_end_overrun : Ip247Error::limit_start_overrun);
      const double v = clamp_speed(job.speed, job.ba == 1 ? md.jog1 : md.jog2, clamped);
      if (clamped) raise(Ip247Error::speed_out_of_range);
      ba_ = job.ba;
      phase_ = Phase::jog;
      running_ = true;
      pe_ = false;
      has_target_ = false;
      jog_dir_ = d;
      go(planner_->position() + d * far_pulses, kin_.frequency_hz(v));
      return;
    }
    case 5:
      ba_ = 5;
      referenced_ = false;  // starting BA5 deletes the reference point
      if (job.byte_param != 0) {
        planner_->set_position(kin_.pulses(md.reference_coordinate), 0);  // set: no motion, no pattern reset
        referenced_ = true;
        pe_ = false;
        return;
      }
      phase_ = Phase::reference;
      running_ = true;
      pe_ = false;
      has_target_ = false;
      ref_seen_cam_ = false;
      single_steps_ = 0;
      ref_pattern_base_ = planner_->motor_position();  // the 100 ms RS pulse zeroes the pattern counters
      ref_ = prev_in_.reference ? RefPhase::leave : RefPhase::away;
      return;
    case 6:
    case 7: {
      if (job.ba == 6 && !referenced_) return raise(Ip247Error::reference_missing);
      std::int64_t target = 0;
      if (job.ba == 6) {
        if (dir_cmd && !md.rotary) return raise(Ip247Error::job_not_allowed);
        if (outside(job.value)) return raise(Ip247Error::illegal_path);
        if (md.rotary) {
          if (job.value < md.sw_start + off_.zero() || job.value > md.sw_end + off_.zero()) {
            return raise(Ip247Error::traversing_range_exceeded);
          }
          const Ip247Rotary rule =
              !dir_cmd ? Ip247Rotary::shortest : (fwd ? Ip247Rotary::forward : Ip247Rotary::backward);
          target = p + ip247_rotary_delta(p, job.value - off_.zero() - off_.tool(), range(), rule);
        } else {
          target = job.value - off_.zero() - off_.tool();
        }
      } else {
        if (!dir_cmd) return raise(Ip247Error::job_not_allowed);
        const std::int64_t d = fwd ? job.value : -job.value;
        if (std::llabs(d) > 2 * ip247_coordinate_limit) return raise(Ip247Error::illegal_path);
        target = p + d;
      }
      if (!md.rotary && referenced_ && (target < md.sw_start || target > md.sw_end)) {
        return raise(Ip247Error::traversing_range_exceeded);
      }
      const int d = ip247_sign(target - p);
      if (d != 0 && d == lock_dir_)
        return raise(d > 0 ? Ip247Error::limit_end_overrun : Ip247Error::limit_start_overrun);
      const double v = clamp_speed(job.speed, md.incremental_speed, clamped);
      ba_ = job.ba;
      phase_ = Phase::move;
      running_ = true;
      start_move(target, v, clamped);
      return;
    }
    case 8:
    case 9:
      if (!referenced_) return raise(Ip247Error::reference_missing);
      if (job.command != Ip247Command::start) return raise(Ip247Error::job_not_allowed);
      start_program(job);
      return;
    case 10:
      if (!referenced_) return raise(Ip247Error::reference_missing);
      if (store_.teach_axis != 0) return raise(Ip247Error::teach_in_exclusive);
      if (store_.find(job.byte_param) != nullptr) return raise(Ip247Error::program_exists);
      if (job.byte_param < 0 || job.byte_param > ip247_max_program_number) return raise(Ip247Error::job_not_allowed);
      ba_ = 10;
      teach_in_ = true;
      store_.teach_axis = axis_;
      teach_ = Ip247Program{};
      teach_.number = job.byte_param;
      return;
    case 11: {
      if (!teach_in_) return raise(Ip247Error::job_not_allowed);
      ba_ = 11;
      teach_in_ = false;
      store_.teach_axis = 0;
      Ip247Block end;
      end.number = static_cast<int>(teach_.blocks.size()) + 1;
      end.m = 2;
      teach_.blocks.push_back(end);
      const Ip247Error e = store_.write(teach_.number, make_ip247_program_text(teach_));
      if (e != Ip247Error::none) raise(e);
      return;
    }
    case 12:
    case 13: {
      if (outside(job.value)) return raise(Ip247Error::illegal_path);
      std::int64_t z = off_.zero_ba;
      if (job.ba == 12) {
        z += job.value - actual();
      } else {
        if (!dir_cmd) return raise(Ip247Error::job_not_allowed);
        z += fwd ? -job.value : job.value;
      }
      const std::int64_t zs = z + off_.zero_prog;
      if (outside(md.sw_start + zs) || outside(md.sw_end + zs) || outside(p + zs + off_.tool())) {
        return raise(Ip247Error::traversing_range_exceeded);
      }
      ba_ = job.ba;
      off_.zero_ba = z;
      return;
    }
    case 14:
      ba_ = 14;
      off_.zero_ba = 0;
      off_.zero_prog = 0;
      return;
    case 15: {
      if (!dir_cmd) return raise(Ip247Error::job_not_allowed);
      if (outside(job.value)) return raise(Ip247Error::illegal_path);
      const std::int64_t t = fwd ? job.value : -job.value;
      if (md.rotary && std::llabs(t) >= range()) return raise(Ip247Error::illegal_tool_offset);
      if (outside(p + off_.zero() + t)) return raise(Ip247Error::traversing_range_exceeded);
      ba_ = 15;
      off_.tool_ba = t;  // replaces every tool offset, including those of programs
      off_.tool_prog = 0;
      return;
    }
    case 16:
      ba_ = 16;
      off_.tool_ba = 0;
      off_.tool_prog = 0;
      return;
    default:
      raise(Ip247Error::job_not_allowed);
      return;
  }
}

void Ip247Axis::teach_store() {
  Ip247Block b;
  b.number = static_cast<int>(teach_.blocks.size()) + 1;
  b.x_milli = actual();
  b.f = md_->incremental_speed;
  teach_.blocks.push_back(b);
  raise(Ip247Error::block_stored);
}

bool Ip247Axis::start_program(const Ip247Job& job) {
  const Ip247Error e = interp_.start(job.byte_param, *md_, internal_position(), job.ba == 9);
  if (e != Ip247Error::none) {
    raise(e);
    return false;
  }
  program_ = job.byte_param;
  store_.acquire(program_);
  ba_ = job.ba;
  single_block_ = job.ba == 9;
  phase_ = Phase::program;
  prog_ = ProgState::fetch;
  running_ = true;
  pe_ = false;
  has_target_ = false;
  next_.reset();
  m_ = -1;
  m_history_.clear();
  takeovers_ = 0;
  set_m(ip247_m_none);
  return true;
}

void Ip247Axis::execute(const Ip247Action& a, std::int64_t now_ns) {
  action_ = a;
  set_m(a.m_output);
  if (a.kind == Kind::dwell) {
    pe_ = false;
    dwell_end_ = now_ns + a.dwell_ms * 1'000'000;
    prog_ = ProgState::dwell;
    return;
  }
  if (a.zero_length) {
    pe_ = true;
    prog_ = ProgState::fetch;
    return;
  }
  prog_ = ProgState::motion;
  start_move(a.target, a.speed, false);
  if (!a.flying) return;
  // G10: interpret the next block now and join it (the structural rules are the interpreter's).
  Ip247Action nx;
  for (int k = 0; k < 4 && nx.kind == Kind::pending; ++k) nx = interp_.next(off_);
  if (nx.kind != Kind::motion) {
    raise(nx.kind == Kind::fault ? nx.error : Ip247Error::block_not_interpreted);
    abort_job();
    return;
  }
  // Kinematic rules: the next block must be at least the braking distance of this one and long
  // enough to brake from its own speed.
  const double f_this = std::min(kin_.frequency_hz(a.speed), static_cast<double>(md_->fmax_hz));
  const double f_next = std::min(kin_.frequency_hz(nx.speed), static_cast<double>(md_->fmax_hz));
  const auto braking = [this](double f) {
    return f <= md_->fss_hz ? 0.0 : ramp_->distance_steps(ramp_->time_to_frequency(f));
  };
  const auto len = static_cast<double>(std::llabs(kin_.pulses(nx.target) - kin_.pulses(a.target)));
  if (len < braking(f_this) || len < braking(f_next)) {
    raise(Ip247Error::flying_change_failed);
    abort_job();
    return;
  }
  next_ = nx;
  transition_p_ = a.target;
  target_p_ = nx.target;
  go(kin_.pulses(nx.target), kin_.frequency_hz(a.speed));
}

void Ip247Axis::interrupt() {
  raise(Ip247Error::program_waits_for_continuation);
  switch (prog_) {
    case ProgState::wait_takeover:
      resume_ = Resume::action;
      break;
    case ProgState::dwell:
      pe_ = true;  // the dwell counts as elapsed
      resume_ = Resume::fetch;
      break;
    case ProgState::motion:
      planner_->halt();
      resume_ = Resume::motion;
      break;
    default:
      resume_ = Resume::fetch;
      break;
  }
  prog_ = ProgState::interrupted;
}

void Ip247Axis::program_step(std::int64_t now_ns) {
  for (int guard = 0; guard < 4; ++guard) {
    switch (prog_) {
      case ProgState::fetch: {
        const Ip247Action a = interp_.next(off_);
        if (a.kind == Kind::pending) return;
        if (a.kind == Kind::fault) {
          raise(a.error);
          finish_job();
          return;
        }
        if (a.kind == Kind::end) {
          set_m(2);
          has_target_ = false;
          finish_job();
          return;
        }
        if (a.halt_before) {
          action_ = a;
          prog_ = ProgState::wait_takeover;
          return;
        }
        execute(a, now_ns);
        if (prog_ != ProgState::fetch) return;
        break;  // zero-length: fetch again
      }
      case ProgState::motion: {
        const std::int64_t p = internal_position();
        if (next_) {
          const int d = ip247_sign(next_->target - action_.target);
          if ((p - transition_p_) * d >= 0) {  // flying change point passed: new speed, new M
            const Ip247Action nx = *next_;
            next_.reset();
            execute(nx, now_ns);
          }
          return;
        }
        if (!busy() && !ext_wait_) {
          pe_ = true;
          has_target_ = false;
          prog_ = ProgState::fetch;
          break;
        }
        return;
      }
      case ProgState::dwell:
        if (now_ns < dwell_end_) return;
        pe_ = true;
        prog_ = ProgState::fetch;
        break;
      case ProgState::interrupted:
        if (running_ && !busy()) {
          running_ = false;
          if (resume_ == Resume::motion && !next_ && planner_->position() == kin_.pulses(action_.target)) {
            pe_ = true;  // interrupted in the deceleration: the target is reached
            has_target_ = false;
            resume_ = Resume::fetch;
          }
        }
        return;
      case ProgState::wait_takeover:
      case ProgState::wait_start:
        return;
    }
  }
}

void Ip247Axis::reference_step(const Ip247Inputs& in) {
  const int rd = md_->reference_direction;
  const double f_ref = kin_.frequency_hz(md_->reference_speed);
  const double f_ss = md_->fss_hz;
  const std::int64_t pos = planner_->position();
  switch (ref_) {
    case RefPhase::away: {
      const bool limit = rd > 0 ? actuated_start(in) : actuated_end(in);  // the switch against the direction
      if (in.reference) ref_seen_cam_ = true;
      if (limit || (ref_seen_cam_ && !in.reference)) {  // reverse at the limit or at the end of the cam
        planner_->halt();
        if (!busy()) {
          ref_ = RefPhase::search;
          ref_seen_cam_ = false;
        }
        return;
      }
      if (!busy()) planner_->move_to(pos - rd * far_pulses, f_ref);
      return;
    }
    case RefPhase::search:
      if ((rd > 0 ? actuated_end(in) : actuated_start(in))) {
        planner_->halt();
        raise(rd > 0 ? Ip247Error::limit_end_overrun : Ip247Error::limit_start_overrun);
        abort_job();
        return;
      }
      if (in.reference) ref_seen_cam_ = true;
      if (ref_seen_cam_ && !in.reference) {  // past the cam: brake, then back at fss
        planner_->halt();
        if (!busy()) ref_ = RefPhase::back;
        return;
      }
      if (!busy()) planner_->move_to(pos + rd * far_pulses, f_ref);
      return;
    case RefPhase::back:
      if (in.reference) {
        planner_->stop_now();  // at fss the motor stops at once
        ref_ = RefPhase::leave;
        return;
      }
      if (!busy()) planner_->move_to(pos - rd * far_pulses, f_ss);
      return;
    case RefPhase::creep:
    case RefPhase::leave: {
      if (busy()) return;
      if (ref_ == RefPhase::leave && !in.reference) ref_ = RefPhase::creep;  // the cam is left
      if (ref_ == RefPhase::creep) {
        // Synchronous: continue to the first zero of the pattern counter (zeroed at the start).
        const bool synced =
            !md_->reference_sync || ip247_mod(planner_->motor_position() - ref_pattern_base_, md_->patterns) == 0;
        if (synced) {
          planner_->set_position(kin_.pulses(md_->reference_coordinate), rd);
          referenced_ = true;
          sync_ = md_->reference_sync;
          finish_job();
          return;
        }
      } else if (++single_steps_ > 2500) {
        raise(Ip247Error::reference_cam_defective);
        abort_job();
        return;
      }
      planner_->move_to(pos + rd, f_ss);  // single steps in the reference direction
      return;
    }
  }
}

void Ip247Axis::step(std::int64_t now_ns, std::int64_t period_ns, const Ip247Inputs& in,
                     std::vector<gpio::Edge>* edges) {
  now_ = now_ns;
  if (!planner_) {
    prev_in_ = in;
    bb_ = in.ready;
    first_step_ = false;
    return;
  }
  const bool rising_stop = !first_step_ && in.external_stop && !prev_in_.external_stop;
  const bool falling_stop = !first_step_ && !in.external_stop && prev_in_.external_stop;
  if (!first_step_ && !in.ready && prev_in_.ready) {  // BB lost: synchronisation lost, motion aborted
    sync_ = false;
    if (running_) {
      planner_->stop_now();
      raise(Ip247Error::power_section_off);
      abort_job();
    }
  }
  prev_in_ = in;
  bb_ = in.ready;
  first_step_ = false;
  if (ext_wait_ && falling_stop) {
    ext_wait_ = false;
    if (!planner_->move_to(held_target_, held_f_)) raise(Ip247Error::speed_out_of_range);
  } else if (rising_stop && running_ && !ext_wait_) {
    if (phase_ == Phase::program) {
      interrupt();
    } else {
      abort_job();
    }
    raise(Ip247Error::external_stop);
  }
  // Limit switches: only the one in the direction of travel, only while moving toward it.
  const int dir = busy() ? ip247_sign(planner_->target() - planner_->position()) : 0;
  if (phase_ != Phase::reference) {
    if ((dir > 0 && actuated_end(in)) || (dir < 0 && actuated_start(in))) {
      lock_dir_ = dir;
      abort_job();
      raise(dir > 0 ? Ip247Error::limit_end_overrun : Ip247Error::limit_start_overrun);
    }
  }
  if (lock_dir_ != 0 && dir == -lock_dir_ && !(lock_dir_ > 0 ? actuated_end(in) : actuated_start(in))) lock_dir_ = 0;
  // SW limits (linear axis with a reference point): braking starts on reaching them.
  if (phase_ == Phase::jog && referenced_ && !md_->rotary) {
    const std::int64_t p = internal_position();
    if ((dir > 0 && p >= md_->sw_end) || (dir < 0 && p <= md_->sw_start)) {
      abort_job();
      raise(dir > 0 ? Ip247Error::sw_limit_end_overrun : Ip247Error::sw_limit_start_overrun);
    }
  }
  switch (phase_) {
    case Phase::idle:
      if (running_ && !busy()) running_ = false;
      break;
    case Phase::jog:
      if (!busy() && !ext_wait_) {
        running_ = false;
        phase_ = Phase::idle;
        if (pending_jog_) {
          const Ip247Job j = *pending_jog_;
          pending_jog_.reset();
          command(j);
        }
      }
      break;
    case Phase::move:
      if (!busy() && !ext_wait_) {
        pe_ = planner_->position() == kin_.pulses(target_p_);
        has_target_ = !pe_;
        running_ = false;
        phase_ = Phase::idle;
      }
      break;
    case Phase::reference:
      reference_step(in);
      break;
    case Phase::program:
      program_step(now_ns);
      break;
  }
  if (edges != nullptr) {
    planner_->plan(now_ns, now_ns + period_ns, *edges);
  } else {
    scratch_.clear();
    planner_->plan(now_ns, now_ns + period_ns, scratch_);
  }
}

}  // namespace hil::controllers::s5
