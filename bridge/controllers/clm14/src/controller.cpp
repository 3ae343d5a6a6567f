// SPDX-License-Identifier: MIT
// CLM1.4 model: memory, modes, safety, errors, tasks and restart (manual §6/§7, digest §6/§7).
#include "hil/controllers/clm14/controller.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <cmath>

namespace hil::controllers::clm14 {

using namespace std::chrono_literals;

const char* to_string(Mode m) noexcept {
  switch (m) {
    case Mode::parameter:
      return "parameter";
    case Mode::manual:
      return "manual";
    case Mode::automatic:
      return "automatic";
  }
  return "?";
}

Controller::Controller(Options options)
    : options_(options), program_(program_lines), text_(program_lines, "NOP"), logic_text_(logic_lines, "NOP") {
  logic_text_[0] = "END";
  parameters_ = [](std::string_view) { return std::string{}; };
}

void Controller::attach_axis(int axis, AxisPort* port) {
  if (axis >= 1 && axis <= 4) axes_[static_cast<std::size_t>(axis - 1)].port = port;
}

std::expected<void, ProgramError> Controller::store_line(int line, std::string_view text) {
  if (line < 0 || line >= program_lines)
    return std::unexpected(
        ProgramError{ClmError::invalid_block_number, line, fmt::format("line {} is beyond 2999", line)});
  auto in = parse_instruction(text);
  if (!in) {
    auto e = in.error();
    e.line = line;
    e.message = fmt::format("NC line {:04d}: {}", line, e.message);
    return std::unexpected(e);
  }
  std::string stored(text);
  while (!stored.empty() && stored.back() == ' ') stored.pop_back();
  while (!stored.empty() && stored.front() == ' ') stored.erase(stored.begin());
  if (in->op == Op::cou || in->op == Op::bac) {
    // §5.7 COU: the offset acts once, when the line is stored, then reads "+00000".
    const std::size_t offset_index = in->op == Op::cou ? 0 : 1;
    int& count = counters_[line];
    if (in->counter_reset)
      count = 0;
    else
      count = std::max(0, count + static_cast<int>(in->n[offset_index].value / micro_one));
    in->n[offset_index] = Num{};
    in->counter_reset = false;
    stored = clear_counter_offset(stored);
  } else {
    counters_.erase(line);
  }
  program_[static_cast<std::size_t>(line)] = std::move(*in);
  text_[static_cast<std::size_t>(line)] = std::move(stored);
  return {};
}

std::expected<void, ProgramError> Controller::load_program(const std::vector<std::pair<int, std::string>>& lines) {
  // Check everything first: a bad program changes nothing.
  for (const auto& [n, t] : lines) {
    if (n < 0 || n >= program_lines)
      return std::unexpected(ProgramError{ClmError::invalid_block_number, n, fmt::format("line {} is beyond 2999", n)});
    if (auto in = parse_instruction(t); !in) {
      auto e = in.error();
      e.line = n;
      e.message = fmt::format("NC line {:04d}: {}", n, e.message);
      return std::unexpected(e);
    }
  }
  std::fill(program_.begin(), program_.end(), Instruction{});
  std::fill(text_.begin(), text_.end(), std::string("NOP"));
  for (const auto& [n, t] : lines) (void)store_line(n, t);
  return {};
}

void Controller::store_logic_line(int line, std::string text) {
  if (line < 0 || line >= logic_lines) return;
  if (powered_ && mode_ != Mode::parameter && logic_text_[static_cast<std::size_t>(line)] != text)
    raise(static_cast<int>(ClmError::logic_program_lost),
          fmt::format("logic line {:04d} changed outside Parameter mode", line), 2, line);
  logic_text_[static_cast<std::size_t>(line)] = std::move(text);
}

Duration Controller::cycle_time() const {
  return std::chrono::duration_cast<Duration>(std::chrono::duration<double, std::milli>(settings_.cycle_ms));
}

// ---- power-up, parameters, logic task ---------------------------------------------------------

void Controller::apply_parameters(TimePoint now) {
  if (validator_) {
    if (auto v = validator_(); !v) {
      settings_ok_ = false;
      error_ = 0;  // a parameter error replaces what was shown
      raise(static_cast<int>(ClmError::parameter_invalid), v.error().message, 0, 0);
      error_item_[0] = v.error().message.substr(0, 4);
      return;
    }
  }
  auto s = make_settings(parameters_);
  if (!s) {
    settings_ok_ = false;
    error_ = 0;  // a parameter error replaces what was shown
    raise(static_cast<int>(ClmError::parameter_invalid), s.error().message, 0, 0);
    error_item_[0] = s.error().message.substr(0, 4);
    return;
  }
  if (on_settings_) on_settings_(*s);
  for (int a = 1; a <= 4; ++a)
    if (s->axes[static_cast<std::size_t>(a - 1)].enabled && axes_[static_cast<std::size_t>(a - 1)].port == nullptr) {
      settings_ok_ = false;
      raise(static_cast<int>(ClmError::parameter_invalid),
            fmt::format("B000: axis {} is enabled but no axis is connected to it", a), 0, 0);
      error_item_[0] = "B000";
      return;
    }
  settings_ = *s;
  settings_ok_ = true;
  if (error_ == static_cast<int>(ClmError::parameter_invalid)) {
    error_ = 0;
    error_message_.clear();
    error_item_[0].clear();
  }
  for (std::size_t t = 0; t < 5; ++t) {
    tasks_[t].used = settings_.task_used[t];
    tasks_[t].start = settings_.task_start[t];
  }
  (void)now;
}

void Controller::compile_logic() {
  auto p = LogicProgram::compile(logic_text_);
  if (!p) {
    logic_ok_ = false;
    logic_ = LogicProgram{};
    raise(static_cast<int>(ClmError::logic_program), p.error().message, 2, std::max(0, p.error().line));
    return;
  }
  logic_ = std::move(*p);
  logic_ok_ = true;
  if (error_ == static_cast<int>(ClmError::logic_program) || error_ == static_cast<int>(ClmError::logic_program_lost)) {
    error_ = 0;
    error_message_.clear();
    error_item_[2].clear();
  }
}

void Controller::power_up(TimePoint now) {
  now_ = now;
  powered_ = true;
  // Volatile state: lost with the power (the battery keeps program, variables, counters, M3, M6.00-19).
  for (int g : {2, 4, 5}) image_.clear_markers(g);
  for (int b = 20; b < marker_bytes; ++b) image_.set_byte({Area::marker, 6, static_cast<std::uint8_t>(b)}, 0);
  for (int s = 0; s < 3; ++s) image_.clear_outputs(s);
  for (auto& a : axes_) {
    a.homed = false;
    a.base = a.sac = 0.0;
    a.has_target = a.held = a.feeding = a.con = a.srm = a.rep = false;
    a.software_enabled = true;
    a.acc_permille = a.dec_permille = 0;
    a.fak = micro_one;
    a.rtm = 0;
    a.override_permille = 1000;
    a.override_limit = false;
    a.homing = a.homing_restart = false;
    a.homer.abort();
    a.homed_out.reset();
  }
  wheel_ = {};
  cutoff_length_line_ = -1;
  start_0000_ = false;
  reset_coupled_state();
  apply_parameters(now);
  compile_logic();
  run_ = RunState::idle;
  for (auto& t : tasks_) {
    t.active = false;
    t.stack.clear();
    t.pc = t.start;
    t.phase = 0;
  }
  mode_valid_ = false;
  logic_next_ = now;
}

// ---- the cycle ----------------------------------------------------------------------------------

void Controller::cycle(TimePoint now) {
  if (!powered_) power_up(now);
  now_ = now;
  ++cycle_count_;
  update_axes_in(now);
  update_master_in();
  update_master2_in();
  update_analog_in();
  update_mode(now);
  update_safety(now);
  step_wheels();
  step_axis_inputs();
  jog(now);
  step_axis_functions(now);
  run_tasks(now);
  step_couplings(now);
  if (logic_ok_ && mode_ != Mode::parameter && now >= logic_next_) {
    logic_.run(image_);
    logic_next_ = now + options_.logic_period;
  }
  update_system_variables();
  update_outputs();
  previous_inputs_ = image_;
}

void Controller::update_mode(TimePoint now) {
  const bool p = image_.bit(sys::parameter_mode);
  const bool a = image_.bit(sys::automatic);
  if (p && a) {
    if (error_ == 0) raise(static_cast<int>(ClmError::invalid_mode), "Parameter and Automatic selected together");
    return;
  }
  const Mode want = p ? Mode::parameter : a ? Mode::automatic : Mode::manual;
  if (!mode_valid_) {
    mode_valid_ = true;
    // Power-up: outputs and volatile markers are already clear; Automatic is entered through
    // enter_mode() below so that its checks run.
    mode_ = want == Mode::parameter ? Mode::parameter : Mode::manual;
    if (mode_ != Mode::parameter && tasks_[2].used && settings_ok_) {
      tasks_[2].active = true;
      tasks_[2].pc = tasks_[2].start;
    }
  }
  if (want != mode_) enter_mode(want, now);
}

void Controller::enter_mode(Mode m, TimePoint now) {
  const Mode old = mode_;
  mode_ = m;
  for (int ax = 1; ax <= 4; ++ax) abort_homing(ax, false);  // a mode change aborts homing (§7.9)
  if (old == Mode::automatic) {
    if (run_ == RunState::running) save_restart();
    stop_program(false);
    clear_nc_markers();
    txt53_.clear();
    for (auto& a : axes_) {
      a.acc_permille = a.dec_permille = 0;
      a.fak = micro_one;
      a.override_permille = 1000;
      a.override_limit = false;
      a.override_master = false;  // VEO: cancelled on Auto <-> Manual
      a.aeo = false;
      a.rep = false;
    }
    fak5_ = micro_one;
    mlo_.on = false;  // MLO: leaving Automatic disables it
    test_step_ = 0;   // test mode: the material clock stops on Automatic -> Manual (§7.12)
  }
  if (old == Mode::manual && m == Mode::parameter) txt53_.clear();
  if (m == Mode::parameter) {
    stop_program(false);
    reset_coupled_state();  // FOL off, mode 1, factor 1 (§5.7 FOL)
    tasks_[2].active = false;
    for (int s = 0; s < 3; ++s) image_.clear_outputs(s);
    for (int g : {2, 4, 5}) image_.clear_markers(g);
    for (int b = 20; b < 40; ++b) image_.set_byte({Area::marker, 6, static_cast<std::uint8_t>(b)}, 0);
    for (auto& a : axes_) {
      a.homed = false;
      if (a.port != nullptr) a.port->stop();
    }
  }
  if (old == Mode::parameter) {
    apply_parameters(now);
    compile_logic();
    image_.clear_markers(5);
    for (int b = 20; b < 40; ++b) image_.set_byte({Area::marker, 6, static_cast<std::uint8_t>(b)}, 0);
    for (auto& a : axes_) {
      a.homed = false;
      a.base = a.sac = 0.0;
      a.rtm = 0;
      a.fak = micro_one;
    }
    wheel_ = {};
    cutoff_length_line_ = -1;  // the program may have changed: the next start is at 0000
    fak5_ = micro_one;
    if (tasks_[2].used && settings_ok_) {
      tasks_[2].active = true;
      tasks_[2].pc = tasks_[2].start;
      tasks_[2].stack.clear();
      tasks_[2].phase = 0;
    }
  }
  if (m == Mode::manual && settings_ok_ && error_ == 0 && settings_.manual_vector_on_mode_change &&
      !settings_.manual_vector_input)
    start_manual_vector(settings_.manual_vector_line);
  if (m == Mode::automatic && settings_ok_) {
    for (int ax = 1; ax <= settings_.axis_count; ++ax) {
      const auto& as = settings_.axes[static_cast<std::size_t>(ax - 1)];
      const auto& ar = axes_[static_cast<std::size_t>(ax - 1)];
      if (as.enabled && ar.software_enabled && !image_.bit(sys::enable[static_cast<std::size_t>(ax - 1)])) {
        raise(axis_code(ClmError::drive_not_ready, ax), fmt::format("Automatic selected without Enable axis {}", ax));
        break;
      }
    }
    if (flying_cutoff() && error_ == 0) {
      // §7.12: the carriage must stand at its origin (error 36); task 1 then starts at once
      // (Start has no function), at 0000 [decided].
      // Homing option 5 (passive, §7.9): "Manual -> Auto is allowed while on the switch; the
      // axis is homed when the synchronised carriage leaves it" - so a carriage not yet homed
      // that stands on its home switch passes the origin check (step_homing homes it).
      const auto& c = settings_.axes[0];
      const bool passive_on_switch = c.homing_type == 4 && !options_.drive_homing && !axes_[0].homed &&
                                     c.home_switch_input && image_.bit(*c.home_switch_input);
      const double window = std::max(c.reached_window, 0.01);
      if (!passive_on_switch && std::abs(clm_position(1)) > window)
        raise(static_cast<int>(ClmError::not_home_position),
              fmt::format("flying cutoff: the carriage is at {:.3f} IU, not at its origin", clm_position(1)));
      else {
        start_program(now);
        tasks_[0].pc = cutoff_start_line();
      }
    }
  }
}

void Controller::update_safety(TimePoint now) {
  const bool estop_ok = image_.bit(sys::emergency_stop_ok);
  if (!estop_ok && error_ != static_cast<int>(ClmError::emergency_stop)) {
    for (auto& a : axes_)
      if (a.port != nullptr) a.port->quick_stop();
    raise(static_cast<int>(ClmError::emergency_stop), "E-Stop input I0.00.2 (X3/3) missing");
  }
  if (image_.bit(sys::external_clear) && !previous_inputs_.bit(sys::external_clear)) command_clear();
  // Drive enable and brake (§9.1, digest §7.3).
  for (int ax = 1; ax <= 4; ++ax) {
    auto& a = axes_[static_cast<std::size_t>(ax - 1)];
    const auto& as = settings_.axes[static_cast<std::size_t>(ax - 1)];
    const bool input = image_.bit(sys::enable[static_cast<std::size_t>(ax - 1)]);
    if (mode_ == Mode::automatic && settings_ok_ && as.enabled && a.software_enabled && !input && error_ == 0 &&
        run_ != RunState::idle)
      raise(axis_code(ClmError::drive_not_ready, ax), fmt::format("Enable axis {} lost in Automatic", ax));
    const bool on = settings_ok_ && as.enabled && a.port != nullptr && mode_ != Mode::parameter && estop_ok && input &&
                    error_ == 0 && a.software_enabled;
    if (on && !a.drive_enable) a.enable_since = now;
    if (on != a.drive_enable && a.port != nullptr) a.port->set_enabled(on);
    if (!on && a.drive_enable) {
      a.has_target = a.feeding = a.held = a.pending = a.con = a.srm = false;
      abort_homing(ax, false);
    }
    a.drive_enable = on;
  }
  // Manual vector (B014, §7.10): a rising edge in Manual runs a program that ends with RTS.
  if (settings_.manual_vector_input && mode_ == Mode::manual && error_ == 0 && !tasks_[0].manual_vector &&
      image_.bit(*settings_.manual_vector_input) && !previous_inputs_.bit(*settings_.manual_vector_input)) {
    bool busy = false;
    for (const auto& a : axes_) busy = busy || a.jog || a.homing;
    if (!busy) start_manual_vector(settings_.manual_vector_line);
  }
  // Interrupt vector (B015, task 1, Automatic): continue at the B015 line, no return.
  if (settings_.interrupt_vector_input && mode_ == Mode::automatic && error_ == 0 && run_ == RunState::running) {
    const bool now_in = image_.bit(*settings_.interrupt_vector_input);
    const bool was = previous_inputs_.bit(*settings_.interrupt_vector_input);
    const int e = settings_.interrupt_vector_edge;
    const bool edge = e <= 1 ? (now_in && !was) : (!now_in && was);
    const bool inhibited = (e == 0 || e == 2) && !tasks_[0].stack.empty();
    if (edge && !inhibited) {
      Task& t1 = tasks_[0];
      t1.pc = settings_.interrupt_vector_line;
      t1.stack.clear();
      t1.phase = 0;
      if (mat_owner_ == 1) mat_owner_ = -1;
      if (settings_.interrupt_vector_aborts_move) {
        for (auto& a : axes_)
          if (a.port != nullptr && a.has_target && a.feeding) {
            a.port->stop();
            a.has_target = a.feeding = false;
          }
        // FOL mode 2 "stops / re-syncs on Interrupt" (§5.7) [decided]: with p = 1 a mode-2 slave
        // ramps out (the coupling stays, at ratio 0); the next FOL, or Start after a stop, ramps
        // it back in. With p = 0 it keeps following, as a positioning keeps running.
        if (options_.fol2_stops_at_interrupt)
          for (int ax = 1; ax <= 4; ++ax) pause_follow(ax, true);
      }
    }
  }
  // Start, Immediate Stop, Restart (Automatic only).
  const bool start_edge = image_.bit(sys::start) && !previous_inputs_.bit(sys::start);
  const bool restart_edge = image_.bit(sys::restart) && !previous_inputs_.bit(sys::restart);
  const bool imm_ok = image_.bit(sys::immediate_stop_ok);
  if (mode_ != Mode::automatic || error_ != 0) return;
  if (flying_cutoff()) return;  // §7.12: Start, Immediate Stop and Restart have no function
  if (!imm_ok && run_ == RunState::running) stop_program(true);
  if (!imm_ok) return;
  if (restart_edge && restart_.valid && !restart_blocked_) {
    if (settings_.restart_line != 0) {
      run_ = RunState::running;
      Task& t1 = tasks_[0];
      t1.active = true;
      t1.restart_program = true;
      t1.pc = settings_.restart_line;
      t1.stack.clear();
      t1.phase = 0;
    } else {
      restore_restart(true);
    }
    return;
  }
  if ((start_edge || restart_edge) && !stopped_by_command_) {
    if (run_ == RunState::idle)
      start_program(now);
    else if (run_ == RunState::stopped)
      resume_program();
  }
}

void Controller::start_manual_vector(int line) {
  Task& t1 = tasks_[0];
  t1.manual_vector = true;
  t1.active = true;
  t1.pc = line;
  t1.stack.clear();
  t1.phase = 0;
}

bool Controller::command_start() {
  if (flying_cutoff()) return false;  // §7.12: !START has no function
  if (mode_ != Mode::automatic || error_ != 0 || !image_.bit(sys::immediate_stop_ok)) return false;
  stopped_by_command_ = false;
  if (run_ == RunState::idle)
    start_program(now_);
  else if (run_ == RunState::stopped)
    resume_program();
  return true;
}

void Controller::command_stop() {
  if (run_ == RunState::running && !flying_cutoff()) {
    stop_program(true);
    stopped_by_command_ = true;
  }
}

void Controller::command_clear() {
  if (error_ == 0) return;
  if (error_ == static_cast<int>(ClmError::parameter_invalid) || error_ == static_cast<int>(ClmError::logic_program))
    return;  // cleared by leaving Parameter mode with a valid set / program
  if (error_ == static_cast<int>(ClmError::emergency_stop) && !image_.bit(sys::emergency_stop_ok)) return;
  if (error_ == static_cast<int>(ClmError::invalid_mode) && image_.bit(sys::parameter_mode) &&
      image_.bit(sys::automatic))
    return;
  error_ = 0;
  error_message_.clear();
  for (auto& e : error_item_) e.clear();
  for (std::size_t b = 0; b < 7; ++b)
    if (settings_.output_clear[b] == 1) write_byte({Area::output, 1, static_cast<std::uint8_t>(b)}, 0);
  fak5_ = micro_one;
  for (auto& a : axes_) {
    a.sac = 0.0;
    a.fak = micro_one;
    a.rtm = 0;
    a.acc_permille = a.dec_permille = 0;
    a.homed_out.reset();  // the Ax24 output is shown again after outputs were cleared
    if (a.port != nullptr) a.port->reset();
  }
  for (std::size_t t = 0; t < 5; ++t)
    if (t != 2) {
      tasks_[t].pc = tasks_[t].start;
      tasks_[t].stack.clear();
      tasks_[t].phase = 0;
    }
  stopped_by_command_ = false;
}

void Controller::set_analog_input(int input, int millivolts) noexcept {
  if (input >= 1 && input <= 4) analog_mv_[static_cast<std::size_t>(input - 1)] = std::clamp(millivolts, -10000, 10000);
}

int Controller::analog_input(int input) const noexcept {
  return input >= 1 && input <= 4 ? analog_mv_[static_cast<std::size_t>(input - 1)] : 0;
}

void Controller::set_axis_software_enable(int axis, bool on) {
  if (axis >= 1 && axis <= 4) axes_[static_cast<std::size_t>(axis - 1)].software_enabled = on;
}

void Controller::raise(int code, std::string message, int item_kind, int item) {
  if (error_ != 0 && code != static_cast<int>(ClmError::emergency_stop)) return;  // the first error stays
  const bool lag_or_runaway = (code & 0x0F) == 0x02 || (code & 0x0F) == 0x03;
  if (code >= 0x40 && lag_or_runaway) restart_blocked_ = true;
  if (run_ == RunState::running && mode_ == Mode::automatic) save_restart();
  error_ = code;
  error_message_ = std::move(message);
  if (item_kind >= 0 && item_kind < 4) error_item_[static_cast<std::size_t>(item_kind)] = fmt::format("{:04d}", item);
  stop_program(false);
  reset_coupled_state();  // couplings end; FOL back to mode 1, factor 1 (§5.7 FOL)
  for (std::size_t b = 0; b < 7; ++b)
    if (settings_.output_clear[b] != 2) {
      // 0 = clear on the fault; 1 = keep, clear when the fault is cleared (command_clear)
      if (settings_.output_clear[b] == 0) write_byte({Area::output, 1, static_cast<std::uint8_t>(b)}, 0);
    }
  clear_nc_markers();
  for (auto& a : axes_) {
    a.rep = false;
    a.con = false;
  }
  if (code == static_cast<int>(ClmError::emergency_stop)) {
    // all outputs off, including Error (§9.1 E-Stop)
    for (int s = 0; s < 3; ++s) image_.clear_outputs(s);
  }
}

void Controller::clear_nc_markers() {
  image_.clear_markers(2);
}

void Controller::write_bit(const BitAddress& a, bool v) {
  if (a.byte.area == Area::input) return;
  // An output the logic task stores to is no longer driven by NC (§9.1).
  if (((logic_.owned_mask(a.byte) >> a.bit) & 1U) != 0) return;
  image_.set_bit(a, v);
}

void Controller::write_byte(const ByteAddress& a, std::uint8_t v) {
  if (a.area == Area::input) return;
  const std::uint8_t keep = logic_.owned_mask(a);
  image_.set_byte(a, static_cast<std::uint8_t>((image_.byte(a) & keep) | (v & ~keep)));
}

// ---- program run state --------------------------------------------------------------------------

void Controller::start_program(TimePoint now) {
  (void)now;
  run_ = RunState::running;
  stopped_by_command_ = false;
  restart_.valid = false;
  restart_blocked_ = false;
  for (std::size_t t = 0; t < 5; ++t) {
    if (t == 2) continue;
    Task& k = tasks_[t];
    k.active = k.used;
    k.pc = k.start;
    k.stack.clear();
    k.phase = 0;
    k.restart_program = k.manual_vector = false;
  }
}

void Controller::resume_program() {
  run_ = RunState::running;
  for (std::size_t t = 0; t < 5; ++t)
    if (t != 2 && tasks_[t].used) tasks_[t].active = true;
  for (int ax = 1; ax <= 4; ++ax) {
    resume_axis(ax);
    pause_follow(ax, false);  // FOL mode 2 re-synchronises on Start
    auto& a = axes_[static_cast<std::size_t>(ax - 1)];
    if (a.homing_restart && a.port != nullptr) {
      a.homing_restart = false;
      (void)start_homing(ax, 0);
    }
  }
}

void Controller::stop_program(bool keep_position) {
  for (std::size_t t = 0; t < 5; ++t) {
    if (t == 2) continue;
    Task& k = tasks_[t];
    k.active = false;
    if (!keep_position) {
      k.pc = k.start;
      k.stack.clear();
      k.phase = 0;
      k.restart_program = k.manual_vector = false;
    }
  }
  if (mat_owner_ >= 0 && mat_owner_ != 2) mat_owner_ = -1;
  if (!keep_position) end_cutoff();
  srp_.measuring = srp_.missed = false;
  for (int ax = 1; ax <= 4; ++ax) {
    auto& a = axes_[static_cast<std::size_t>(ax - 1)];
    a.con = false;
    a.srm = false;
    // Homing stops; in Automatic HOM runs again at the next Start (§7.9 "Termination").
    abort_homing(ax, keep_position && mode_ == Mode::automatic);
    if (follow_[static_cast<std::size_t>(ax - 1)].active) {
      if (keep_position) pause_follow(ax, true);  // mode 2 ramps down; mode 1 keeps following (§5.7)
      continue;
    }
    if (keep_position) {
      hold_axis(ax);
    } else {
      if (a.port != nullptr && (a.fb.busy || a.has_target)) a.port->stop();
      a.has_target = a.feeding = a.held = a.pending = false;
      a.rmi_suspended = a.rmi_offset_pending = false;
    }
  }
  run_ = keep_position && run_ != RunState::idle ? RunState::stopped : RunState::idle;
}

void Controller::save_restart() {
  if (restart_blocked_ || flying_cutoff()) return;  // §7.12: no restart in flying cutoff
  restart_.valid = true;
  for (std::size_t t = 0; t < 5; ++t) {
    restart_.pc[t] = tasks_[t].pc;
    restart_.phase[t] = program_[static_cast<std::size_t>(tasks_[t].pc)].op == Op::wai ? 0 : tasks_[t].phase;
    restart_.stack[t] = tasks_[t].stack;
    restart_.active[t] = tasks_[t].used && t != 2;
  }
  for (std::size_t a = 0; a < 4; ++a) {
    restart_.target[a] = axes_[a].target;
    restart_.has_target[a] = axes_[a].has_target && axes_[a].feeding;
  }
  for (std::size_t b = 0; b < 7; ++b)
    restart_.outputs[b] = image_.byte({Area::output, 1, static_cast<std::uint8_t>(b)});
}

void Controller::restore_restart(bool outputs) {
  if (outputs)
    for (std::size_t b = 0; b < 7; ++b)
      write_byte({Area::output, 1, static_cast<std::uint8_t>(b)}, restart_.outputs[b]);
  run_ = RunState::running;
  for (std::size_t t = 0; t < 5; ++t) {
    if (t == 2) continue;
    Task& k = tasks_[t];
    k.pc = restart_.pc[t];
    k.stack = restart_.stack[t];
    k.active = restart_.active[t];
    k.phase = restart_.phase[t];
    k.restart_program = false;
  }
  for (int ax = 1; ax <= 4; ++ax) {
    auto& a = axes_[static_cast<std::size_t>(ax - 1)];
    if (restart_.has_target[static_cast<std::size_t>(ax - 1)] && a.port != nullptr) {
      a.target = restart_.target[static_cast<std::size_t>(ax - 1)];
      a.has_target = true;
      a.held = true;
      resume_axis(ax);
    }
  }
  restart_.valid = false;
}

// ---- tasks ----------------------------------------------------------------------------------------

void Controller::run_tasks(TimePoint now) {
  for (int t = 1; t <= 5; ++t) {
    Task& k = tasks_[static_cast<std::size_t>(t - 1)];
    if (!k.active) continue;
    if (t == 3 ? mode_ == Mode::parameter : (mode_ != Mode::automatic && !k.manual_vector)) continue;
    step_task(t, now);
  }
}

void Controller::step_task(int t, TimePoint now) {
  Task& k = tasks_[static_cast<std::size_t>(t - 1)];
  // TXT 0 lines run up to 4 in one cycle (§5.7 TXT); everything else one instruction per cycle.
  for (int burst = 0; burst < 4; ++burst) {
    if (k.pc < 0 || k.pc >= program_lines) {
      raise(static_cast<int>(ClmError::invalid_block_number), fmt::format("task {} ran past line 2999", t), 1, 2999);
      return;
    }
    const Instruction& in = program_[static_cast<std::size_t>(k.pc)];
    const int line = k.pc;
    const Flow f = exec(t, k, in, now);
    if (error_ != 0 && t != 3) return;
    switch (f) {
      case Flow::wait:
        return;
      case Flow::halt:
        k.phase = 0;
        return;
      case Flow::jump:
        k.phase = 0;
        k.pc = k.jump_to;
        break;
      case Flow::next:
        k.phase = 0;
        k.pc = line + 1;
        break;
    }
    if (k.pc >= program_lines) {
      raise(static_cast<int>(ClmError::invalid_block_number), fmt::format("task {} ran past line 2999", t), 1, line);
      return;
    }
    const bool txt0 = in.op == Op::txt && in.n[0].value == 0;
    const Instruction& following = program_[static_cast<std::size_t>(k.pc)];
    if (!(txt0 && following.op == Op::txt && following.n[0].value == 0 && f == Flow::next)) return;
  }
}

// ---- outputs and system variables -----------------------------------------------------------------

void Controller::update_system_variables() {
  vars_[0] = static_cast<Micro>(cycle_count_ % 100'000'000ULL) * micro_one;
  if (mode_ == Mode::automatic && run_ == RunState::running) ++auto_cycles_;
  vars_[1] = static_cast<Micro>(auto_cycles_ % 100'000'000ULL) * micro_one;
  for (std::size_t t = 0; t < 5; ++t) vars_[2 + t] = tasks_[t].pc * micro_one;
  const auto clamp = [](double v) { return std::clamp(to_micro(v), -variable_max, variable_max); };
  for (int ax = 1; ax <= 4; ++ax) {
    const auto& a = axes_[static_cast<std::size_t>(ax - 1)];
    if (a.port == nullptr) continue;
    const std::size_t b = static_cast<std::size_t>(ax * 100);
    vars_[b] = clamp(clm_position(ax));
    vars_[b + 3] = clamp(a.fb.following_error);
    vars_[b + 4] = clamp(a.fb.velocity);
    vars_[b + 10] = a.has_target ? clamp(a.target - clm_position(ax)) : 0;
  }
  for (int ax = 1; ax <= 2; ++ax)
    if (settings_.axes[static_cast<std::size_t>(ax - 1)].measuring_wheel() &&
        axes_[static_cast<std::size_t>(ax - 1)].port)
      vars_[static_cast<std::size_t>(46 + ax)] = clamp(motor_position(ax));  // V047 / V048
  update_measurements();
  hours_ms_ += settings_.cycle_ms;
  vars_[19] = clamp(hours_ms_ / 3.6e6);
}

void Controller::update_outputs() {
  const bool estop = error_ == static_cast<int>(ClmError::emergency_stop);
  if (estop) {
    for (int s = 0; s < 3; ++s) image_.clear_outputs(s);
    return;
  }
  image_.set_bit(sys::out_manual, mode_ == Mode::manual);
  image_.set_bit(sys::out_automatic, mode_ == Mode::automatic);
  image_.set_bit(sys::out_parameter, mode_ == Mode::parameter);
  image_.set_bit(sys::out_error, error_ == 0);
  image_.set_bit(sys::out_run, mode_ == Mode::automatic && run_ == RunState::running &&
                                   image_.bit(sys::immediate_stop_ok) && !tasks_[0].manual_vector);
  image_.set_bit(sys::out_restart_possible, restart_.valid && !restart_blocked_);
  image_.set_bit(sys::out_inhibit, inhibit_);
  for (int ax = 1; ax <= 4; ++ax) {
    const auto& a = axes_[static_cast<std::size_t>(ax - 1)];
    image_.set_bit(sys::out_drive_enable[static_cast<std::size_t>(ax - 1)], a.drive_enable);
    image_.set_bit(sys::out_brake[static_cast<std::size_t>(ax - 1)],
                   a.drive_enable && now_ - a.enable_since >= options_.brake_delay);
  }
  if (settings_.error_code_byte >= 1 && settings_.error_code_byte <= 6)
    write_byte({Area::output, 1, static_cast<std::uint8_t>(settings_.error_code_byte - 1)},
               static_cast<std::uint8_t>(error_));
}

// ---- views ------------------------------------------------------------------------------------------

std::string Controller::error_item(int kind) const {
  if (kind < 0 || kind > 3) return {};
  return error_item_[static_cast<std::size_t>(kind)];
}

Micro Controller::variable(int n) const {
  return n >= 0 && n < 1000 ? vars_[static_cast<std::size_t>(n)] : 0;
}

bool Controller::set_variable(int n, Micro v) {
  if (n < 600 || n > 999 || v > variable_max || v < -variable_max) return false;
  vars_[static_cast<std::size_t>(n)] = v;
  return true;
}

std::optional<Controller::CounterView> Controller::counter(int line) const {
  if (line < 0 || line >= program_lines) return std::nullopt;
  const Instruction& in = program_[static_cast<std::size_t>(line)];
  if (in.op != Op::cou && in.op != Op::bac) return std::nullopt;
  const auto it = counters_.find(line);
  CounterView v;
  v.count = it == counters_.end() ? 0 : it->second;
  const Num& preset = in.op == Op::cou ? in.n[1] : in.n[2];
  v.preset =
      preset.is_var() ? static_cast<int>(variable(preset.var) / micro_one) : static_cast<int>(preset.value / micro_one);
  return v;
}

TaskView Controller::task(int t) const {
  if (t < 1 || t > 5) return {};
  const Task& k = tasks_[static_cast<std::size_t>(t - 1)];
  TaskView v;
  v.used = k.used;
  v.active = k.active;
  v.pc = k.pc;
  v.depth = static_cast<int>(k.stack.size());
  v.main_pc = k.stack.empty() ? k.pc : k.stack.front();
  return v;
}

double Controller::position(int axis) const {
  return axis >= 1 && axis <= 4 ? clm_position(axis) : 0.0;
}
double Controller::following_error(int axis) const {
  return axis >= 1 && axis <= 4 ? axes_[static_cast<std::size_t>(axis - 1)].fb.following_error : 0.0;
}
double Controller::velocity(int axis) const {
  return axis >= 1 && axis <= 4 ? axes_[static_cast<std::size_t>(axis - 1)].fb.velocity : 0.0;
}
bool Controller::homed(int axis) const {
  if (axis < 1 || axis > 4) return false;
  return axes_[static_cast<std::size_t>(axis - 1)].homed ||
         settings_.axes[static_cast<std::size_t>(axis - 1)].absolute_encoder();
}
double Controller::latched_position(int axis) const {
  return axis >= 1 && axis <= 4 ? axes_[static_cast<std::size_t>(axis - 1)].latched : 0.0;
}

}  // namespace hil::controllers::clm14
