// SPDX-License-Identifier: MIT
// WF 725/726 on the controller runtime: modes, submodes, the DB axis, data codes, limits and
// errors (docs/wf725.md). The traversing programs are in wf725_controller_program.cpp.
#include "hil/controllers/s5/wf725_controller.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <cmath>
#include <fstream>
#include <sstream>

#include "hil/controllers/io_address_s5.hpp"
#include "hil/controllers/parameter_controller.hpp"

namespace hil::controllers::s5 {
namespace {

using namespace wf_db;

IoLayout wf_layout() {
  return IoLayout{{4, 2, 1, 2U * wf_db::words}};
}

}  // namespace

Wf725Controller::Wf725Controller(LoadedParameters parameters, Wf725MachineData md, ControllerAxis axis, Duration cycle,
                                 Wf725Options options)
    : Controller(parameters.profile, std::move(parameters.set), wf_layout(), cycle),
      md_(md),
      opt_(options),
      store_(std::make_shared<Wf725ProgramStore>(wf725_memory_limits(md.series))),
      db_(io(), S5DataBlock{options.db, 0, wf_db::words}) {
  traversing_cat_ = catalogue("traversing");
  io_cat_ = catalogue("program_io");
  admin_cat_ = catalogue("memory_admin");
  standard2_cat_ = catalogue("standard2");
  store_user_ = store_->add_user([this](int n) { return runs_stored_program(n); });
  std::copy(std::begin(opt_.ref_speeds), std::end(opt_.ref_speeds), std::begin(ref_speeds_));
  if (auto syntax = wf725_program_syntax(profile())) syntax_ = *syntax;
  jog_feed_ = opt_.jog_feed;
  const std::string s = "_" + axis.name;
  for (std::uint8_t e = 0; e < 6; ++e) {
    (void)io().name_bit(fmt::format("x7_e{}", e + 1), {IoArea::input, 0, e});
    (void)io().name_bit(fmt::format("x7_a{}", e + 1), {IoArea::output, 0, e});
  }
  const BitAddress minus{IoArea::input, 1, 0}, plus{IoArea::input, 1, 1};
  (void)io().name_bit("limit_minus" + s, minus);
  (void)io().name_bit("limit_plus" + s, plus);
  axis.limit_switches.negative = minus;
  axis.limit_switches.positive = plus;
  (void)io().name_bit("in_position" + s, {IoArea::output, 1, 0});
  (void)io().name_bit("moving" + s, {IoArea::output, 1, 1});
  (void)io().name_bit("error" + s, {IoArea::output, 1, 2});
  (void)io().name_bit("drive_enable" + s, {IoArea::output, 1, 3});
  (void)io().name_bit("device_error", {IoArea::marker, 0, 0});
  // Encoder fault inputs (our model of the measuring circuit, docs/wf725.md "Encoder faults").
  constexpr const char* faults[] = {"encoder_cable_break",  "encoder_level_low",    "encoder_zero_mark_missing",
                                    "encoder_pulse_loss",   "encoder_parity_error", "encoder_telegram_fault",
                                    "encoder_position_jump"};
  for (std::uint8_t b = 0; b < 7; ++b) (void)io().name_bit(faults[b] + s, {IoArea::input, 2, b});
  // Voltage fault inputs (our model of the ADC checks, docs/wf725.md "Voltage checks"): input byte 3.
  constexpr const char* supplies[] = {"adc_fault",         "supply_15v_fault", "supply_p15v_fault",
                                      "supply_m15v_fault", "fuse_5v_blown",    "fuse_24v_blown"};
  for (std::uint8_t b = 0; b < 6; ++b) (void)io().name_bit(supplies[b], {IoArea::input, 3, b});
  (void)io().name_bit("dac_short" + s, {IoArea::input, 3, 6});
  const auto d = [&](const char* name, std::uint16_t w, std::uint8_t b) {
    (void)io().name_bit(name + s, db_.bit_address(w, b));
  };
  d("traversing", dw_mode, bit_mode_traversing);
  d("program_io", dw_mode, bit_mode_program_io);
  d("machine_data", dw_mode, bit_mode_machine_data);
  d("submode_1", dw_mode, 0);
  d("submode_2", dw_mode, 1);
  d("submode_4", dw_mode, 2);
  d("submode_8", dw_mode, 3);
  d("start", dw_control, bit_start);
  d("plus", dw_control, bit_plus);
  d("stop", dw_control, bit_stop);
  d("minus", dw_control, bit_minus);
  d("reset", dw_control, bit_reset);
  d("skip_block", dw_control, bit_skip);
  d("ram", dw_control, bit_ram);
  d("rf", dw_enable, bit_drive_enable);
  d("cam_bit", dw_enable, bit_cam);
  d("m_ack", dw_enable, bit_m_ack);
  d("peh", dw_status, bit_peh);
  d("moving_plus", dw_status, bit_moving_plus);
  d("moving_minus", dw_status, bit_moving_minus);
  d("pre_limit", dw_status, bit_pre_limit);
  d("limit_switch", dw_status, bit_limit);
  d("error_strobe", dw_status, bit_error);
  d("syn", dw_status, bit_syn);
  d("m_strobe", dw_status, bit_m_strobe);
  d("data_execute", dw_data_execute, 0);
  d("data_done", dw_data_status, 0);
  d("data_refused", dw_data_status, 1);
  d("waits_start", dw_flags, 0);
  d("program_active", dw_flags, 1);
  d("waits_enable", dw_flags, 2);
  // The deceleration cam: D 2.1 with MD 15 = 1 (cam source over S5), else X7 E1/E2/E3 of axis A/B/C.
  const auto axis_index = static_cast<std::uint8_t>(std::clamp(opt_.axis - 'A', 0, 2));
  cam_bit_ = (!md_.fast_input_map() && md_.integer(15) == 1) ? db_.bit_address(dw_enable, bit_cam)
                                                             : BitAddress{IoArea::input, 0, axis_index};
  (void)io().name_bit("reference_cam" + s, *cam_bit_);
  if (axis.reference) axis.reference->cam = cam_bit_;
  add_axis(std::move(axis));
}

std::expected<BitAddress, std::string> Wf725Controller::resolve_bit(std::string_view text) const {
  if (auto a = io().find_bit(text)) return *a;
  if (auto s = parse_s5_address(text, opt_.db); s && s->is_bit()) {
    const S5DataBlock blocks[] = {db_.block()};
    if (auto b = to_bit_address(*s, blocks))
      return *b;
    else
      return std::unexpected(b.error());
  }
  std::string names;
  for (const auto& sig : io().signals()) names += (names.empty() ? "" : ", ") + sig.name;
  return std::unexpected(
      fmt::format("'{}' is neither an I/O name of the wf725-726 controller ({}) nor an S5 "
                  "address (E 0.0, A 1.0, DB{} D 2.0)",
                  text, names, opt_.db));
}

double Wf725Controller::to_machine(double axis_mm) const noexcept {
  double m = axis_mm + offset_mm_;
  if (md_.rotary()) {
    const double mod = static_cast<double>(md_.integer(18)) * um;
    m = std::fmod(m, mod);
    if (m < 0) m += mod;
  }
  return m;
}

double Wf725Controller::machine_mm() const noexcept {
  return to_machine(axis(0).status().position);
}

double Wf725Controller::machine_command_mm() const noexcept {
  return to_machine(axis(0).status().command_position);
}

double Wf725Controller::actual_um() const noexcept {
  return (machine_mm() + zero_shift_mm_) / um;
}

bool Wf725Controller::cam() const noexcept {
  return cam_bit_ && io().get(*cam_bit_);
}

bool Wf725Controller::fast_input(int e) const noexcept {
  return e >= 1 && e <= 6 && io().get(BitAddress{IoArea::input, 0, static_cast<std::uint8_t>(e - 1)});
}

bool Wf725Controller::motion_done() const noexcept {
  if (open_loop()) return ol_done();
  const auto& st = axis(0).status();
  return !st.busy && st.state != motion::AxisState::moving && st.state != motion::AxisState::stopping;
}

motion::Direction Wf725Controller::rotary_direction() const noexcept {
  // §4.3 MD 18: G90 on a rotary axis goes the way D 1.1 / D 1.3 select; neither or both: shortest.
  const bool plus = db_.bit(dw_control, bit_plus), minus = db_.bit(dw_control, bit_minus);
  if (plus == minus) return motion::Direction::shortest;
  return plus ? motion::Direction::positive : motion::Direction::negative;
}

// ---- errors ----------------------------------------------------------------------------------

void Wf725Controller::raise_wf(int code, TimePoint now, std::string_view context) {
  if (traversing_cat_ != nullptr) raise(*traversing_cat_, code, now, 0, context);
}

void Wf725Controller::raise_io(int code, TimePoint now, std::string_view context, std::string_view catalogue_id) {
  const auto* c = catalogue(catalogue_id);
  if (c != nullptr) raise(*c, code, now, 0, context);
  db_.set_bit(dw_data_status, 1, true);
}

void Wf725Controller::clear_self_acknowledging() noexcept {
  std::vector<std::pair<const profiles::ErrorCatalogue*, int>> drop;
  for (const auto& e : errors().active())
    if (e.ack == AckRule::self_clearing) drop.emplace_back(e.catalogue, e.code);
  for (const auto& [c, code] : drop) (void)clear_error(*c, code, 0);
}

bool Wf725Controller::has_error_below_60() const noexcept {
  return std::any_of(errors().active().begin(), errors().active().end(),
                     [&](const DeviceError& e) { return e.catalogue == traversing_cat_ && e.code < 0x60; });
}

bool Wf725Controller::has_error(int code) const noexcept {
  return std::any_of(errors().active().begin(), errors().active().end(),
                     [&](const DeviceError& e) { return e.catalogue == traversing_cat_ && e.code == code; });
}

std::optional<DeviceErrorCode> Wf725Controller::map_axis_fault(std::size_t i, const hil::Fault& fault,
                                                               const motion::AxisStatus&) const noexcept {
  if (traversing_cat_ == nullptr) return std::nullopt;
  static const DeviceFaultMap map = wf725_faults();
  const auto code = map.code(i, fault.code, fault.code == ControllerFault::hard_limit_negative);
  if (!code) return std::nullopt;
  return DeviceErrorCode{traversing_cat_, *code};
}

// ---- the cycle -------------------------------------------------------------------------------

void Wf725Controller::on_cycle(const CycleTime& cycle) noexcept {
  const TimePoint now = cycle.now;
  last_now_ = now;
  if (db_.rising(dw_control, bit_reset)) {
    // RESET: aborts the job and clears every error a reset may clear (§5.1 acknowledgement types).
    abort_job();
    (void)acknowledge(Acknowledgement::reset);
  }
  handle_mode(now);
  drift_cycle(now);
  encoder_cycle(now);
  voltage_cycle(now);
  handle_drive(now);
  if (db_.rising(dw_data_execute, 0)) {
    handle_data_code(now);
  } else if (!db_.bit(dw_data_execute, 0)) {
    db_.set_bit(dw_data_status, 0, false);
    db_.set_bit(dw_data_status, 1, false);
  }
  if (traversing_) {
    const auto sub = static_cast<Submode>(db_.dr(dw_mode));
    if (sub != submode_) {
      // A change of submode ends the job and cancels the zero offsets (§4.3 MD 11-14).
      abort_job();
      submode_ = sub;
      zero_shift_mm_ = 0.0;
      g92_active_ = g54_active_ = false;
    }
    handle_start(now);
    if (open_loop()) ol_cycle(now);
    run_job(cycle);
    if (open_loop()) {
      ol_check_limits(now);
    } else {
      check_limits(now);
    }
  }
  split_cycle(now);  // split drive MD 27/29 (wf725_split_drive.cpp)
  m_cycle(now);
  write_status();
  db_.end_cycle();
}

void Wf725Controller::handle_mode(TimePoint now) {
  const std::uint8_t bits = db_.dl(dw_mode) & 0x07;
  const std::uint8_t before = static_cast<std::uint8_t>(db_.previous_word(dw_mode) >> 8) & 0x07;
  if (bits == before || std::popcount(bits) != 1 || bits == mode_bits_) return;
  if (bits == (1U << (bit_mode_traversing - 8))) {
    // Checks on each selection of traversing (§4.3): a failing set keeps the module out of it.
    if (const int code = check_wf725_mode_change(md_)) {
      raise_wf(code, now, "selection of mode traversing refused");
      return;
    }
    traversing_ = true;
  } else {
    abort_job();
    traversing_ = false;
  }
  mode_bits_ = bits;
}

void Wf725Controller::handle_drive(TimePoint now) {
  auto& ax = axis(0);
  const auto& st = ax.status();
  const bool rf = db_.bit(dw_enable, bit_drive_enable);
  const bool drive_off_error =
      std::any_of(errors().active().begin(), errors().active().end(), [](const DeviceError& e) {
        return e.reaction == profiles::Reaction::drive_off || e.reaction == profiles::Reaction::needs_reset;
      });
  const bool want = rf && !drive_off_error;
  if (want && st.state == motion::AxisState::disabled) {
    (void)ax.enable();
    drive_enabled_ = true;
  } else if (!rf && drive_enabled_) {
    // D 2.0 went to 0 while traversing: error 13, except with an error < 60, RESET or a drive fault.
    const bool moving = st.state == motion::AxisState::moving || job_ != Job::none;
    const bool ready = st.drive_state != DriveState::fault && st.drive_state != DriveState::fault_reaction_active;
    if (moving && !has_error_below_60() && !db_.bit(dw_control, bit_reset) && ready)
      raise_wf(0x13, now, "drive enable D 2.0 dropped while traversing");
    abort_job();
    (void)ax.disable();
    drive_enabled_ = false;
  }
}

void Wf725Controller::abort_job() {
  release_slaves(true);  // a combined program ends on every axis it moves
  master_ = nullptr;
  auto& ax = axis(0);
  const auto s = ax.status().state;
  if (open_loop()) {
    ol_stop();  // speed 0 on the MD 2 ramp
    ol_ = OpenLoop{};
  } else if (s == motion::AxisState::moving) {
    (void)ax.stop();
  }
  job_ = Job::none;
  jog_dir_ = 0;
  stack_.clear();
  step_ = Step::fetch;
  limit_side_ = 0;
  running_program_ = running_block_ = 0;
  running_buffer_ = 0;
  continuous_measure_ = false;
  g99_wait_ = false;
}

bool Wf725Controller::go(double target_mm, std::int64_t feed, TimePoint now, motion::Direction dir,
                         double acceleration) {
  if (feed <= 0) {
    raise_wf(0x73, now, "no feed for the motion");
    return false;
  }
  double t = target_mm;
  limit_side_ = 0;
  if (open_loop()) return ol_go(t, feed, now, dir);  // F is the speed level (docs/wf725.md)
  if (armed() && !md_.rotary()) {
    // Dynamic pre-limit switches MD 11/13: the move ends exactly on them (error 95/96 there).
    const double lo = static_cast<double>(md_.integer(11)) * um, hi = static_cast<double>(md_.integer(13)) * um;
    if (t < lo) {
      t = lo;
      limit_side_ = -1;
    } else if (t > hi) {
      t = hi;
      limit_side_ = +1;
    }
  }
  auto& ax = axis(0);
  motion::Limits lim = ax.config().limits;
  // Feeds above MD 3 are reduced to MD 3 (§4.3 MD 3); 10^-2 mm/min -> mm/s.
  lim.velocity = std::min(lim.velocity, static_cast<double>(feed) / 100.0 / 60.0);
  if (acceleration > 0.0) lim.acceleration = std::min(lim.acceleration, acceleration);
  const double axis_target =
      md_.rotary() ? std::fmod(std::fmod(t, ax.config().modulo) + ax.config().modulo, ax.config().modulo) : to_axis(t);
  double goal = axis_target;
  if (md_.rotary()) {
    // machine = axis + offset (mod): aim the axis at target - offset.
    goal = std::fmod(std::fmod(t - offset_mm_, ax.config().modulo) + ax.config().modulo, ax.config().modulo);
  }
  positioning_ = true;
  if (const auto ec = ax.move_absolute(goal, dir, lim)) {
    if (ec == hil::MotionFault::not_enabled) {
      raise_wf(0x13, now, "motion without drive enable D 2.0");
    } else {
      raise_wf(0x62, now, fmt::format("the axis refused the motion: {}", ec.message()));
    }
    return false;
  }
  return true;
}

bool Wf725Controller::go_velocity(int direction, std::int64_t feed, TimePoint now) {
  if (open_loop()) {
    // Open loop runs at the level; the pre-limits are checked on the actual value.
    limit_side_ = 0;
    if (feed <= 0) {
      raise_wf(0x73, now, "speed level 0");
      return false;
    }
    return ol_run(direction, feed, now);
  }
  if (armed() && !md_.rotary()) {
    // Towards the pre-limit switch: the axis stops exactly on it.
    const double beyond =
        direction < 0 ? static_cast<double>(md_.integer(11) - 1) * um : static_cast<double>(md_.integer(13) + 1) * um;
    return go(beyond, feed, now);
  }
  if (feed <= 0) {
    raise_wf(0x73, now, "no feed for the motion");
    return false;
  }
  auto& ax = axis(0);
  motion::Limits lim = ax.config().limits;
  lim.velocity = std::min(lim.velocity, static_cast<double>(feed) / 100.0 / 60.0);
  limit_side_ = 0;
  positioning_ = true;
  if (const auto ec = ax.move_velocity(direction * lim.velocity, lim)) {
    raise_wf(ec == hil::MotionFault::not_enabled ? 0x13 : 0x62, now, ec.message());
    return false;
  }
  return true;
}

void Wf725Controller::handle_start(TimePoint now) {
  const bool start = db_.rising(dw_control, bit_start);
  if (db_.bit(dw_control, bit_stop) && job_ != Job::none) abort_job();
  if (submode_ == Submode::set_up) {
    const bool plus = db_.bit(dw_control, bit_plus), minus = db_.bit(dw_control, bit_minus);
    const int dir = plus == minus ? 0 : (plus ? 1 : -1);
    if (dir != jog_dir_ && (job_ == Job::none || job_ == Job::jog)) {
      if (dir == 0) {
        abort_job();
      } else {
        clear_self_acknowledging();
        if (!db_.bit(dw_enable, bit_drive_enable)) {
          raise_wf(0x13, now, "jog without drive enable D 2.0");
        } else if (jog_feed_ == 0) {
          raise_wf(0x72, now, "set-up speed (data code 1C) is 0");
        } else if (!errors().blocks_motion(0) && split_start(now) && go_velocity(dir, jog_feed_, now)) {
          job_ = Job::jog;
        }
        jog_dir_ = dir;
      }
    }
    return;
  }
  if (!start) return;
  if (job_ == Job::program && step_ == Step::wait_start) {
    clear_self_acknowledging();
    if (!advance()) {
      end_program();
      return;
    }
    step_ = Step::fetch;
    return;
  }
  if (job_ != Job::none) return;
  clear_self_acknowledging();
  if (errors().blocks_motion(0)) return;  // an error waits for its acknowledgement
  if (!db_.bit(dw_enable, bit_drive_enable)) {
    raise_wf(0x13, now, "start without drive enable D 2.0");
    return;
  }
  if (md_.closed_loop() && md_.get(2) == 0) {  // open loop: MD 2 = 0 is a step change
    raise_wf(0x71, now, "MD 2 = 0");
    return;
  }
  if (!split_start(now)) return;  // split drive: the slave, MD 1/2/38/39, MD 29 (no-op without)
  auto& ax = axis(0);
  const bool roller = md_.integer(42) == 1 && md_.closed_loop() && md_.incremental();
  switch (submode_) {
    case Submode::none:
    case Submode::set_up:
    case Submode::run:  // RUN has no start function: data code 10 acts there
      return;
    case Submode::reference: {
      const bool plus = db_.bit(dw_control, bit_plus), minus = db_.bit(dw_control, bit_minus);
      if (plus && minus) return raise_wf(0x77, now);
      if (!plus && !minus) return raise_wf(0x78, now);
      for (int i = 0; i < 3; ++i)
        if (ref_speeds_[i] == 0) return raise_wf(0x74 + i, now, fmt::format("data code {:X}", 8 + i));
      if (!md_.incremental()) {
        synced_ = true;  // absolute encoders are synchronized at power-up
        return;
      }
      synced_ = false;
      ref_dir_ = plus ? 1 : -1;
      ref_bits_ = plus ? 1 : 2;
      ref_ = cam() ? RefPhase::reduced : RefPhase::rapid;
      const int side = md_.integer(7) == 2 ? -1 : 1;
      if (ref_ == RefPhase::rapid ? go_velocity(ref_dir_, ref_speeds_[0], now) : go_velocity(side, ref_speeds_[1], now))
        job_ = Job::reference;
      return;
    }
    case Submode::set_actual:
      // §4.3 MD 28: the start loads MD 28 into the actual value, synchronizes, arms the limits.
      offset_mm_ = static_cast<double>(md_.integer(28)) * um - ax.status().command_position;
      zero_shift_mm_ = 0.0;
      synced_ = true;
      return;
    case Submode::mdi: {
      if (!mdi_position_) return raise_wf(0x65, now);
      if (mdi_feed_ == 0) return raise_wf(0x66, now);
      if (roller && !mdi_incremental_) return raise_wf(0x70, now, "roller feed (MD 42 = 1) takes G91 only");
      if (roller) offset_mm_ = -ax.status().command_position;  // the actual value is cleared at every start
      const double base = machine_command_mm();
      const double target = mdi_incremental_ ? base + static_cast<double>(*mdi_position_) * um
                                             : static_cast<double>(*mdi_position_) * um - zero_shift_mm_;
      mdi_position_.reset();
      if (go(target, mdi_feed_, now,
             md_.rotary() && !mdi_incremental_ ? rotary_direction() : motion::Direction::shortest))
        job_ = Job::move;
      return;
    }
    case Submode::single_step:
    case Submode::automatic:
    case Submode::automatic_step:
      (void)start_program(now, submode_ != Submode::automatic);
      return;
    case Submode::automatic_buffer:
      (void)start_buffer(now);
      return;
    case Submode::control: {
      // Control: the voltage of data code 1D with the polarity of D 1.1 (+) / D 1.3 (-) (errors 77/78).
      const bool plus = db_.bit(dw_control, bit_plus), minus = db_.bit(dw_control, bit_minus);
      if (plus && minus) return raise_wf(0x77, now, "submode control: both polarities");
      if (!plus && !minus) return raise_wf(0x78, now, "submode control: the polarity of the voltage");
      if (control_mv_ <= 0) return raise_wf(0x73, now, "control voltage (data code 1D) is 0");
      const std::int64_t feed = open_loop()
                                    ? std::max<std::int64_t>(1, std::llround(control_mv_ / 100.0))
                                    : std::llround(static_cast<double>(control_mv_) / static_cast<double>(md_.get(23)) *
                                                   static_cast<double>(md_.get(3)) * 100.0);
      if (go_velocity(plus ? 1 : -1, feed, now)) {
        job_ = Job::jog;
        jog_dir_ = plus ? 1 : -1;
      }
      return;
    }
    case Submode::clamping:
      if (md_.closed_loop() && md_.integer(25) < md_.integer(32))
        return raise_wf(0x10, now, "clamping with MD 25 < MD 32");
      clamp_command_mm_ = machine_command_mm();
      job_ = Job::clamping;
      return;
  }
  raise_io(900, now, fmt::format("submode {} is not one of the WF's (docs/wf725.md)", static_cast<int>(submode_)),
           "standard2");
}

void Wf725Controller::run_job(const CycleTime& cycle) {
  const TimePoint now = cycle.now;
  auto& ax = axis(0);
  const auto state = ax.status().state;
  if (job_ != Job::none && job_ != Job::clamping &&
      (state == motion::AxisState::error || state == motion::AxisState::disabled)) {
    // A supervision fault (a hard limit switch 15/16, following error 11, ...) ended the motion:
    // the job is over and a pre-limit it aimed at was not reached (no 95/96).
    abort_job();
    return;
  }
  switch (job_) {
    case Job::none:
      return;
    case Job::jog:
    case Job::move:
      if (motion_done()) {
        // 95/96 only where the move really ended on the pre-limit switch MD 11/13.
        const double pre = static_cast<double>(md_.integer(limit_side_ < 0 ? 11 : 13)) * um;
        if (limit_side_ != 0 && std::abs(machine_command_mm() - pre) < 0.5 * um)
          raise_wf(limit_side_ < 0 ? 0x95 : 0x96, now);
        limit_side_ = 0;
        if (job_ == Job::move) job_ = Job::none;
      }
      return;
    case Job::clamping:
      if (std::abs(clamp_command_mm_ - machine_mm()) > static_cast<double>(md_.integer(32)) * um) {
        raise_wf(0x23, now);
        job_ = Job::none;
      }
      return;
    case Job::program:
      program_cycle(cycle);
      return;
    case Job::slave:
      return;  // the master's combined program watches the motion (wf725_combined.cpp)
    case Job::reference:
      break;
  }
  // Reference point approach (§4.3 MD 16/17, MD 7): cam at V_rapid, off the cam at V_reduced
  // towards the MD 7 side, to the next zero mark (every MD 34 increments), MD 17 further at V_slow.
  const int bits = (db_.bit(dw_control, bit_plus) ? 1 : 0) | (db_.bit(dw_control, bit_minus) ? 2 : 0);
  if (bits != ref_bits_) {
    abort_job();
    raise_wf(0x79, now, "direction changed during the reference point approach");
    return;
  }
  const int side = md_.integer(7) == 2 ? -1 : 1;
  switch (ref_) {
    case RefPhase::rapid:
      if (cam()) {
        ref_ = RefPhase::reduced;
        if (!go_velocity(side, ref_speeds_[1], now)) abort_job();
      }
      return;
    case RefPhase::reduced: {
      if (cam()) return;
      const auto& c = ax.config();
      const double inc_per_mm = static_cast<double>(c.inc_per_unit.num) / static_cast<double>(c.inc_per_unit.den);
      const double rev = static_cast<double>(md_.integer(34)) / inc_per_mm;
      const double p = ax.status().command_position;
      const double zm = side > 0 ? std::ceil(p / rev) * rev : std::floor(p / rev) * rev;
      ref_target_axis_ = zm + static_cast<double>(md_.integer(17)) * um;
      // A missing zero mark (the encoder fault input): with the zero-mark check (MD 41 N = 0) the
      // axis runs one encoder revolution past it and stops with 09; masked, the point is taken.
      const bool zm_check = (md_.integer(41) & 131'072) == 0 && md_.integer(40) == 0;
      if (encoder_input(2) && zm_check) ref_target_axis_ = zm + side * rev;
      if (open_loop()) {
        // Open loop: a staged positioning at the level V_slow onto the zero mark + MD 17.
        if (!ol_go(to_machine(ref_target_axis_), ref_speeds_[2], now, motion::Direction::shortest)) {
          abort_job();
          return;
        }
        ref_ = RefPhase::slow;
        return;
      }
      motion::Limits lim = c.limits;
      lim.velocity = std::min(lim.velocity, static_cast<double>(ref_speeds_[2]) / 100.0 / 60.0);
      if (const auto ec = ax.move_absolute(ref_target_axis_, motion::Direction::shortest, lim)) {
        raise_wf(0x62, now, ec.message());
        abort_job();
        return;
      }
      ref_ = RefPhase::slow;
      return;
    }
    case RefPhase::slow:
      if (!motion_done()) return;
      if (encoder_input(2) && (md_.integer(41) & 131'072) == 0 && md_.integer(40) == 0) {
        job_ = Job::none;
        raise_encoder(0x09, now, "no zero mark within MD 34 pulses after leaving the cam");
        return;
      }
      offset_mm_ = static_cast<double>(md_.integer(16)) * um - ref_target_axis_;
      zero_shift_mm_ = 0.0;
      synced_ = true;
      job_ = Job::none;
      return;
  }
}

void Wf725Controller::check_limits(TimePoint now) {
  if (!armed() || md_.rotary()) {
    range_side_ = 0;
    return;
  }
  // Range limit switches MD 12/14 on the command position (closed loop): position control off.
  const double c = machine_command_mm();
  const int side = c < static_cast<double>(md_.integer(12)) * um - 1e-9   ? -1
                   : c > static_cast<double>(md_.integer(14)) * um + 1e-9 ? 1
                                                                          : 0;
  if (side != 0 && side != range_side_) {
    abort_job();
    raise_wf(side < 0 ? 0x15 : 0x16, now, fmt::format("command position {:.3f} mm", c));
  }
  range_side_ = side;
}

void Wf725Controller::output_m(int m, TimePoint now) {
  m_ = m;
  m_history_.push_back(m);
  const std::int64_t md8 = md_.integer(8);
  if (md8 <= 3) {
    m_state_ = MState::strobe;  // handshake: the PLC acknowledges with D 2.2
  } else {
    m_state_ = MState::timed;
    m_until_ = now + std::chrono::milliseconds(md8);
  }
}

void Wf725Controller::m_cycle(TimePoint now) {
  switch (m_state_) {
    case MState::idle:
      return;
    case MState::strobe:
      // Acknowledged with the leading edge; the trailing edge releases the next M output (§4.3 MD 8).
      if (db_.rising(dw_enable, bit_m_ack)) m_state_ = MState::wait_release;
      return;
    case MState::wait_release:
      if (!db_.bit(dw_enable, bit_m_ack)) m_state_ = MState::idle;
      return;
    case MState::timed:
      if (now >= m_until_) m_state_ = MState::idle;
      return;
  }
}

void Wf725Controller::write_status() {
  const auto& st = axis(0).status();
  const bool moving = st.state == motion::AxisState::moving || st.state == motion::AxisState::stopping;
  const bool at_rest = !moving && st.state == motion::AxisState::standstill;
  const bool peh = at_rest && (open_loop() && ol_.positioning ? ol_.peh : st.in_position);
  if (peh && !peh_ && positioning_ && md_.closed_loop() && md_.integer(33) > md_.integer(25)) {
    // §4.3 MD 25: with MD 33 > MD 25 the standstill check fails each time a positioning reaches
    // the PEH window (the check switches from MD 24 to MD 25 there).
    raise_wf(0x10, last_now_, "MD 33 > MD 25");
  }
  if (peh) positioning_ = false;
  peh_ = peh;
  db_.set_bit(dw_status, bit_peh, peh);
  db_.set_bit(dw_status, bit_moving_plus, moving && st.command_velocity > 0);
  db_.set_bit(dw_status, bit_moving_minus, moving && st.command_velocity < 0);
  db_.set_bit(dw_status, bit_pre_limit, has_error(0x95) || has_error(0x96));
  db_.set_bit(dw_status, bit_limit, has_error(0x15) || has_error(0x16));
  db_.set_bit(dw_status, bit_syn, synced_);
  const bool strobe = m_state_ == MState::strobe || m_state_ == MState::timed;
  db_.set_bit(dw_status, bit_m_strobe, strobe);
  db_.set_dl(dw_status, strobe ? static_cast<std::uint8_t>(m_) : 0);
  int wf_error = 0, io_error = 0;
  for (const auto& e : errors().active()) {
    if (e.catalogue == traversing_cat_)
      wf_error = e.code;
    else
      io_error = e.code;
  }
  db_.set_bit(dw_status, bit_error, wf_error != 0);
  db_.set_dr(dw_error, static_cast<std::uint8_t>(wf_error));
  db_.set_dl(dw_error, wf725_level_bcd(open_loop() ? ol_.level : 0));  // open-loop speed level, BCD
  db_.write_word(dw_io_error, s5_bcd_word(io_error));
  db_.write_dd(dd_actual, static_cast<std::int32_t>(std::llround(actual_um())));
  db_.set_dl(dw_block, static_cast<std::uint8_t>(running_program_));
  db_.set_dr(dw_block, static_cast<std::uint8_t>(running_block_));
  db_.set_dl(dw_state, mode_bits_);
  db_.set_dr(dw_state, static_cast<std::uint8_t>(submode_));
  db_.set_bit(dw_flags, 0, job_ == Job::program && step_ == Step::wait_start);
  db_.set_bit(dw_flags, 1, job_ == Job::program);
  db_.set_bit(dw_flags, 2, job_ == Job::program && step_ == Step::wait_enable);
  // Fast outputs X7 A1..A6 by MD 10 (digit n = function of An): 1 PEH, 2 moving +, 3 moving -,
  // 4 last but one cut-off point (WF 726 open loop). Open loop: A1-A3 are the cut-off points A/B/C.
  Wf725CutOffOutputs cut;
  if (open_loop() && ol_.positioning && !ol_.zero)
    cut = wf725_cut_off_outputs(ol_stages(), (ol_.target - unwrapped_mm()) * ol_.dir / um);
  else if (open_loop() && ol_.positioning)
    cut.last_but_one = !ol_.peh;
  std::int64_t md10 = md_.integer(10);
  for (std::uint8_t a = 0; a < 6; ++a, md10 /= 10) {
    const auto f = md10 % 10;
    bool on = (f == 1 && peh) || (f == 2 && moving && st.command_velocity > 0) ||
              (f == 3 && moving && st.command_velocity < 0) || (f == 4 && cut.last_but_one);
    if (open_loop() && a < 3) on = a == 0 ? cut.a : a == 1 ? cut.b : cut.c;
    io().set(BitAddress{IoArea::output, 0, a}, on);
  }
  io().set(BitAddress{IoArea::output, 1, 0}, peh);
  io().set(BitAddress{IoArea::output, 1, 1}, moving);
  io().set(BitAddress{IoArea::output, 1, 2}, errors().blocks_motion(0));
  io().set(BitAddress{IoArea::output, 1, 3}, st.state != motion::AxisState::disabled);
  io().set(BitAddress{IoArea::marker, 0, 0}, errors().any());
}

}  // namespace hil::controllers::s5
